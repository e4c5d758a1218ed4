/* End-to-end measurements of leptrino-bench: the client against leptrino-sim
 * in another process over a pseudo-terminal, as a user's program runs it.
 *
 * Latency of sample k, the headline: the time the read that returned it
 * returned, minus the time the virtual sensor called the write() that handed
 * it to the pty. The sim records that time for every data message
 * (`--trace-writes FILE`, docs/simulator.md), keyed by k, the index of the
 * sample in its stream (the sequence number in the reserved bytes, unwrapped);
 * both are CLOCK_MONOTONIC of one machine. Kept as a second figure: the
 * latency from the sample's deadline t0 + (k+1)/rate (t0 from the trace's
 * start record), which adds the sim's own wake-up lateness; that lateness is
 * reported as well (write call minus deadline).
 *
 * Beside leptrino's paths, in the same run against the same sim, the field
 * baselines (field_stream.c): one byte per read() on a VMIN=0/VTIME=0 port
 * into the plain decoder, sleeping 1 ms after an empty read (field_sleep) or
 * spinning (field_busy, bounded in time), with the ratios between them. */
#define _DEFAULT_SOURCE
#define _XOPEN_SOURCE 600 /* posix_openpt, ptsname */
#include "e2e.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "leptrino/leptrino.h"
#include "leptrino/serial.h"
#include "leptrino/session.h"
#include "leptrino/sim.h"
#include "struct_api.h"

#define LAT_MAX 200000u

typedef struct sim_proc {
    pid_t pid;
    char port[256];
    char dir[64];   /* temporary directory of the trace, "" when none */
    char trace[96]; /* the sim's --trace-writes file */
    long trace_off; /* bytes of it already taken */
} sim_proc;

void e2e_defaults(e2e_options *o, const char *self)
{
    static char sim[4096];
    static char python[4096];
    const char *slash = strrchr(self, '/');
    int dir = slash != NULL ? (int)(slash - self) : 1;
    memset(o, 0, sizeof(*o));
    o->self = self;
    o->source = LEP_BENCH_SOURCE_DIR;
    /* Build tree (bench/ beside tools/), then installed (same bindir), then PATH. */
    snprintf(sim, sizeof sim, "%.*s/../tools/leptrino-sim/leptrino-sim", dir, slash ? self : ".");
    if (access(sim, X_OK) != 0) {
        snprintf(sim, sizeof sim, "%.*s/leptrino-sim", dir, slash ? self : ".");
        if (access(sim, X_OK) != 0) {
            snprintf(sim, sizeof sim, "leptrino-sim");
        }
    }
    o->sim = sim;
    snprintf(python, sizeof python, "%s/build/venv/bin/python", o->source);
    o->python = access(python, X_OK) == 0 ? python : "python3";
}

static int64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static double cpu_s(int who)
{
    struct rusage ru;
    getrusage(who, &ru);
    return (double)ru.ru_utime.tv_sec + (double)ru.ru_utime.tv_usec * 1e-6 +
           (double)ru.ru_stime.tv_sec + (double)ru.ru_stime.tv_usec * 1e-6;
}

/* read + write system calls of this process so far (/proc/self/io), or -1. */
static long long proc_rw_syscalls(void)
{
    char line[128];
    long long r = -1;
    long long w = -1;
    FILE *f = fopen("/proc/self/io", "r");
    if (f == NULL) {
        return -1;
    }
    while (fgets(line, sizeof line, f) != NULL) {
        (void)(sscanf(line, "syscr: %lld", &r) || sscanf(line, "syscw: %lld", &w));
    }
    fclose(f);
    return r >= 0 && w >= 0 ? r + w : -1;
}

/* Start leptrino-sim at rate; with trace, it records its writes into a new
 * file in a new temporary directory (removed by sim_stop). */
static int sim_start(const e2e_options *o, double rate, int trace, sim_proc *sp)
{
    int fds[2];
    char a_rate[32];
    FILE *f;
    pid_t parent;
    memset(sp, 0, sizeof(*sp));
    snprintf(a_rate, sizeof a_rate, "%g", rate);
    if (trace) {
        snprintf(sp->dir, sizeof sp->dir, "/tmp/leptrino-bench-XXXXXX");
        if (mkdtemp(sp->dir) == NULL) {
            sp->dir[0] = '\0';
        } else {
            snprintf(sp->trace, sizeof sp->trace, "%s/writes.bin", sp->dir);
        }
    }
    if (pipe(fds) != 0) {
        return -1;
    }
    parent = getpid();
    sp->pid = fork();
    if (sp->pid < 0) {
        return -1;
    }
    if (sp->pid == 0) {
        char *argv[] = { (char *)o->sim, "--rate", a_rate, "--trace-writes", sp->trace, NULL };
        if (sp->trace[0] == '\0') {
            argv[3] = NULL;
        }
        bench_child_follow_parent(parent);
        dup2(fds[1], 1);
        close(fds[0]);
        close(fds[1]);
        execvp(argv[0], argv);
        _exit(127);
    }
    close(fds[1]);
    f = fdopen(fds[0], "r");
    if (f == NULL || fgets(sp->port, sizeof sp->port, f) == NULL) {
        if (f != NULL) {
            fclose(f);
        }
        kill(sp->pid, SIGTERM);
        waitpid(sp->pid, NULL, 0);
        return -1;
    }
    fclose(f);
    sp->port[strcspn(sp->port, "\n")] = '\0';
    return 0;
}

