/* POSIX serial backend: open errors, raw I/O, timeouts, disconnect, discovery. */
#define _GNU_SOURCE

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#include "leptrino/leptrino.h"
#include "leptrino/serial.h"
#include "struct_api.h"
#include "host/serial/serial_list.h"
#include "unity.h"

static lep_serial *port;
static int master = -1;
static char err[256];
static char slave_path[128];

void setUp(void)
{
    port = NULL;
    master = -1;
    err[0] = '\0';
}

void tearDown(void)
{
    lep_serial_close(port);
    if (master >= 0)
        close(master);
}

/* A bare pty pair: the test plays the sensor on the master side. */
static void make_pty(void)
{
    master = posix_openpt(O_RDWR | O_NOCTTY);
    TEST_ASSERT_TRUE(master >= 0);
    TEST_ASSERT_EQUAL_INT(0, grantpt(master));
    TEST_ASSERT_EQUAL_INT(0, unlockpt(master));
    TEST_ASSERT_EQUAL_INT(0, ptsname_r(master, slave_path, sizeof slave_path));
}

static void open_port(const char *path)
{
    int rc = lep_serial_open(path, &port, err, sizeof err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, rc, err);
}

static void test_missing_path(void)
{
    TEST_ASSERT_EQUAL_INT(LEP_E_NOT_FOUND,
                          lep_serial_open("/dev/ttyNOPE-leptrino", &port, err, sizeof err));
    TEST_ASSERT_NULL(port);
    TEST_ASSERT_NOT_NULL(strstr(err, "/dev/ttyNOPE-leptrino"));
    TEST_ASSERT_NOT_NULL(strstr(err, "no such port"));
}

static void test_not_a_tty(void)
{
    char file[64];
    int fd;
    TEST_ASSERT_EQUAL_INT(LEP_E_NOT_TTY, lep_serial_open("/dev/null", &port, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "/dev/null"));
    TEST_ASSERT_NOT_NULL(strstr(err, "not a terminal"));
    snprintf(file, sizeof file, "/tmp/lep-notatty-%ld", (long)getpid());
    fd = open(file, O_CREAT | O_WRONLY | O_TRUNC, 0600);
    TEST_ASSERT_TRUE(fd >= 0);
    close(fd);
    TEST_ASSERT_EQUAL_INT(LEP_E_NOT_TTY, lep_serial_open(file, &port, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, file));
    TEST_ASSERT_NOT_NULL(strstr(err, "regular file"));
    unlink(file);
    TEST_ASSERT_EQUAL_INT(LEP_E_NOT_TTY, lep_serial_open("/tmp", &port, err, sizeof err));
    TEST_ASSERT_NULL(port);
}

static void test_permission(void)
{
    char file[64];
    int fd;
    if (geteuid() == 0) {
        TEST_IGNORE_MESSAGE("running as root: permission checks never refuse root, so "
                            "LEP_E_PERMISSION cannot be provoked here");
    }
    snprintf(file, sizeof file, "/tmp/lep-noperm-%ld", (long)getpid());
    fd = open(file, O_CREAT | O_WRONLY | O_TRUNC, 0000);
    TEST_ASSERT_TRUE(fd >= 0);
    close(fd);
    TEST_ASSERT_EQUAL_INT(LEP_E_PERMISSION, lep_serial_open(file, &port, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, file));
    unlink(file);
}

