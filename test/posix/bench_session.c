/* Benchmark (not a test): what recording costs through the session, for a
 * latency budget. Prints one JSON object: samples, CPU seconds of the reading
 * thread (getrusage RUSAGE_THREAD on Linux, else the process), CPU share of
 * one core, microseconds per sample, and context switches (wake-ups) per
 * sample. Syscalls per sample: run it on a port served by another process
 * under `strace -c -f` (docs/session.md).
 *
 * usage: bench_session [--latency MS] [--seconds S] [--rate HZ] [PORT]
 *   without PORT an in-process virtual sensor serves it (its own thread's CPU
 *   is not counted where RUSAGE_THREAD exists). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _GNU_SOURCE
#endif

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "leptrino/error.h"
#include "leptrino/serial.h"
#include "leptrino/session.h"
#include "struct_api.h"

#define CAP 4096u

static double tv(struct timeval t)
{
    return (double)t.tv_sec + (double)t.tv_usec / 1e6;
}

static int usage_now(struct rusage *ru)
{
#if defined(RUSAGE_THREAD)
    return getrusage(RUSAGE_THREAD, ru);
#else
    return getrusage(RUSAGE_SELF, ru);
#endif
}

int main(int argc, char **argv)
{
    static double t[CAP];
    static double si[CAP * LEP_AXES];
    static int16_t raw[CAP * LEP_AXES];
    static uint8_t status[CAP];
    lep_session_options o;
    lep_session *s;
    lep_session_batch b;
    lep_session_health_info h;
    struct rusage r0, r1;
    char err[256];
    double seconds = 10.0, t0, cpu;
    uint64_t samples = 0;
    long sw;
    int i, rc;

    lep_session_options_init(&o);
    o.use_sim = true;
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--latency") == 0 && i + 1 < argc)
            o.latency_ms = atoi(argv[++i]);
        else if (strcmp(argv[i], "--seconds") == 0 && i + 1 < argc)
            seconds = atof(argv[++i]);
        else if (strcmp(argv[i], "--rate") == 0 && i + 1 < argc)
            o.sim.rate_hz = atof(argv[++i]); /* the in-process virtual sensor's rate */
        else if (argv[i][0] != '-') {
            o.port = argv[i];
            o.use_sim = false;
        } else {
            fprintf(stderr,
                    "usage: bench_session [--latency MS] [--seconds S] [--rate HZ] [PORT]\n");
            return 2;
        }
    }
    rc = lep_session_open_so(&o, &s, err, sizeof err);
    if (rc != LEP_OK) {
        fprintf(stderr, "bench_session: %s\n", err);
        return 1;
    }
    memset(&b, 0, sizeof b);
    b.cap = CAP;
    b.t_mono = t;
    b.si = si;
    b.raw = raw;
    b.status = status;
    if (lep_session_start(s) != LEP_OK) {
        fprintf(stderr, "bench_session: start failed\n");
        lep_session_close(s);
        return 1;
    }
    usage_now(&r0);
    t0 = lep_monotonic_seconds();
    while (lep_monotonic_seconds() - t0 < seconds) {
        b.n = 0;
        rc = lep_session_read_batch(s, &b, 1000);
        samples += b.n;
        if (rc != LEP_OK && rc != LEP_E_TIMEOUT)
            break;
    }
    usage_now(&r1);
    lep_session_get_health(s, &h);
    lep_session_close(s);
    cpu = tv(r1.ru_utime) - tv(r0.ru_utime) + tv(r1.ru_stime) - tv(r0.ru_stime);
    sw = (r1.ru_nvcsw - r0.ru_nvcsw) + (r1.ru_nivcsw - r0.ru_nivcsw);
    printf("{\"rate_hz\":%g,\"latency_ms\":%d,\"seconds\":%.3f,\"samples\":%llu,\"lost\":%llu,"
           "\"cpu_s\":%.4f,"
           "\"cpu_percent\":%.3f,\"us_per_sample\":%.3f,\"switches_per_sample\":%.4f}\n",
           h.nominal_hz, o.latency_ms, seconds, (unsigned long long)samples,
           (unsigned long long)h.lost, cpu, 100.0 * cpu / seconds,
           samples > 0 ? 1e6 * cpu / (double)samples : 0.0,
           samples > 0 ? (double)sw / (double)samples : 0.0);
    return 0;
}