/* Stop the sim, remove its trace; its CPU seconds (user + sys) over its life. */
static double sim_stop(sim_proc *sp)
{
    struct rusage ru;
    int status;
    int w;
    memset(&ru, 0, sizeof(ru));
    kill(sp->pid, SIGTERM);
    w = (int)wait4(sp->pid, &status, 0, &ru);
    if (sp->trace[0] != '\0') {
        remove(sp->trace);
    }
    if (sp->dir[0] != '\0') {
        rmdir(sp->dir);
    }
    if (w < 0) {
        return 0.0 / 0.0;
    }
    return (double)ru.ru_utime.tv_sec + (double)ru.ru_utime.tv_usec * 1e-6 +
           (double)ru.ru_stime.tv_sec + (double)ru.ru_stime.tv_usec * 1e-6;
}

/* CPU nanoseconds of every thread of process pid so far (the sum of
 * /proc/PID/task/TID/schedstat's first field: time on a CPU, exact for a
 * thread that is asleep when read), or -1 where that is not available. */
static long long proc_cpu_ns(pid_t pid)
{
    char path[64];
    long long sum = 0;
    struct dirent *e;
    DIR *d;
    snprintf(path, sizeof path, "/proc/%ld/task", (long)pid);
    d = opendir(path);
    if (d == NULL) {
        return -1;
    }
    while ((e = readdir(d)) != NULL) {
        char stat_path[128];
        long long ns = -1;
        FILE *f;
        if (e->d_name[0] == '.') {
            continue;
        }
        snprintf(stat_path, sizeof stat_path, "%s/%.20s/schedstat", path, e->d_name);
        f = fopen(stat_path, "r");
        if (f != NULL) {
            if (fscanf(f, "%lld", &ns) != 1) {
                ns = -1;
            }
            fclose(f);
        }
        if (ns < 0) {
            sum = -1;
            break;
        }
        sum += ns;
    }
    closedir(d);
    return sum;
}

typedef struct stream_result {
    int rc;
    size_t samples;
    size_t lost; /* sequence numbers skipped */
    double wall_s;
    double cpu_s;
    double sim_cpu_s; /* the sim's threads over the same window, or NaN */
    long long rw_syscalls;
    long long sleeps; /* the field loop's nanosleep calls (0 for leptrino's paths) */
    int64_t t_start;  /* just before the start command was written */
    double t0_window_us;
    uint64_t *k;     /* [min(samples, LAT_MAX)]: stream index of each sample */
    int64_t *t_recv; /* when the read that returned it returned */
} stream_result;

static void stream_free(stream_result *r)
{
    free(r->k);
    free(r->t_recv);
    r->k = NULL;
    r->t_recv = NULL;
}

/* The client's own blocking call, the session with two latency budgets, and
 * the field baselines (a 1 ms sleep after an empty read, or a busy loop). */
enum mode {
    MODE_CLIENT = 0,
    MODE_LOW_LATENCY = 1,
    MODE_RECORDING = 2,
    MODE_FIELD_SLEEP = 3,
    MODE_FIELD_BUSY = 4
};
#define RECORDING_BUDGET_MS 100
#define FIELD_BUSY_SECONDS 2.5 /* the busy loop burns a core: this long, no more */

static int budget_of(int mode)
{
    return mode == MODE_RECORDING ? RECORDING_BUDGET_MS : 0;
}

static int is_field(int mode)
{
    return mode == MODE_FIELD_SLEEP || mode == MODE_FIELD_BUSY;
}

/* Stream from port for `seconds` (or `count` samples) in mode: open, start-up
 * recovery, start, read, stop. Records each sample's stream index and the
 * time the read that returned it returned; CPU of this process and of the
 * sim (sim_pid, 0 for none) over the reading. */
