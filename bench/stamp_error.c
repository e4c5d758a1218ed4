/* leptrino-stamp-error: how far the session's stamps are from the sensor's
 * clock. Prints figures, asserts nothing.
 *
 * A virtual sensor runs in this process on its own thread (lep_sim_start,
 * any "sim-*" option), with its write trace on (lep_sim_trace_writes); a
 * session reads it through its pty as a port (not the in-process shortcut),
 * for --seconds, at --latency. Sample k of the stream (its sequence number,
 * unwrapped) is due on the sensor's clock at t0 + (k+1)/rate, t0 the stream's
 * start record in the trace and rate the sensor's true rate (sim-rate times
 * 1 + sim-ppm 1e-6). The error of a stamp is t_mono - that. Printed: mean,
 * RMS, p99 and max of |error| over the first second of the stream and after
 * it, and the sim's own lateness (its write() call minus the deadline).
 *
 * --busy N starts N busy loops (child processes) beside it for the run.
 *
 * --record-reads FILE writes a read trace (test/vectors/timeline/README.md):
 * what the session's timeline was fed, read by read (its time, how many
 * samples, the port found empty), from a private recorder of the timeline
 * (session_tap.h), with the truth: the stream index k of each sample and
 * the sensor's true rate, times in ns since t0, and the stamp the session
 * gave each read's newest sample. test_timeline replays such traces. */
#define _DEFAULT_SOURCE
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <errno.h>
#include <fcntl.h>
#include <stdbool.h>

#include "host/session/session_tap.h"
#include "leptrino/error.h"
#include "leptrino/options.h"
#include "leptrino/session.h"
#include "leptrino/sim.h"

#define CAP 512u
#define MAX_SAMPLES 2000000u

typedef struct rec24 {
    uint64_t k;
    int64_t t_call_ns;
    int64_t t_return_ns;
} rec24;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void figures(const char *what, const double *e, size_t n)
{
    double *a, sum = 0.0, sq = 0.0;
    size_t i;
    if (n == 0) {
        printf("  %-14s no samples\n", what);
        return;
    }
    a = malloc(n * sizeof *a);
    if (a == NULL)
        return;
    for (i = 0; i < n; i++) {
        sum += e[i];
        sq += e[i] * e[i];
        a[i] = fabs(e[i]);
    }
    qsort(a, n, sizeof *a, cmp_double);
    printf("  %-14s n %7zu  mean %8.1f us  rms %8.1f us  p99 %8.1f us  max %8.1f us\n", what, n,
           sum / (double)n * 1e6, sqrt(sq / (double)n) * 1e6,
           a[(size_t)((double)(n - 1) * 0.99)] * 1e6, a[n - 1] * 1e6);
    free(a);
}

/* ---- the read trace (--record-reads) ---- */

static timeline_fed *fed;
static size_t n_fed, cap_fed;
static bool fed_broken;

static void on_fed(void *user, const timeline_fed *f)
{
    (void)user;
    if (n_fed == cap_fed) {
        size_t cap = cap_fed ? cap_fed * 2u : 65536u;
        timeline_fed *p = realloc(fed, cap * sizeof *p);
        if (p == NULL) {
            fed_broken = true;
            return;
        }
        fed = p;
        cap_fed = cap;
    }
    fed[n_fed++] = *f;
}

static long long ns_since(double t, double t0_s)
{
    return llround((t - t0_s) * 1e9);
}

/* The feeds of the stream that was measured, joined with the samples
 * delivered (in the order fed): k[i] the stream index of sample i, t[i] its
 * stamp. Stops at the first read not wholly delivered. */
/* Create path for the read trace (never an existing file): its descriptor, or -1 said. */
static int create_reads(const char *path)
{
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd < 0)
        fprintf(stderr, "leptrino-stamp-error: %s: %s%s\n", path, strerror(errno),
                errno == EEXIST ? " (an existing file is never replaced)" : "");
    return fd;
}