static void test_bad_args(void)
{
    lep_serial_info info;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_serial_open(NULL, &port, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_serial_open("", &port, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_serial_open("/dev/null", NULL, NULL, 0));
    lep_serial_close(NULL);
    lep_serial_get_latency_info(NULL, &info);
    TEST_ASSERT_EQUAL_INT(-1, info.ftdi_latency_ms);
    TEST_ASSERT_EQUAL_INT(-1, lep_serial_fd(NULL));
}

static void test_busy(void)
{
    lep_serial *second = NULL;
    make_pty();
    open_port(slave_path);
    TEST_ASSERT_EQUAL_INT(LEP_E_BUSY, lep_serial_open(slave_path, &second, err, sizeof err));
    TEST_ASSERT_NULL(second);
    TEST_ASSERT_NOT_NULL(strstr(err, slave_path));
    TEST_ASSERT_NOT_NULL(strstr(err, "in use by another program"));
}

/* Every byte value passes unchanged both ways (raw mode, no translation). */
static void test_raw_bytes_both_ways(void)
{
    uint8_t all[256], got[256];
    size_t have = 0;
    lep_io io;
    lep_serial_info info;
    int i;
    make_pty();
    open_port(slave_path);
    TEST_ASSERT_EQUAL_STRING(slave_path, lep_serial_path(port));
    TEST_ASSERT_TRUE(lep_serial_fd(port) >= 0);
    lep_serial_get_latency_info(port, &info);
    TEST_ASSERT_FALSE(info.low_latency); /* a pty has no such flag */
    TEST_ASSERT_EQUAL_INT(-1, info.ftdi_latency_ms);
    for (i = 0; i < 256; i++)
        all[i] = (uint8_t)i;
    lep_serial_get_io(port, &io);
    TEST_ASSERT_EQUAL_INT(256, (int)write(master, all, sizeof all));
    while (have < sizeof got) {
        int n = io.read(io.user, got + have, sizeof got - have, 1000);
        TEST_ASSERT_TRUE(n > 0);
        have += (size_t)n;
    }
    TEST_ASSERT_EQUAL_MEMORY(all, got, sizeof all);

    TEST_ASSERT_EQUAL_INT(LEP_OK, io.write(io.user, all, sizeof all));
    have = 0;
    while (have < sizeof got) {
        ssize_t n = read(master, got + have, sizeof got - have);
        TEST_ASSERT_TRUE(n > 0);
        have += (size_t)n;
    }
    TEST_ASSERT_EQUAL_MEMORY(all, got, sizeof all);
}

/* One read returns everything available, not a byte at a time. */
static void test_read_takes_what_is_there(void)
{
    uint8_t data[200], got[1024];
    lep_io io;
    struct timespec ts = { 0, 20000000 };
    memset(data, 0xA5, sizeof data);
    make_pty();
    open_port(slave_path);
    lep_serial_get_io(port, &io);
    TEST_ASSERT_EQUAL_INT(200, (int)write(master, data, sizeof data));
    nanosleep(&ts, NULL);
    TEST_ASSERT_EQUAL_INT(200, io.read(io.user, got, sizeof got, 100));
    TEST_ASSERT_EQUAL_INT(0, io.read(io.user, got, sizeof got, 0));
}

static void test_timeout_precision(void)
{
    uint8_t buf[16];
    lep_io io;
    int ms[3] = { 1, 50, 300 };
    int i;
    make_pty();
    open_port(slave_path);
    lep_serial_get_io(port, &io);
    for (i = 0; i < 3; i++) {
        double t = lep_monotonic_seconds(), dt;
        char msg[80];
        TEST_ASSERT_EQUAL_INT(0, io.read(io.user, buf, sizeof buf, ms[i]));
        dt = lep_monotonic_seconds() - t;
        snprintf(msg, sizeof msg, "timeout %d ms took %.3f ms", ms[i], dt * 1e3);
        /* never early; late only by the scheduler (a loaded machine, valgrind):
         * the bound catches a timeout taken as seconds or ignored, not jitter */
        TEST_ASSERT_TRUE_MESSAGE(dt >= ms[i] / 1e3 && dt < ms[i] / 1e3 + 5.0, msg);
    }
}

static void test_disconnect(void)
{
    uint8_t buf[16];
    lep_io io;
    double t;
    make_pty();
    open_port(slave_path);
    lep_serial_get_io(port, &io);
    close(master); /* the cable is pulled */
    master = -1;
    /* at once, not at the end of the read's 60 s timeout (half of it bounds a
     * loaded machine's delay with room to spare) */
    t = lep_monotonic_seconds();
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, io.read(io.user, buf, sizeof buf, 60000));
    TEST_ASSERT_TRUE(lep_monotonic_seconds() - t < 30.0);
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, io.read(io.user, buf, sizeof buf, 60000));
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, io.write(io.user, buf, 4));
}