static void stream_run(const char *port, int mode, double seconds, size_t count, pid_t sim_pid,
                       stream_result *r)
{
    static lep_client c;
    lep_serial *sp = NULL;
    lep_session *ss = NULL;
    field_port fp;
    lep_product_info info;
    char err[256];
    uint64_t k = 0;
    int have_k = 0;
    double t_end;
    double c0;
    long long s0;
    long long sim0 = sim_pid > 0 ? proc_cpu_ns(sim_pid) : -1;
    double w0;
    memset(r, 0, sizeof(*r));
    memset(&fp, 0, sizeof(fp));
    fp.fd = -1;
    r->k = malloc(LAT_MAX * sizeof(uint64_t));
    r->t_recv = malloc(LAT_MAX * sizeof(int64_t));
    if (r->k == NULL || r->t_recv == NULL) {
        r->rc = LEP_E_ARG;
        return;
    }
    if (mode == MODE_CLIENT) {
        r->rc = lep_serial_open(port, &sp, err, sizeof err);
        if (r->rc == LEP_OK) {
            lep_serial_client_init(&c, sp);
            r->rc = lep_client_sync(&c, 50, &info);
        }
    } else if (is_field(mode)) {
        r->rc = field_open(&fp, port, mode == MODE_FIELD_SLEEP);
    } else {
        lep_session_options o;
        lep_session_options_init(&o);
        o.port = port;
        o.latency_ms = budget_of(mode);
        r->rc = lep_session_open_so(&o, &ss, err, sizeof err);
    }
    r->t_start = now_ns();
    if (r->rc == LEP_OK) {
        r->rc = mode == MODE_CLIENT ? lep_client_start(&c)
                : is_field(mode)    ? field_send(&fp, LEP_CMD_START)
                                    : lep_session_start(ss);
    }
    r->t0_window_us = (double)(now_ns() - r->t_start) / 1e3;
    sim0 = sim_pid > 0 ? proc_cpu_ns(sim_pid) : -1;
    c0 = cpu_s(RUSAGE_SELF);
    s0 = proc_rw_syscalls();
    w0 = bench_now_s();
    t_end = w0 + seconds;
    while (r->rc == LEP_OK && (count > 0 ? r->samples < count : bench_now_s() < t_end)) {
        static uint16_t seq[512];
        size_t n = 0;
        size_t i;
        int64_t t_recv;
        if (mode == MODE_CLIENT) {
            lep_sample smp;
            r->rc = lep_client_next_sample(&c, &smp, 1000);
            seq[0] = smp.reserved;
            n = r->rc == LEP_OK ? 1u : 0u;
        } else if (is_field(mode)) {
            r->rc = field_next(&fp, &seq[0], 1000);
            n = r->rc == LEP_OK ? 1u : 0u;
        } else {
            lep_session_batch b;
            memset(&b, 0, sizeof(b));
            b.cap = sizeof(seq) / sizeof(seq[0]);
            b.seq = seq;
            r->rc = lep_session_read_batch(ss, &b, 1000);
            n = b.n;
        }
        t_recv = now_ns();
        for (i = 0; i < n; i++) {
            if (have_k) {
                uint16_t step = (uint16_t)(seq[i] - (uint16_t)k);
                uint64_t next = k + (step == 0 ? 65536u : step);
                r->lost += (size_t)(next - k - 1u);
                k = next;
            } else {
                k = seq[i];
                have_k = 1;
            }
            if (r->samples < LAT_MAX) {
                r->k[r->samples] = k;
                r->t_recv[r->samples] = t_recv;
            }
            r->samples++;
        }
    }
    r->wall_s = bench_now_s() - w0;
    r->cpu_s = cpu_s(RUSAGE_SELF) - c0;
    r->rw_syscalls = s0 >= 0 ? proc_rw_syscalls() - s0 : -1;
    r->sleeps = fp.fd >= 0 ? fp.sleeps : 0;
    {
        long long sim1 = sim0 >= 0 ? proc_cpu_ns(sim_pid) : -1;
        r->sim_cpu_s = sim0 >= 0 && sim1 >= sim0 ? (double)(sim1 - sim0) / 1e9 : 0.0 / 0.0;
    }
    if (mode == MODE_CLIENT) {
        if (sp != NULL) {
            (void)lep_client_stop(&c);
            lep_serial_close(sp);
        }
    } else if (is_field(mode)) {
        field_close(&fp);
    } else {
        lep_session_close(ss);
    }
}

/* The sim's write trace of the stream just stopped: records from where the
 * last call left off up to the stream's end record (waited for up to 2 s;
 * the sim writes it out before it answers the stop). On return *t0 is the
 * stream's start (0 when not seen), write_ns[k] the write() call of sample k
 * (0: none), end_ns[k] the return of that write(), *kn the size of both
 * (malloc'd; free them). 0, or -1 without a trace. */
