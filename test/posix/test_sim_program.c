/* The leptrino-sim program: first line, client session, signals, bad arguments. */
#define _DEFAULT_SOURCE

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "leptrino/leptrino.h"
#include "leptrino/serial.h"
#include "leptrino/sim.h"
#include "struct_api.h"
#include "unity.h"

#ifndef LEP_SIM_EXE
#error "LEP_SIM_EXE must name the leptrino-sim executable"
#endif

static pid_t child = -1;
static lep_serial *port;
static lep_client client;
static char err[256];

void setUp(void)
{
    child = -1;
    port = NULL;
}

void tearDown(void)
{
    lep_serial_close(port);
    if (child > 0) {
        kill(child, SIGKILL);
        waitpid(child, NULL, 0);
    }
}

static void sleep_ms(long ms)
{
    struct timespec ts;
    ts.tv_sec = ms / 1000;
    ts.tv_nsec = (ms % 1000) * 1000000L;
    nanosleep(&ts, NULL);
}

/* Start leptrino-sim with args; read its first stdout line into line.
 * stderr goes to errfd when >= 0. */
static void spawn(const char *const *args, char *line, size_t cap, int *out_fd, int *err_fd)
{
    int out[2], er[2];
    const char *argv[32];
    size_t i, n = 0;
    argv[n++] = LEP_SIM_EXE;
    for (i = 0; args[i] != NULL && n < 31; i++)
        argv[n++] = args[i];
    argv[n] = NULL;
    TEST_ASSERT_EQUAL_INT(0, pipe(out));
    TEST_ASSERT_EQUAL_INT(0, pipe(er));
    child = fork();
    TEST_ASSERT_TRUE(child >= 0);
    if (child == 0) {
        dup2(out[1], 1);
        dup2(er[1], 2);
        close(out[0]);
        close(out[1]);
        close(er[0]);
        close(er[1]);
        execv(LEP_SIM_EXE, (char *const *)argv);
        _exit(127);
    }
    close(out[1]);
    close(er[1]);
    {
        size_t len = 0;
        line[0] = '\0';
        while (len + 1 < cap && strchr(line, '\n') == NULL) {
            ssize_t r = read(out[0], line + len, cap - 1 - len);
            if (r <= 0)
                break;
            len += (size_t)r;
            line[len] = '\0';
        }
        if (strchr(line, '\n') != NULL)
            *strchr(line, '\n') = '\0';
    }
    *out_fd = out[0];
    *err_fd = er[0];
}

static int wait_exit(int timeout_ms)
{
    int status, i;
    for (i = 0; i < timeout_ms / 10; i++) {
        pid_t r = waitpid(child, &status, WNOHANG);
        if (r == child) {
            child = -1;
            return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        }
        sleep_ms(10);
    }
    return -1;
}

static void test_session_and_clean_exit(void)
{
    char link[64], line[256];
    lep_product_info info;
    lep_rated rated;
    uint8_t code = 9;
    lep_sample smp;
    int ofd, efd, i;
    snprintf(link, sizeof link, "/tmp/lep-simexe-%ld", (long)getpid());
    {
        const char *args[] = { "--model", "CFS034CA301U",        "--serial", "424242", "--link",
                               link,      "--output-rate-field", "--rate",   "500",    NULL };
        spawn(args, line, sizeof line, &ofd, &efd);
    }
    TEST_ASSERT_EQUAL_STRING(link, line);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_serial_open(line, &port, err, sizeof err), err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_serial_client_init(&client, port));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 30, &info));
    TEST_ASSERT_EQUAL_STRING("CFS034CA301U", info.model);
    TEST_ASSERT_EQUAL_STRING("424242", info.serial);
    TEST_ASSERT_EQUAL_UINT32(500, info.output_rate_hz);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_FLOAT(300.0f, rated.axis[LEP_FZ]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    for (i = 0; i < 100; i++) { /* (5 s: a failure bound, a sample is due every 2 ms) */
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, 5000));
        TEST_ASSERT_EQUAL_UINT16(i, smp.reserved);
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));

    /* SIGUSR1 is the power switch: the filter set takes effect */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_set(&client, 2));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_get(&client, &code));
    TEST_ASSERT_EQUAL_UINT8(0, code);
    kill(child, SIGUSR1);
    for (i = 0; i < 100 && code != 2; i++) {
        sleep_ms(10);
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_get(&client, &code));
    }
    TEST_ASSERT_EQUAL_UINT8(2, code);

    lep_serial_close(port);
    port = NULL;
    kill(child, SIGTERM);
    TEST_ASSERT_EQUAL_INT(0, wait_exit(3000));
    TEST_ASSERT_NOT_EQUAL(0, access(link, F_OK)); /* link removed */
    close(ofd);
    close(efd);
}