static void test_disconnect_while_waiting(void)
{
    /* the sensor vanishes during a read that is already waiting */
    uint8_t buf[16];
    lep_io io;
    pid_t pid;
    double t;
    make_pty();
    open_port(slave_path);
    lep_serial_get_io(port, &io);
    pid = fork();
    TEST_ASSERT_TRUE(pid >= 0);
    if (pid == 0) {
        struct timespec ts = { 0, 100000000 };
        nanosleep(&ts, NULL);
        _exit(0);
    }
    close(master); /* the child holds the last master reference */
    master = -1;
    t = lep_monotonic_seconds();
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, io.read(io.user, buf, sizeof buf, 3000));
    t = lep_monotonic_seconds() - t;
    TEST_ASSERT_TRUE(t >= 0.05 && t < 1.5);
}

static void on_alarm(int sig)
{
    (void)sig;
}

/* A read of 300 ms on a silent port while a 20 ms interval timer's handler
 * runs: it returns 0 after its timeout, neither failing at the first signal
 * nor running on. flags: the handler's sa_flags. With SA_RESTART the kernel
 * restarts a restartable call with its own timer reset (a blocking read()
 * with VTIME would then never time out); poll() is never restarted, and the
 * port recomputes the time left after each EINTR. The upper bound only tells
 * a hang from a return: it is ten times the timeout. */
static void read_under_timer_signals(int flags)
{
    uint8_t buf[16];
    lep_io io;
    struct sigaction sa;
    struct itimerval it, off;
    double t;
    make_pty();
    open_port(slave_path);
    lep_serial_get_io(port, &io);
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_alarm;
    sa.sa_flags = flags;
    TEST_ASSERT_EQUAL_INT(0, sigaction(SIGALRM, &sa, NULL));
    memset(&it, 0, sizeof it);
    memset(&off, 0, sizeof off);
    it.it_value.tv_usec = 20000;
    it.it_interval.tv_usec = 20000;
    TEST_ASSERT_EQUAL_INT(0, setitimer(ITIMER_REAL, &it, NULL));
    t = lep_monotonic_seconds();
    TEST_ASSERT_EQUAL_INT(0, io.read(io.user, buf, sizeof buf, 300));
    t = lep_monotonic_seconds() - t;
    (void)setitimer(ITIMER_REAL, &off, NULL);
    /* a tick generated before the timer stopped may still be delivered
     * (valgrind delivers signals late): ignore it rather than let the
     * default action end the test */
    sa.sa_handler = SIG_IGN;
    (void)sigaction(SIGALRM, &sa, NULL);
    TEST_ASSERT_TRUE(t >= 0.3);
    TEST_ASSERT_TRUE(t < 3.0);
    /* and bytes sent now are read at once */
    TEST_ASSERT_EQUAL_INT(3, (int)write(master, "abc", 3));
    TEST_ASSERT_EQUAL_INT(3, io.read(io.user, buf, sizeof buf, 2000));
    TEST_ASSERT_EQUAL_MEMORY("abc", buf, 3);
}

static void test_signals_during_read(void)
{
    read_under_timer_signals(0);
}

static void test_restarting_signals_during_read(void)
{
    read_under_timer_signals(SA_RESTART);
}

/* A write to a port that takes nothing (nobody reads the master) times out
 * after its 2 s instead of blocking, and the port reads normally afterwards. */