static int trace_take(sim_proc *sp, int64_t *t0, int64_t **write_ns, int64_t **end_ns, size_t *kn)
{
    lep_sim_trace_record rec;
    int64_t *w = NULL;
    int64_t *e = NULL;
    size_t cap = 0;
    int ended = 0;
    int tries;
    FILE *f;
    *t0 = 0;
    *write_ns = NULL;
    *end_ns = NULL;
    *kn = 0;
    if (sp->trace[0] == '\0' || (f = fopen(sp->trace, "rb")) == NULL) {
        return -1;
    }
    for (tries = 0; !ended && tries < 400; tries++) {
        if (fseek(f, sp->trace_off, SEEK_SET) != 0) {
            break;
        }
        while (!ended && fread(&rec, sizeof rec, 1, f) == 1) {
            sp->trace_off += (long)sizeof rec;
            if (rec.k == LEP_SIM_TRACE_START) {
                *t0 = rec.t_call_ns;
            } else if (rec.k == LEP_SIM_TRACE_END) {
                ended = 1;
            } else if (rec.k < (uint64_t)LAT_MAX * 4u) {
                if (rec.k >= cap) {
                    size_t ncap = cap == 0 ? 16384u : cap;
                    int64_t *nw, *ne;
                    while (ncap <= rec.k) {
                        ncap *= 2u;
                    }
                    nw = realloc(w, ncap * sizeof(int64_t));
                    if (nw == NULL) {
                        break;
                    }
                    w = nw;
                    ne = realloc(e, ncap * sizeof(int64_t));
                    if (ne == NULL) {
                        break;
                    }
                    e = ne;
                    memset(w + cap, 0, (ncap - cap) * sizeof(int64_t));
                    memset(e + cap, 0, (ncap - cap) * sizeof(int64_t));
                    cap = ncap;
                }
                w[rec.k] = rec.t_call_ns;
                e[rec.k] = rec.t_return_ns;
            }
        }
        if (!ended) {
            struct timespec ts = { 0, 5000000 };
            clearerr(f);
            nanosleep(&ts, NULL);
        }
    }
    fclose(f);
    *write_ns = w;
    *end_ns = e;
    *kn = cap;
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a;
    double y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sort v[0..n) and write p50, p99, max, min (nulls when n is 0); returns the p50. */
static double json_spread(double *v, size_t n)
{
    double p50;
    qsort(v, n, sizeof(double), cmp_double);
    p50 = bench_percentile(v, n, 0.50);
    json_num("p50", p50);
    json_num("p99", bench_percentile(v, n, 0.99));
    json_num("max", n > 0 ? v[n - 1u] : 0.0 / 0.0);
    json_num("min", n > 0 ? v[0] : 0.0 / 0.0);
    return p50;
}

/* Latency figures of r against the sim's trace (see the file's comment);
 * returns the p50 from the write (NaN without one). */
static double report_latency(sim_proc *sp, const stream_result *r)
{
    size_t n = r->samples < LAT_MAX ? r->samples : LAT_MAX;
    size_t i, m = 0, d = 0, late_n = 0;
    int64_t t0;
    int64_t *w, *we;
    size_t kn;
    double p50;
    double period_ns = 1e9 / 1200.0;
    double *from_write = malloc((n + 1u) * sizeof(double));
    double *from_write_end = malloc((n + 1u) * sizeof(double));
    double *from_deadline = malloc((n + 1u) * sizeof(double));
    double *late = malloc((n + 1u) * sizeof(double));
    int traced = trace_take(sp, &t0, &w, &we, &kn) == 0;
    if (from_write == NULL || from_write_end == NULL || from_deadline == NULL || late == NULL) {
        n = 0;
    }
    for (i = 0; i < n; i++) {
        uint64_t k = r->k[i];
        double deadline = (double)(k + 1u) * period_ns;
        if (traced && t0 != 0) {
            from_deadline[d++] = ((double)(r->t_recv[i] - t0) - deadline) / 1e3;
        } else { /* no trace: t0 taken as the start command's write, an upper bound */
            from_deadline[d++] = ((double)(r->t_recv[i] - r->t_start) - deadline) / 1e3;
        }
        if (traced && k < kn && w[k] != 0) {
            from_write_end[m] = (double)(r->t_recv[i] - we[k]) / 1e3;
            from_write[m++] = (double)(r->t_recv[i] - w[k]) / 1e3;
            if (t0 != 0) {
                late[late_n++] = ((double)(w[k] - t0) - deadline) / 1e3;
            }
        }
    }
    json_open("latency_us");
    p50 = json_spread(from_write, m);
    json_int("matched", (long long)m);
    json_str("reference",
             traced ? "the sim's write() call of the sample (leptrino-sim --trace-writes), "
                      "to the return of the read that returned it"
                    : "no write trace: see latency_from_deadline_us");
    json_close();
    json_open("latency_from_write_end_us");
    json_spread(from_write_end, m);
    json_int("matched", (long long)m);
    json_str("reference", traced
                              ? "the return of the sim's write() of the sample (the pty holds it), "
                                "to the return of the read that returned it: a secondary figure, "
                                "latency_us less the write call's own time"
                              : "no write trace");
    json_close();
    json_open("latency_from_deadline_us");
    json_spread(from_deadline, d);
    json_str("reference", traced && t0 != 0
                              ? "the sample's deadline at the sim, t0+(k+1)/rate, t0 from its trace"
                              : "sim deadline t0+(k+1)/rate, t0 = when the start command was "
                                "written (upper bounds by at most t0_window_us)");
    json_num("t0_window_us", r->t0_window_us);
    json_close();
    json_open("sim_lateness_us");
    json_spread(late, late_n);
    json_str("reference",
             "the sim's write() call minus the sample's deadline: its own wake-up lateness");
    json_close();
    free(w);
    free(we);
    free(from_write_end);
    free(from_write);
    free(from_deadline);
    free(late);
    return m > 0 ? p50 : 0.0 / 0.0;
}

int e2e_child_main(int argc, char **argv)
{
    stream_result r;
    if (argc < 3) {
        return 2;
    }
    stream_run(argv[1], atoi(argv[0]), atof(argv[2]), 0, 0, &r);
    stream_free(&r);
    return r.rc == LEP_OK ? 0 : 1;
}

/* System calls of a child streaming `seconds` in mode, counted by strace -f -c. */
static long long strace_calls(const e2e_options *o, const char *port, int mode, double seconds)
{
    char out[] = "/tmp/leptrino-bench-st-XXXXXX";
    char a_mode[8], a_secs[32], a_out[64], line[256];
    long long calls = -1;
    FILE *f;
    int fd = mkstemp(out);
    char *argv[] = { "strace",        "-f",          "-c",   "-U",         "calls", "-o", a_out,
                     (char *)o->self, "--e2e-child", a_mode, (char *)port, a_secs,  NULL };
    if (fd < 0) {
        return -1;
    }
    close(fd);
    snprintf(a_out, sizeof a_out, "%s", out);
    snprintf(a_mode, sizeof a_mode, "%d", mode);
    snprintf(a_secs, sizeof a_secs, "%g", seconds);
    if (bench_run(argv, NULL) == 0 && (f = fopen(out, "r")) != NULL) {
        while (fgets(line, sizeof line, f) != NULL) {
            long long v;
            char word[16];
            if (sscanf(line, " %lld %15s", &v, word) == 2 && strcmp(word, "total") == 0) {
                calls = v;
            }
        }
        fclose(f);
    }
    remove(out);
    return calls;
}

/* The figures of one path that the comparison between paths uses. */
typedef struct path_figures {
    double latency_p50_us; /* from the sim's write */
    double cpu_us_per_sample;
    double cpu_percent;         /* of one core */
    double rw_per_sample;       /* read + write calls (/proc/self/io) */
    double syscalls_per_sample; /* strace, NaN without */
} path_figures;

static const char *path_of(int mode)
{
    switch (mode) {
    case MODE_CLIENT:
        return "lep_client_next_sample over lep_serial, one sample per call";
    case MODE_FIELD_SLEEP:
        return "field baseline: VMIN=0/VTIME=0, one byte per read() into the plain decoder, "
               "a fixed 1 ms nanosleep after a read that returned 0";
    case MODE_FIELD_BUSY:
        return "field baseline: VMIN=0/VTIME=0, one byte per read() into the plain decoder, "
               "busy loop (never sleeps), run for a bounded time";
    default:
        return "lep_session_read over the port, batches of up to 512";
    }
}

/* Stream one path against the sim (sp): `samples` samples, or run_seconds
 * when samples is 0; then strace children streaming 0 and strace_seconds
 * (none when strace_seconds is 0). Writes the path's object under key and
 * fills *pf. */
static void report_mode(const e2e_options *o, const char *key, int mode, sim_proc *sp,
                        size_t samples, double run_seconds, double strace_seconds, path_figures *pf)
{
    stream_result r;
    struct stat st;
    double per_sample = 0.0 / 0.0;
    json_open(key);
    /* Streams of earlier paths (and of the strace children) are in the trace already. */
    if (sp->trace[0] != '\0' && stat(sp->trace, &st) == 0) {
        sp->trace_off = (long)st.st_size;
    }
    stream_run(sp->port, mode, samples > 0 ? 0.0 : run_seconds, samples, sp->pid, &r);
    json_str("path", path_of(mode));
    if (is_field(mode)) {
        json_null("latency_budget_ms");
    } else {
        json_int("latency_budget_ms", budget_of(mode));
    }
    json_int("rc", r.rc);
    json_int("samples", (long long)r.samples);
    json_int("lost", (long long)r.lost);
    pf->latency_p50_us = report_latency(sp, &r);
    pf->cpu_us_per_sample = r.samples ? r.cpu_s * 1e6 / (double)r.samples : 0.0 / 0.0;
    pf->cpu_percent = 100.0 * r.cpu_s / r.wall_s;
    pf->rw_per_sample =
        r.rw_syscalls >= 0 && r.samples ? (double)r.rw_syscalls / (double)r.samples : 0.0 / 0.0;
    json_num("wall_s", r.wall_s);
    json_num("cpu_s", r.cpu_s);
    json_num("cpu_percent_of_one_core", pf->cpu_percent);
    json_num("cpu_us_per_sample", pf->cpu_us_per_sample);
    json_num("sim_cpu_us_per_sample",
             r.samples ? r.sim_cpu_s * 1e6 / (double)r.samples : 0.0 / 0.0);
    json_num("sim_over_client_cpu", r.sim_cpu_s / r.cpu_s);
    json_num("read_write_syscalls_per_sample_proc", pf->rw_per_sample);
    if (is_field(mode)) {
        double sleeps = r.samples ? (double)r.sleeps / (double)r.samples : 0.0 / 0.0;
        json_num("idle_sleeps_per_sample", sleeps);
        json_num("syscalls_per_sample_proc", pf->rw_per_sample + sleeps);
        json_str("syscalls_proc_method",
                 "read+write calls (/proc/self/io) plus the loop's own nanosleep "
                 "calls, over the untraced run");
    }
    stream_free(&r);
    if (strace_seconds > 0.0 && bench_have("strace")) {
        long long base = strace_calls(o, sp->port, mode, 0.0);
        long long run = strace_calls(o, sp->port, mode, strace_seconds);
        double per_s = base >= 0 && run >= 0 ? (double)(run - base) / strace_seconds : 0.0 / 0.0;
        per_sample = per_s / 1200.0;
        json_num("syscalls_per_s", per_s);
        json_num("syscalls_per_sample", per_sample);
        json_str("syscalls_method",
                 "strace -f -c: (calls streaming T s) - (calls streaming 0 s), over T; "
                 "the traced run is slower than the untraced one");
    } else {
        json_null("syscalls_per_s");
        json_null("syscalls_per_sample");
        json_str("syscalls_method",
                 strace_seconds > 0.0
                     ? "strace not installed"
                     : "not run under strace: a busy loop's count is set by strace's own "
                       "speed; see read_write_syscalls_per_sample_proc");
    }
    pf->syscalls_per_sample = per_sample;
    json_close();
}

/* The comparison of one run: leptrino's paths against the field baseline
 * that sleeps (the one that does not burn a core). Ratios are
 * field / leptrino: above 1, leptrino spends less. */
static void report_field_comparison(const path_figures *low, const path_figures *rec,
                                    const path_figures *fsleep, const path_figures *fbusy)
{
    json_open("field_comparison");
    json_num("field_sleep_over_low_latency_latency_p50",
             fsleep->latency_p50_us / low->latency_p50_us);
    json_num("field_sleep_over_low_latency_cpu_per_sample",
             fsleep->cpu_us_per_sample / low->cpu_us_per_sample);
    json_num("field_sleep_over_recording_cpu_per_sample",
             fsleep->cpu_us_per_sample / rec->cpu_us_per_sample);
    json_num("field_sleep_over_recording_syscalls_per_sample",
             fsleep->syscalls_per_sample / rec->syscalls_per_sample);
    json_num("field_sleep_over_recording_read_write_per_sample_proc",
             fsleep->rw_per_sample / rec->rw_per_sample);
    json_num("field_busy_over_low_latency_latency_p50",
             fbusy->latency_p50_us / low->latency_p50_us);
    json_num("field_busy_cpu_percent_of_one_core", fbusy->cpu_percent);
    json_str("method",
             "same run, same sim: each ratio is the field path's figure over leptrino's "
             "(latency from the sim's write p50; getrusage CPU per sample; system calls per "
             "sample by strace, and read+write calls by /proc/self/io)");
    json_close();
}

static void max_rate(const e2e_options *o)
{
    static const double rates[] = { 1200, 2400, 4800, 7200, 10000 };
    double best = 0.0;
    size_t i;
    json_open_array("rates");
    for (i = 0; i < sizeof(rates) / sizeof(rates[0]); i++) {
        sim_proc sp;
        stream_result r;
        json_open(NULL);
        json_num("rate_hz", rates[i]);
        if (sim_start(o, rates[i], 0, &sp) != 0) {
            json_str("error", "leptrino-sim did not start");
            json_close();
            break;
        }
        stream_run(sp.port, MODE_LOW_LATENCY, o->smoke ? 0.3 : 2.0, 0, 0, &r);
        (void)sim_stop(&sp);
        stream_free(&r);
        json_int("rc", r.rc);
        json_int("samples", (long long)r.samples);
        json_int("lost", (long long)r.lost);
        json_num("received_hz", (double)r.samples / r.wall_s);
        json_close();
        if (r.rc != LEP_OK || r.lost != 0) {
            break;
        }
        best = rates[i];
    }
    json_close_array();
    json_num("max_rate_without_loss_hz", best > 0.0 ? best : 0.0 / 0.0);
}

/* The number after "key": in a one-line JSON object, or NaN. */
static double json_field(const char *text, const char *key)
{
    char pat[64];
    const char *p;
    snprintf(pat, sizeof pat, "\"%s\": ", key);
    p = strstr(text, pat);
    return p != NULL ? strtod(p + strlen(pat), NULL) : 0.0 / 0.0;
}

/* One run of bench_record.py --json with the session's latency budget
 * latency_s; its output line into line. NULL, or why there is no figure. */
static const char *python_run(const e2e_options *o, const char *latency_s, char *line, size_t cap)
{
    char script[4096];
    char out[] = "/tmp/leptrino-bench-py-XXXXXX";
    const char *reason = NULL;
    int fd = mkstemp(out);
    char *check[] = { (char *)o->python, "-c", "import leptrino", NULL };
    char *argv[] = { (char *)o->python,
                     script,
                     "--json",
                     "--latency",
                     (char *)latency_s,
                     "--runs",
                     o->smoke ? "1" : "3",
                     "--seconds",
                     o->smoke ? "0.3" : "2",
                     NULL };
    FILE *f;
    line[0] = '\0';
    snprintf(script, sizeof script, "%s/bindings/python/bench_record.py", o->source);
    if (fd < 0) {
        reason = "no temporary file";
    } else if (access(script, R_OK) != 0) {
        reason = "bindings/python/bench_record.py not found (pass --source DIR)";
    } else if (bench_run(check, NULL) != 0) {
        reason = "the leptrino package is not importable by this interpreter (pass --python PATH)";
    } else if (bench_run(argv, out) != 0) {
        reason = "bench_record.py failed";
    } else if ((f = fopen(out, "r")) != NULL) {
        if (fgets(line, (int)cap, f) == NULL) {
            line[0] = '\0';
        }
        fclose(f);
        if (json_field(line, "record_us_per_sample") != json_field(line, "record_us_per_sample")) {
            reason = "bench_record.py printed no record() figure";
        }
    }
    if (fd >= 0) {
        close(fd);
        remove(out);
    }
    return reason;
}

static void python_costs(const e2e_options *o)
{
    char line[2048];
    char backend[32] = "";
    const char *reason = python_run(o, "0.05", line, sizeof line);
    const char *b = strstr(line, "\"backend\": \"");
    if (b != NULL) {
        sscanf(b + 12, "%31[^\"]", backend);
    }
    json_open("python");
    json_str("interpreter", o->python);
    json_str("backend", backend[0] != '\0' ? backend : NULL);
    json_num("latency_budget_s", 0.05);
    json_num("record_us_cpu_per_sample", json_field(line, "record_us_per_sample"));
    json_num("stream_iter_us_cpu_per_sample", json_field(line, "iterate_us_per_sample"));
    json_num("session_read_only_us_cpu_per_sample",
             json_field(line, "session_read_only_us_per_sample"));
    json_str("reason", reason);
    /* With no budget every sample is a wake-up of its own: what the per-sample
     * figures cost before the session batched them. */
    reason = reason == NULL ? python_run(o, "0", line, sizeof line) : reason;
    json_open("latency_budget_0");
    json_num("record_us_cpu_per_sample", json_field(line, "record_us_per_sample"));
    json_num("stream_iter_us_cpu_per_sample", json_field(line, "iterate_us_per_sample"));
    json_num("session_read_only_us_cpu_per_sample",
             json_field(line, "session_read_only_us_per_sample"));
    json_str("reason", reason);
    json_close();
    json_str("method",
             "bindings/python/bench_record.py --json (time.thread_time of the calling thread, "
             "virtual sensor in process on a C thread), median of its runs; the Sensor's "
             "default latency budget 0.05 s, and 0 below");
    json_close();
}

/* The least CPU any virtual sensor can spend per sample here: a thread that
 * sleeps to each absolute deadline (clock_nanosleep TIMER_ABSTIME) at 1200
 * Hz and, with write_pty, writes one 25-byte message to a pty master (the
 * slave drained every 50 periods, so the pty never fills). CPU per period
 * (getrusage of this thread's process; nothing else runs in it meanwhile),
 * or NaN. */
static double sender_floor_us(size_t periods, int write_pty)
{
    static const uint8_t msg[25] = { 0x10, 0x02 };
    uint8_t drain[4096];
    const int64_t period = 833333;
    int m = -1;
    int sl = -1;
    int64_t t0;
    double c0;
    size_t k;
    if (write_pty) {
        struct termios t;
        m = posix_openpt(O_RDWR | O_NOCTTY);
        if (m < 0 || grantpt(m) != 0 || unlockpt(m) != 0 || ptsname(m) == NULL ||
            fcntl(m, F_SETFL, O_NONBLOCK) != 0 ||
            (sl = open(ptsname(m), O_RDWR | O_NOCTTY | O_NONBLOCK)) < 0 || tcgetattr(sl, &t) != 0) {
            if (m >= 0) {
                close(m);
            }
            return 0.0 / 0.0;
        }
        cfmakeraw(&t);
        (void)tcsetattr(sl, TCSANOW, &t);
    }
    t0 = now_ns();
    c0 = cpu_s(RUSAGE_SELF);
    for (k = 0; k < periods; k++) {
        int64_t due = t0 + (int64_t)(k + 1u) * period;
        struct timespec ts;
        ts.tv_sec = (time_t)(due / 1000000000);
        ts.tv_nsec = (long)(due % 1000000000);
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR) {
        }
        if (write_pty) {
            (void)!write(m, msg, sizeof msg);
            if (k % 50u == 49u) {
                while (read(sl, drain, sizeof drain) > 0) {
                }
            }
        }
    }
    c0 = cpu_s(RUSAGE_SELF) - c0;
    if (write_pty) {
        close(sl);
        close(m);
    }
    return c0 * 1e6 / (double)periods;
}