/* The link of a running leptrino-sim is refused (nothing changed); after it
 * is killed (SIGKILL: no clean-up), its stale link and lock are taken over. */
static void test_link_ownership_across_processes(void)
{
    char link[64], lock[80], line[256], target[256];
    lep_sim_options o;
    lep_sim *sim = NULL;
    int ofd, efd;
    ssize_t n;
    snprintf(link, sizeof link, "/tmp/lep-simown-%ld", (long)getpid());
    snprintf(lock, sizeof lock, "%s.lock", link);
    {
        const char *args[] = { "--link", link, NULL };
        spawn(args, line, sizeof line, &ofd, &efd);
    }
    TEST_ASSERT_EQUAL_STRING(link, line);
    n = readlink(link, target, sizeof target - 1);
    TEST_ASSERT_TRUE(n > 0);
    target[n] = '\0';
    lep_sim_options_init(&o);
    snprintf(o.link, sizeof o.link, "%s", link);
    TEST_ASSERT_EQUAL_INT(LEP_E_BUSY, lep_sim_start_so(&o, &sim, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "running virtual sensor"), err);
    {
        char pid[32], now[256];
        snprintf(pid, sizeof pid, "pid %ld", (long)child);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, pid), err);
        n = readlink(link, now, sizeof now - 1);
        TEST_ASSERT_TRUE(n > 0);
        now[n] = '\0';
        TEST_ASSERT_EQUAL_STRING(target, now); /* untouched */
    }
    kill(child, SIGKILL);
    TEST_ASSERT_EQUAL_INT(128 + SIGKILL, wait_exit(3000));
    close(ofd);
    close(efd);
    TEST_ASSERT_EQUAL_INT(0, access(lock, F_OK)); /* left behind, unlocked */
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_start_so(&o, &sim, err, sizeof err), err);
    TEST_ASSERT_EQUAL_STRING(link, lep_sim_port(sim));
    lep_sim_stop(sim);
    TEST_ASSERT_NOT_EQUAL(0, access(link, F_OK));
    TEST_ASSERT_NOT_EQUAL(0, access(lock, F_OK));
}

static void test_sigint_exits_zero(void)
{
    char line[256];
    int ofd, efd;
    const char *args[] = { "--start-streaming", NULL };
    spawn(args, line, sizeof line, &ofd, &efd);
    TEST_ASSERT_EQUAL_INT(0, strncmp(line, "/dev/", 5));
    kill(child, SIGINT);
    TEST_ASSERT_EQUAL_INT(0, wait_exit(3000));
    close(ofd);
    close(efd);
}

static void expect_usage_error(const char *const *args, const char *needle)
{
    char line[256], msg[512];
    int ofd, efd;
    ssize_t n;
    spawn(args, line, sizeof line, &ofd, &efd);
    TEST_ASSERT_EQUAL_STRING("", line); /* nothing on stdout */
    TEST_ASSERT_EQUAL_INT(2, wait_exit(3000));
    n = read(efd, msg, sizeof msg - 1);
    TEST_ASSERT_TRUE(n > 0);
    msg[n] = '\0';
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, needle), msg);
    TEST_ASSERT_EQUAL_PTR_MESSAGE(msg + n - 1, strchr(msg, '\n'), "one line only");
    close(ofd);
    close(efd);
}