static void test_write_stall_times_out(void)
{
    static uint8_t big[256 * 1024];
    uint8_t buf[16];
    lep_io io;
    make_pty();
    open_port(slave_path);
    lep_serial_get_io(port, &io);
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, io.write(io.user, big, sizeof big));
    TEST_ASSERT_EQUAL_INT(2, (int)write(master, "xy", 2));
    TEST_ASSERT_EQUAL_INT(2, io.read(io.user, buf, sizeof buf, 1000));
    TEST_ASSERT_EQUAL_MEMORY("xy", buf, 2);
}

static void test_monotonic(void)
{
    double a = lep_monotonic_seconds();
    uint32_t m = lep_monotonic_ms();
    double b = lep_monotonic_seconds();
    TEST_ASSERT_TRUE(b >= a);
    TEST_ASSERT_TRUE((uint32_t)(a * 1000.0) - 1u <= m + 1u);
}

/* ---- discovery over a fake sysfs/dev tree ---- */

static char root[64];

static void mk(const char *rel)
{
    char p[256];
    snprintf(p, sizeof p, "%s/%s", root, rel);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, mkdir(p, 0755), p);
}

static void put(const char *rel, const char *text)
{
    char p[256];
    FILE *f;
    snprintf(p, sizeof p, "%s/%s", root, rel);
    f = fopen(p, "w");
    TEST_ASSERT_NOT_NULL_MESSAGE(f, p);
    fputs(text, f);
    fclose(f);
}

static void ln(const char *target_rel, const char *rel)
{
    char t[256], p[256];
    snprintf(t, sizeof t, "%s/%s", root, target_rel);
    snprintf(p, sizeof p, "%s/%s", root, rel);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, symlink(t, p), p);
}