void e2e_report(const e2e_options *o)
{
    sim_proc sp;
    double sim_cpu;
    size_t samples = o->smoke ? 400u : 12000u;
    double strace_s = o->smoke ? 0.5 : 3.0;
    path_figures low, rec, client, fsleep, fbusy;
    json_open("end_to_end");
    json_str("sim", o->sim);
    if (sim_start(o, 1200.0, 1, &sp) != 0) {
        json_str("error", "leptrino-sim did not start (pass --sim PATH)");
        json_close();
        python_costs(o);
        return;
    }
    report_mode(o, "low_latency", MODE_LOW_LATENCY, &sp, samples, 0.0, strace_s, &low);
    report_mode(o, "recording", MODE_RECORDING, &sp, samples, 0.0, strace_s, &rec);
    report_mode(o, "client", MODE_CLIENT, &sp, samples, 0.0, strace_s, &client);
    report_mode(o, "field_sleep", MODE_FIELD_SLEEP, &sp, samples, 0.0, strace_s, &fsleep);
    /* The busy loop takes a whole core: bounded in time, never under strace. */
    report_mode(o, "field_busy", MODE_FIELD_BUSY, &sp, 0, o->smoke ? 0.3 : FIELD_BUSY_SECONDS, 0.0,
                &fbusy);
    report_field_comparison(&low, &rec, &fsleep, &fbusy);
    sim_cpu = sim_stop(&sp);
    json_num("sim_cpu_s_whole_life", sim_cpu);
    json_open("sender_floor");
    json_num("sleep_us_cpu_per_period", sender_floor_us(o->smoke ? 240u : 2400u, 0));
    json_num("sleep_and_pty_write_us_cpu_per_period", sender_floor_us(o->smoke ? 240u : 2400u, 1));
    json_str("method",
             "this process alone, 1200 Hz: clock_nanosleep(TIMER_ABSTIME) to each deadline, "
             "then one 25-byte write() to a pty master (slave drained every 50 periods); "
             "getrusage CPU per period: the least a virtual sensor can cost here");
    json_close();
    json_int("session_latency_budget_ms", RECORDING_BUDGET_MS);
    max_rate(o);
    json_close();
    python_costs(o);
}
