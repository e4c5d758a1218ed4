/* leptrino-bench helpers: clocks, medians, running other programs. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#if defined(__linux__)
#include <sys/prctl.h>
#endif

#include "bench.h"

double bench_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a;
    double y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_median(double *v, size_t n)
{
    if (n == 0) {
        return 0.0 / 0.0;
    }
    qsort(v, n, sizeof(*v), cmp_double);
    return n % 2u ? v[n / 2u] : (v[n / 2u - 1u] + v[n / 2u]) / 2.0;
}

double bench_percentile(double *sorted, size_t n, double q)
{
    size_t i;
    if (n == 0) {
        return 0.0 / 0.0;
    }
    i = (size_t)(q * (double)(n - 1u) + 0.5);
    return sorted[i < n ? i : n - 1u];
}

void bench_child_follow_parent(pid_t parent)
{
#if defined(__linux__)
    (void)prctl(PR_SET_PDEATHSIG, SIGTERM);
#endif
    if (getppid() != parent) {
        _exit(127);
    }
}

int bench_run(char *const argv[], const char *out_path)
{
    pid_t parent = getpid();
    pid_t pid = fork();
    int status;
    if (pid < 0) {
        return -1;
    }
    if (pid == 0) {
        bench_child_follow_parent(parent);
        int fd =
            open(out_path != NULL ? out_path : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC, 0600);
        int null = open("/dev/null", O_WRONLY);
        if (fd >= 0) {
            dup2(fd, 1);
        }
        if (null >= 0) {
            dup2(null, 2);
        }
        execvp(argv[0], argv);
        _exit(127);
    }
    if (waitpid(pid, &status, 0) < 0) {
        return -1;
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) == 127) {
        return -1;
    }
    return WEXITSTATUS(status);
}

int bench_have(const char *prog)
{
    const char *path = getenv("PATH");
    char buf[4096];
    while (path != NULL && *path) {
        const char *colon = strchr(path, ':');
        size_t n = colon != NULL ? (size_t)(colon - path) : strlen(path);
        if (n > 0 && n + strlen(prog) + 2u < sizeof(buf)) {
            memcpy(buf, path, n);
            buf[n] = '/';
            strcpy(buf + n + 1, prog);
            if (access(buf, X_OK) == 0) {
                return 1;
            }
        }
        path = colon != NULL ? colon + 1 : NULL;
    }
    return 0;
}