static void test_list_fake_tree(void)
{
    lep_port_info ports[8];
    lep_serial_roots roots;
    char sys[128], byid[128], dev[128], want[256];
    size_t n = 99;
    int rc;
    snprintf(root, sizeof root, "/tmp/lep-list-XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(root));
    mk("devices");
    mk("devices/usb1");
    mk("devices/usb1/1-1");
    put("devices/usb1/1-1/idVendor", "0483\n");
    put("devices/usb1/1-1/idProduct", "5740\n");
    put("devices/usb1/1-1/product", "STM32 Virtual ComPort\n");
    put("devices/usb1/1-1/manufacturer", "STMicroelectronics\n");
    mk("devices/usb1/1-1/1-1:1.0");
    mk("devices/usb1/1-2");
    put("devices/usb1/1-2/idVendor", "0403\n");
    put("devices/usb1/1-2/idProduct", "6001\n");
    put("devices/usb1/1-2/product", "FT232R USB UART\n");
    mk("devices/usb1/1-2/1-2:1.0");
    mk("devices/usb1/1-2/1-2:1.0/ttyUSB0");
    mk("devices/platform");
    mk("devices/platform/serial8250");
    mk("devices/pnp0");
    mk("devices/pnp0/00:05");
    mk("bus");
    mk("bus/platform");
    mk("bus/pnp");
    ln("bus/platform", "devices/platform/serial8250/subsystem");
    ln("bus/pnp", "devices/pnp0/00:05/subsystem");
    mk("class");
    mk("class/tty");
    mk("class/tty/ttyACM0");
    ln("devices/usb1/1-1/1-1:1.0", "class/tty/ttyACM0/device");
    mk("class/tty/ttyUSB0");
    ln("devices/usb1/1-2/1-2:1.0/ttyUSB0", "class/tty/ttyUSB0/device");
    mk("class/tty/ttyS0");
    ln("devices/platform/serial8250", "class/tty/ttyS0/device");
    mk("class/tty/ttyS4");
    ln("devices/pnp0/00:05", "class/tty/ttyS4/device");
    mk("class/tty/tty0"); /* a virtual terminal: no device */
    mk("dev");
    put("dev/ttyACM0", "");
    put("dev/ttyUSB0", "");
    put("dev/ttyS4", "");
    mk("dev/serial");
    mk("dev/serial/by-id");
    ln("dev/ttyACM0", "dev/serial/by-id/usb-STMicroelectronics_STM32_Virtual_ComPort-if00");

    snprintf(sys, sizeof sys, "%s/class/tty", root);
    snprintf(byid, sizeof byid, "%s/dev/serial/by-id", root);
    snprintf(dev, sizeof dev, "%s/dev", root);
    roots.sys_class_tty = sys;
    roots.by_id = byid;
    roots.dev = dev;
    rc = lep_priv_serial_list_in(&roots, ports, 8, &n);
    TEST_ASSERT_EQUAL_INT(LEP_OK, rc);
    TEST_ASSERT_EQUAL_size_t(3, n);
    snprintf(want, sizeof want, "%s/ttyACM0", dev);
    TEST_ASSERT_EQUAL_STRING(want, ports[0].path);
    TEST_ASSERT_EQUAL_HEX16(0x0483, ports[0].vid);
    TEST_ASSERT_EQUAL_HEX16(0x5740, ports[0].pid);
    TEST_ASSERT_TRUE(ports[0].likely_sensor);
    TEST_ASSERT_EQUAL_STRING("STMicroelectronics STM32 Virtual ComPort", ports[0].description);
    snprintf(want, sizeof want, "%s/usb-STMicroelectronics_STM32_Virtual_ComPort-if00", byid);
    TEST_ASSERT_EQUAL_STRING(want, ports[0].by_id);
    snprintf(want, sizeof want, "%s/ttyS4", dev);
    TEST_ASSERT_EQUAL_STRING(want, ports[1].path);
    TEST_ASSERT_EQUAL_HEX16(0, ports[1].vid);
    TEST_ASSERT_FALSE(ports[1].likely_sensor);
    TEST_ASSERT_EQUAL_STRING("", ports[1].by_id);
    snprintf(want, sizeof want, "%s/ttyUSB0", dev);
    TEST_ASSERT_EQUAL_STRING(want, ports[2].path);
    TEST_ASSERT_EQUAL_HEX16(0x0403, ports[2].vid);
    TEST_ASSERT_TRUE(ports[2].likely_sensor);
    TEST_ASSERT_EQUAL_STRING("FT232R USB UART", ports[2].description);

    /* a short array: the count still says how many exist */
    rc = lep_priv_serial_list_in(&roots, ports, 1, &n);
    TEST_ASSERT_EQUAL_INT(LEP_OK, rc);
    TEST_ASSERT_EQUAL_size_t(3, n);
    rc = lep_priv_serial_list_in(&roots, NULL, 0, &n);
    TEST_ASSERT_EQUAL_size_t(3, n);
    {
        char cmd[128];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
        TEST_ASSERT_EQUAL_INT(0, system(cmd));
    }
}

static void test_list_this_machine(void)
{
    lep_port_info ports[32];
    size_t n = 0;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_serial_list(ports, 32, &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_serial_list(NULL, 4, &n));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_missing_path);
    RUN_TEST(test_not_a_tty);
    RUN_TEST(test_permission);
    RUN_TEST(test_bad_args);
    RUN_TEST(test_busy);
    RUN_TEST(test_raw_bytes_both_ways);
    RUN_TEST(test_read_takes_what_is_there);
    RUN_TEST(test_timeout_precision);
    RUN_TEST(test_disconnect);
    RUN_TEST(test_disconnect_while_waiting);
    RUN_TEST(test_signals_during_read);
    RUN_TEST(test_restarting_signals_during_read);
    RUN_TEST(test_write_stall_times_out);
    RUN_TEST(test_monotonic);
    RUN_TEST(test_list_fake_tree);
    RUN_TEST(test_list_this_machine);
    return UNITY_END();
}