/* A link path that is not ours to replace: exit 1, one line, nothing changed. */
static void expect_link_error(const char *const *args, const char *needle)
{
    char line[256], msg[512];
    int ofd, efd;
    ssize_t n;
    spawn(args, line, sizeof line, &ofd, &efd);
    TEST_ASSERT_EQUAL_STRING("", line);
    TEST_ASSERT_EQUAL_INT(1, wait_exit(3000));
    n = read(efd, msg, sizeof msg - 1);
    TEST_ASSERT_TRUE(n > 0);
    msg[n] = '\0';
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, needle), msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "nothing was changed"), msg);
    close(ofd);
    close(efd);
}

static void test_bad_arguments(void)
{
    const char *a1[] = { "--model", "NOPE", NULL };
    const char *a2[] = { "--rate", "fast", NULL };
    const char *a3[] = { "--bogus", NULL };
    const char *a4[] = { "--nak", "2", NULL };
    const char *a5[] = { "--reopen-after", "100", NULL };
    const char *a6[] = { "--filter", NULL };
    const char *a7[] = { "--serial", "12ab", NULL };
    const char *a8[] = { "--hangup-after", "inf", NULL };
    char recording[64];
    const char *a9[] = { "--link", recording, NULL };
    FILE *f;
    expect_usage_error(a1, "NOPE");
    expect_usage_error(a2, "fast");
    expect_usage_error(a3, "--bogus");
    expect_usage_error(a4, "--nak");
    expect_usage_error(a5, "needs link");
    expect_usage_error(a6, "--filter");
    expect_usage_error(a7, "12ab");
    expect_usage_error(a8, "0 to 1000000");
    snprintf(recording, sizeof recording, "/tmp/lep-simexe-rec-%ld.csv", (long)getpid());
    f = fopen(recording, "w");
    TEST_ASSERT_NOT_NULL(f);
    fputs("t_s,fx_N\n", f);
    fclose(f);
    expect_link_error(a9, "regular file");
    {
        struct stat st;
        TEST_ASSERT_EQUAL_INT(0, stat(recording, &st));
        TEST_ASSERT_EQUAL_INT(9, (int)st.st_size); /* the recording survived */
    }
    (void)unlink(recording);
}

static void test_help_version_models(void)
{
    char line[256];
    int ofd, efd;
    const char *h[] = { "--help", NULL };
    const char *v[] = { "--version", NULL };
    const char *m[] = { "--list-models", NULL };
    spawn(h, line, sizeof line, &ofd, &efd);
    TEST_ASSERT_NOT_NULL(strstr(line, "usage: leptrino-sim"));
    TEST_ASSERT_EQUAL_INT(0, wait_exit(3000));
    close(ofd);
    close(efd);
    spawn(v, line, sizeof line, &ofd, &efd);
    TEST_ASSERT_NOT_NULL(strstr(line, lep_version()));
    TEST_ASSERT_EQUAL_INT(0, wait_exit(3000));
    close(ofd);
    close(efd);
    spawn(m, line, sizeof line, &ofd, &efd);
    TEST_ASSERT_NOT_NULL(strstr(line, "model"));
    TEST_ASSERT_EQUAL_INT(0, wait_exit(3000));
    close(ofd);
    close(efd);
}

int main(void)
{
    signal(SIGPIPE, SIG_IGN);
    UNITY_BEGIN();
    RUN_TEST(test_session_and_clean_exit);
    RUN_TEST(test_link_ownership_across_processes);
    RUN_TEST(test_sigint_exits_zero);
    RUN_TEST(test_bad_arguments);
    RUN_TEST(test_help_version_models);
    return UNITY_END();
}