static int write_reads(int fd, const char *path, int argc, char **argv, double t0_s, double rate,
                       const uint64_t *k, const double *t, size_t n)
{
    size_t f, i = 0, j;
    FILE *out = fdopen(fd, "w");
    if (out == NULL) {
        close(fd);
        return 1;
    }
    fprintf(out, "# leptrino read trace 1: what the session's timeline was fed, with the truth\n"
                 "# (test/vectors/timeline/README.md). Made by:\n#");
    for (j = 0; j < (size_t)argc; j++)
        fprintf(out, " %s", j == 0 ? "leptrino-stamp-error" : argv[j]);
    fprintf(out, "\n# times: ns since t0, the stream's start in the sensor's write trace\n");
    fprintf(out, "rate %.9f\n", rate);
    for (f = 0; f < n_fed; f++) {
        const timeline_fed *e = &fed[f];
        if (e->what == 'i') {
            fprintf(out, "i %.6f %g %d\n", e->nominal * 1e9, e->gap_periods,
                    e->arrival_gaps ? 1 : 0);
        } else if (e->what == 's') {
            fprintf(out, "s\n");
        } else if (e->what == 'e') {
            fprintf(out, "e %lld\n", ns_since(e->t, t0_s));
        } else if (e->what == 'r') {
            bool run = true;
            if (i + e->n > n)
                break; /* not delivered: the end of the run */
            for (j = 1; j < e->n; j++)
                run = run && k[i + j] == k[i + j - 1u] + 1u;
            fprintf(out, "r %lld %zu %llu %lld", ns_since(e->t, t0_s), e->n,
                    (unsigned long long)e->lost, llround((e->t - t[i + e->n - 1u]) * 1e9));
            if (!run) {
                for (j = 0; j < e->n; j++)
                    fprintf(out, " %llu", (unsigned long long)k[i + j]);
            } else if (i == 0 || k[i] != k[i - 1u] + 1u) {
                fprintf(out, " %llu", (unsigned long long)k[i]);
            }
            fprintf(out, "\n");
            i += e->n;
        }
    }
    if (fclose(out) != 0) {
        fprintf(stderr, "leptrino-stamp-error: %s: %s\n", path, strerror(errno));
        return 1;
    }
    printf("  read trace %s: %zu samples of %zu delivered\n", path, i, n);
    return 0;
}

static pid_t busy[16];
static int n_busy;

static void busy_start(int n)
{
    int i;
    for (i = 0; i < n && i < 16; i++) {
        pid_t p = fork();
        if (p == 0) {
            volatile unsigned long x = 0;
            for (;;)
                x++;
        }
        if (p > 0)
            busy[n_busy++] = p;
    }
}

static void busy_stop(void)
{
    int i;
    for (i = 0; i < n_busy; i++) {
        kill(busy[i], SIGKILL);
        waitpid(busy[i], NULL, 0);
    }
    n_busy = 0;
}

static void usage_to(FILE *to)
{
    fprintf(to, "usage: leptrino-stamp-error [--seconds S] [--latency MS] [--busy N] "
                "[--label TEXT] [--record-reads FILE] [--sim-NAME VALUE ...]\n");
}

static int usage(void)
{
    usage_to(stderr);
    return 2;
}

static int help(void)
{
    usage_to(stdout);
    printf("Streams from an in-process virtual sensor through a session for S seconds (default\n"
           "10) and compares each sample's stamp with the sensor's own clock (its write trace:\n"
           "sample k is due at t0 + (k+1)/rate): mean, RMS, p99 and max of the error over the\n"
           "first second and after it, what went missing and the session's gaps.\n"
           "  --seconds S    how long to stream (default 10)\n"
           "  --latency MS   the session's latency budget (default 0)\n"
           "  --busy N       N busy loops beside it (child processes)\n"
           "  --label TEXT   a label for the printed line\n"
           "  --record-reads FILE  write what the session's timeline was fed, read by read,\n"
           "                 with the truth (a read trace; FILE must not exist)\n"
           "  --sim-NAME V   any option of the virtual sensor (leptrino help sim)\n");
    return 0;
}

int main(int argc, char **argv)
{
    double seconds = 10.0, rate, ppm = 0.0;
    int latency = 0, nb = 0, i, rc, record_fd = -1;
    const char *label = "", *record = NULL;
    timeline_tap tap = { on_fed, NULL };
    uint64_t *karr;
    char err[256], trace[64], port[256];
    lep_options *o;
    lep_sim *sim = NULL;
    lep_session *s = NULL;
    double *t, *e0, *e1, *lateness, t_start = 0.0;
    uint16_t *seq;
    size_t n = 0, n0 = 0, n1 = 0, nl = 0, k;
    int64_t t0 = 0, *write_ns;
    uint64_t kmax = 0, unwrapped = 0;
    FILE *f;
    rec24 r;
    double health[LEP_H_COUNT] = { 0 };
    uint64_t simst[LEP_SIMST_COUNT] = { 0 }, missing = 0;

    for (i = 1; i < argc; i++) /* before anything is allocated */
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0)
            return help();
    o = lep_options_new();
    t = malloc(MAX_SAMPLES * sizeof *t);
    seq = malloc(MAX_SAMPLES * sizeof *seq);
    if (o == NULL || t == NULL || seq == NULL)
        return 1;
    for (i = 1; i < argc; i++) {
        if (i + 1 >= argc)
            return usage();
        if (strcmp(argv[i], "--seconds") == 0)
            seconds = atof(argv[++i]);
        else if (strcmp(argv[i], "--latency") == 0)
            latency = atoi(argv[++i]);
        else if (strcmp(argv[i], "--busy") == 0)
            nb = atoi(argv[++i]);
        else if (strcmp(argv[i], "--label") == 0)
            label = argv[++i];
        else if (strcmp(argv[i], "--record-reads") == 0)
            record = argv[++i];
        else if (strncmp(argv[i], "--sim-", 6) == 0) {
            if (lep_options_set(o, argv[i] + 2, argv[i + 1], err, sizeof err) != LEP_OK) {
                fprintf(stderr, "leptrino-stamp-error: %s\n", err);
                return 2;
            }
            i++;
        } else
            return usage();
    }
    if (record != NULL && (record_fd = create_reads(record)) < 0) {
        free(t);
        free(seq);
        lep_options_free(o);
        return 1;
    }
    (void)lep_options_get_double(o, "sim-rate", &rate);
    if (lep_option_index("sim-ppm") >= 0)
        (void)lep_options_get_double(o, "sim-ppm", &ppm);
    rate *= 1.0 + ppm * 1e-6;

    if (lep_sim_start(o, &sim, err, sizeof err) != LEP_OK) {
        fprintf(stderr, "leptrino-stamp-error: sim: %s\n", err);
        return 1;
    }
    snprintf(trace, sizeof trace, "/tmp/lep-stamp-error-%ld.trace", (long)getpid());
    (void)remove(trace);
    if (lep_sim_trace_writes(sim, trace, err, sizeof err) != LEP_OK) {
        fprintf(stderr, "leptrino-stamp-error: trace: %s\n", err);
        return 1;
    }
    snprintf(port, sizeof port, "%s", lep_sim_port(sim));
    lep_options_set(o, "port", port, err, sizeof err);
    lep_options_set_int(o, "latency", latency, err, sizeof err);
    busy_start(nb);
    rc = lep_session_open(o, &s, err, sizeof err);
    if (rc == LEP_OK && record != NULL)
        lep_priv_session_tap_timeline(s, &tap); /* from the stream's start */
    if (rc == LEP_OK)
        rc = lep_session_start(s);
    if (rc != LEP_OK) {
        fprintf(stderr, "leptrino-stamp-error: session: %s %s\n", lep_strerror(rc), err);
        busy_stop();
        return 1;
    }
    while (n < MAX_SAMPLES) {
        size_t got = 0;
        size_t cap = MAX_SAMPLES - n < CAP ? MAX_SAMPLES - n : CAP;
        rc = lep_session_read(s, 1000, cap, &got, t + n, NULL, NULL, NULL, NULL, NULL, NULL,
                              seq + n);
        if (n == 0 && got > 0)
            t_start = t[0];
        n += got;
        if (rc != LEP_OK && rc != LEP_E_TIMEOUT)
            break;
        if (n > 0 && t[n - 1] - t_start >= seconds)
            break;
    }
    (void)lep_session_health(s, health, LEP_H_COUNT);
    lep_session_stop(s);
    lep_session_close(s);
    busy_stop();
    (void)lep_sim_stats(sim, simst, LEP_SIMST_COUNT);
    lep_sim_stop(sim);

    /* the trace: the last stream start before the data, the write of each k */
    f = fopen(trace, "rb");
    if (f == NULL)
        return 1;
    write_ns = calloc(MAX_SAMPLES + 1, sizeof *write_ns);
    while (fread(&r, sizeof r, 1, f) == 1) {
        if (r.k == UINT64_MAX) {
            t0 = r.t_call_ns;
            memset(write_ns, 0, (MAX_SAMPLES + 1) * sizeof *write_ns);
        } else if (r.k < MAX_SAMPLES)
            write_ns[r.k] = r.t_call_ns;
    }
    fclose(f);
    remove(trace);

    e0 = malloc(n * sizeof *e0 + 1);
    e1 = malloc(n * sizeof *e1 + 1);
    lateness = malloc(n * sizeof *lateness + 1);
    karr = malloc(n * sizeof *karr + 1);
    if (e0 == NULL || e1 == NULL || lateness == NULL || karr == NULL)
        return 1;
    for (k = 0; k < n; k++) {
        double due, err_s;
        if (k == 0)
            unwrapped = seq[0];
        else {
            uint16_t d = (uint16_t)(seq[k] - seq[k - 1]);
            unwrapped += d;
            missing += d > 0 ? d - 1u : 0u;
        }
        karr[k] = unwrapped;
        due = (double)t0 * 1e-9 + (double)(unwrapped + 1u) / rate;
        err_s = t[k] - due;
        if (due - (double)t0 * 1e-9 < 1.0)
            e0[n0++] = err_s;
        else
            e1[n1++] = err_s;
        if (unwrapped < MAX_SAMPLES && write_ns[unwrapped] != 0)
            lateness[nl++] = (double)write_ns[unwrapped] * 1e-9 - due;
        kmax = unwrapped;
    }
    printf("%s latency %d ms, %d busy loops, %.0f Hz (sim-ppm %g), %zu samples, last k %llu\n",
           label, latency, nb, rate, ppm, n, (unsigned long long)kmax);
    /* what went missing (the sequence numbers), what the sim says it did not
     * send, what the session called lost: an undetected hole shows as stamps
     * early by the hole's length from there on */
    printf("  missing by sequence %llu; sim skipped %llu, blocked %llu; session gaps %.0f, "
           "lost %.0f\n",
           (unsigned long long)missing, (unsigned long long)simst[LEP_SIMST_SAMPLES_SKIPPED],
           (unsigned long long)simst[LEP_SIMST_SAMPLES_BLOCKED], health[LEP_H_GAPS],
           health[LEP_H_LOST]);
    figures("first second", e0, n0);
    figures("after it", e1, n1);
    figures("sim lateness", lateness, nl);
    if (record != NULL) {
        if (fed_broken) {
            fprintf(stderr, "leptrino-stamp-error: out of memory for the read trace\n");
            return 1;
        }
        if (write_reads(record_fd, record, argc, argv, (double)t0 * 1e-9, rate, karr, t, n) != 0)
            return 1;
    }
    free(karr);
    free(fed);
    free(e0);
    free(e1);
    free(lateness);
    free(write_ns);
    free(t);
    free(seq);
    lep_options_free(o);
    return 0;
}
