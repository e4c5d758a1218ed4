/* leptrino-bench: measures the library against its physical limits and a
 * plain baseline, in one run, and prints ONE JSON object on stdout.
 *
 *   leptrino-bench [--smoke] [--e2e-only] [--runs N] [--sim PATH] [--python PATH] [--source DIR]
 *
 * Figures come from measurement in this run: decoder instructions per byte
 * from callgrind where valgrind is installed (ns/byte otherwise), messages/s
 * from the clock, end-to-end figures over a pty against leptrino-sim running
 * as another process. See BENCHMARKS.md for the method. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <unistd.h>

#include "bench.h"
#include "e2e.h"
#include "leptrino/leptrino.h"

#define MAX_RUNS 15

static char g_self[4096];

static const size_t k_chunks[] = { 1, 32, 4096 };
#define N_CHUNKS (sizeof(k_chunks) / sizeof(k_chunks[0]))

/* Instructions of one region run under callgrind, or -1. */
static double callgrind_ir(int region, int stream, size_t chunk, size_t frames)
{
    char out[] = "/tmp/leptrino-bench-cg-XXXXXX";
    char a_region[16], a_stream[16], a_chunk[32], a_frames[32], a_out[64];
    char line[512];
    double ir = -1.0;
    FILE *f;
    int fd = mkstemp(out);
    char *argv[] = { "valgrind", "--tool=callgrind", a_out,    "--toggle-collect=region_*",
                     g_self,     "--region",         a_region, a_stream,
                     a_chunk,    a_frames,           NULL };
    if (fd < 0) {
        return -1.0;
    }
    close(fd);
    snprintf(a_out, sizeof a_out, "--callgrind-out-file=%s", out);
    snprintf(a_region, sizeof a_region, "%d", region);
    snprintf(a_stream, sizeof a_stream, "%d", stream);
    snprintf(a_chunk, sizeof a_chunk, "%zu", chunk);
    snprintf(a_frames, sizeof a_frames, "%zu", frames);
    if (bench_run(argv, NULL) == 0 && (f = fopen(out, "r")) != NULL) {
        while (fgets(line, sizeof line, f) != NULL) {
            if (strncmp(line, "summary:", 8) == 0 || strncmp(line, "totals:", 7) == 0) {
                ir = strtod(strchr(line, ':') + 1, NULL);
            }
        }
        fclose(f);
    }
    remove(out);
    return ir;
}

/* Median wall time of one region run over s. */
static double timed_run(int region, const bench_bytes *s, size_t chunk, int runs, size_t *msgs)
{
    double t[MAX_RUNS];
    int r;
    uint32_t sink = 0;
    for (r = 0; r < runs; r++) {
        double t0 = bench_now_s();
        *msgs = bench_region_run(region, s, chunk, &sink);
        t[r] = bench_now_s() - t0;
    }
    if (sink == 0xFFFFFFFFu) {
        fputc(' ', stderr); /* keep sink alive */
    }
    return bench_median(t, (size_t)runs);
}

static void machine(void)
{
    struct utsname u;
    char line[512];
    char model[256] = "";
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f != NULL) {
        while (fgets(line, sizeof line, f) != NULL) {
            char *colon = strchr(line, ':');
            if (strncmp(line, "model name", 10) == 0 && colon != NULL) {
                snprintf(model, sizeof model, "%s", colon + 2);
                model[strcspn(model, "\n")] = '\0';
                break;
            }
        }
        fclose(f);
    }
    json_open("machine");
    json_str("cpu", model[0] ? model : NULL);
    json_int("cpus_online", sysconf(_SC_NPROCESSORS_ONLN));
    if (uname(&u) == 0) {
        json_str("kernel", u.release);
        json_str("arch", u.machine);
    }
#if defined(__VERSION__)
    json_str("compiler", __VERSION__);
#endif
    json_str("build_type", LEP_BENCH_BUILD_TYPE);
    if ((f = fopen("/proc/loadavg", "r")) != NULL) {
        double load = 0.0;
        if (fscanf(f, "%lf", &load) == 1) {
            json_num("load_1min_at_start", load);
        }
        fclose(f);
    }
    json_close();
}

static void limits(void)
{
    json_open("limits");
    json_int("baud", 460800);
    json_num("line_bytes_per_s", 46080.0);
    json_int("data_frame_bytes", 25);
    json_num("sample_rate_hz", 1200.0);
    json_num("period_us", 1e6 / 1200.0);
    json_num("frame_wire_time_us", 25.0 * 10.0 / 460800.0 * 1e6);
    json_num("samples_per_s_at_line_rate", 46080.0 / 25.0);
    json_close();
}

static void decoder(int use_cg, int runs, size_t frames)
{
    int st;
    json_open("decoder");
    json_str("method", use_cg ? "callgrind (valgrind --tool=callgrind --toggle-collect=region_*), "
                                "instructions of the decode loop incl. the caller's event handling"
                              : "clock_gettime, median of runs");
    json_str("unit", use_cg ? "instructions_per_byte" : "ns_per_byte");
    json_str("leptrino", "lep_frame_decoder_feed_all: one call per chunk, a handler per event");
    json_str("leptrino_feed", "lep_frame_decoder_feed: one call per event (and per chunk end)");
    json_str(
        "plain",
        "baseline: a per-byte parse function called from the read loop (bench/plain_decoder.c)");
    json_str("plain_loop", "the same state machine with the loop in its file (state in registers)");
    json_int("frames_per_stream", (long long)frames);
    json_int("runs", runs);
    json_open("streams");
    for (st = 0; st < STREAM_COUNT; st++) {
        bench_bytes s;
        size_t c;
        if (bench_stream_make(st, frames, &s) != 0) {
            continue;
        }
        json_open(bench_stream_name(st));
        json_int("bytes", (long long)s.len);
        json_int("frames_sent", (long long)s.frames);
        json_num("payload_0x10_share", (double)s.payload_dle / (double)s.payload);
        json_int("corrupted_bytes", (long long)s.corrupted);
        json_open("chunks");
        for (c = 0; c < N_CHUNKS; c++) {
            char key[16];
            size_t m_lep = 0;
            size_t m_feed = 0;
            size_t m_plain = 0;
            size_t m_loop = 0;
            double t_lep = timed_run(REGION_LEPTRINO, &s, k_chunks[c], runs, &m_lep);
            double t_feed = timed_run(REGION_FEED, &s, k_chunks[c], runs, &m_feed);
            double t_plain = timed_run(REGION_PLAIN, &s, k_chunks[c], runs, &m_plain);
            double t_loop = timed_run(REGION_PLAIN_LOOP, &s, k_chunks[c], runs, &m_loop);
            double v_lep = t_lep * 1e9 / (double)s.len;
            double v_feed = t_feed * 1e9 / (double)s.len;
            double v_plain = t_plain * 1e9 / (double)s.len;
            double v_loop = t_loop * 1e9 / (double)s.len;
            if (use_cg) {
                v_lep = callgrind_ir(REGION_LEPTRINO, st, k_chunks[c], frames) / (double)s.len;
                v_feed = callgrind_ir(REGION_FEED, st, k_chunks[c], frames) / (double)s.len;
                v_plain = callgrind_ir(REGION_PLAIN, st, k_chunks[c], frames) / (double)s.len;
                v_loop = callgrind_ir(REGION_PLAIN_LOOP, st, k_chunks[c], frames) / (double)s.len;
            }
            snprintf(key, sizeof key, "%zu", k_chunks[c]);
            json_open(key);
            json_num("leptrino", v_lep);
            json_num("plain", v_plain);
            json_num("ratio_plain_over_leptrino", v_plain / v_lep);
            json_num("plain_loop", v_loop);
            json_num("ratio_plain_loop_over_leptrino", v_loop / v_lep);
            json_num("leptrino_feed", v_feed);
            json_num("ratio_plain_over_leptrino_feed", v_plain / v_feed);
            json_int("leptrino_messages", (long long)m_lep);
            json_int("leptrino_feed_messages", (long long)m_feed);
            json_int("plain_messages", (long long)m_plain);
            json_int("plain_loop_messages", (long long)m_loop);
            json_num("leptrino_msgs_per_s", (double)m_lep / t_lep);
            json_num("leptrino_feed_msgs_per_s", (double)m_feed / t_feed);
            json_num("plain_msgs_per_s", (double)m_plain / t_plain);
            json_num("plain_loop_msgs_per_s", (double)m_loop / t_loop);
            json_num("leptrino_ns_per_byte", t_lep * 1e9 / (double)s.len);
            json_num("plain_ns_per_byte", t_plain * 1e9 / (double)s.len);
            json_num("plain_loop_ns_per_byte", t_loop * 1e9 / (double)s.len);
            json_close();
        }
        json_close();
        json_close();
        free(s.data);
    }
    json_close();
    json_close();
}

static void client_step(int use_cg, int runs, size_t frames)
{
    bench_bytes s;
    size_t m = 0;
    double t;
    json_open("client_step");
    if (bench_stream_make(STREAM_REALISTIC, frames, &s) != 0) {
        json_close();
        return;
    }
    t = timed_run(REGION_CLIENT_STEP, &s, 1, runs, &m);
    json_str("what", "lep_client_step_byte fed one byte per call (an ISR ring consumer: pop, "
                     "step, use the sample), realistic stream, streaming");
    json_str("unit", use_cg ? "instructions_per_byte" : "ns_per_byte");
    json_num("leptrino",
             use_cg ? callgrind_ir(REGION_CLIENT_STEP, STREAM_REALISTIC, 1, frames) / (double)s.len
                    : t * 1e9 / (double)s.len);
    json_num("plain_same_input",
             use_cg ? callgrind_ir(REGION_PLAIN, STREAM_REALISTIC, 1, frames) / (double)s.len
                    : 0.0 / 0.0);
    json_num("plain_loop_same_input",
             use_cg ? callgrind_ir(REGION_PLAIN_LOOP, STREAM_REALISTIC, 1, frames) / (double)s.len
                    : 0.0 / 0.0);
    json_int("samples", (long long)m);
    json_num("samples_per_s", (double)m / t);
    json_num("ns_per_byte", t * 1e9 / (double)s.len);
    /* The documented general API on the same input: one call per byte. */
    t = timed_run(REGION_CLIENT_STEP_CALL, &s, 1, runs, &m);
    json_str("step_call_what",
             "lep_client_step(c, &b, 1, &used) per byte (an ISR ring consumer: pop b, "
             "step), lep_client_get_sample on LEP_STEP_SAMPLE, same stream");
    json_num("step_call", use_cg
                              ? callgrind_ir(REGION_CLIENT_STEP_CALL, STREAM_REALISTIC, 1, frames) /
                                    (double)s.len
                              : t * 1e9 / (double)s.len);
    json_int("step_call_samples", (long long)m);
    json_num("step_call_ns_per_byte", t * 1e9 / (double)s.len);
    json_close();
    free(s.data);
}

static void usage(void);

/* One --region argument: a number below count, or the name fn(k) gives for
 * it. Returns the index, or -1 (nothing else accepted: "all_0x10" must not
 * read as 0). */
static int region_arg(const char *a, int count, const char *(*fn)(int))
{
    char *end;
    long v;
    int k;
    for (k = 0; k < count; k++) {
        if (strcmp(a, fn(k)) == 0) {
            return k;
        }
    }
    v = strtol(a, &end, 10);
    return end != a && *end == '\0' && v >= 0 && v < count ? (int)v : -1;
}

/* A positive count (chunk bytes, frames): the value, or 0 when a is not one. */
static size_t count_arg(const char *a)
{
    char *end;
    unsigned long long v;
    if (*a < '0' || *a > '9') {
        return 0;
    }
    v = strtoull(a, &end, 10);
    return *end == '\0' && v <= (unsigned long long)SIZE_MAX / 64u ? (size_t)v : 0;
}

static int region_main(char **argv)
{
    bench_bytes s;
    uint32_t sink = 0;
    size_t n;
    int region = region_arg(argv[0], REGION_COUNT, bench_region_name);
    int stream = region_arg(argv[1], STREAM_COUNT, bench_stream_name);
    size_t chunk = count_arg(argv[2]);
    size_t frames = count_arg(argv[3]);
    if (region < 0 || stream < 0 || chunk == 0 || frames == 0) {
        fprintf(stderr, "leptrino-bench: --region %s %s %s %s: %s\n", argv[0], argv[1], argv[2],
                argv[3],
                region < 0   ? "unknown region"
                : stream < 0 ? "unknown stream"
                : chunk == 0 ? "the chunk size must be a whole number of bytes >= 1"
                             : "the frame count must be a whole number >= 1");
        usage();
        return 2;
    }
    if (bench_stream_make(stream, frames, &s) != 0) {
        return 1;
    }
    n = bench_region_run(region, &s, chunk, &sink);
    printf("%zu %u\n", n, (unsigned)sink);
    free(s.data);
    return 0;
}

static void usage(void)
{
    int k;
    fputs(
        "usage: leptrino-bench [--smoke] [--e2e-only] [--runs N] [--sim PATH] [--python PATH] "
        "[--source DIR]\n"
        "Prints one JSON object of measured figures (see BENCHMARKS.md).\n"
        "--e2e-only: the end-to-end and Python figures alone (a quick look; not the full object).\n"
        "       leptrino-bench --region REGION STREAM CHUNK FRAMES\n"
        "Runs one decoding loop alone (for callgrind's --toggle-collect='region_*').\n"
        "REGION, by number or name:",
        stderr);
    for (k = 0; k < REGION_COUNT; k++) {
        fprintf(stderr, " %d=%s", k, bench_region_name(k));
    }
    fputs("\nSTREAM, by number or name:", stderr);
    for (k = 0; k < STREAM_COUNT; k++) {
        fprintf(stderr, " %d=%s", k, bench_stream_name(k));
    }
    fputs("\n", stderr);
}

int main(int argc, char **argv)
{
    e2e_options eo;
    int smoke = 0;
    int e2e_only = 0;
    int runs = 5;
    int use_cg;
    int i;
    size_t frames;
    ssize_t n = readlink("/proc/self/exe", g_self, sizeof g_self - 1u);
    if (n > 0) {
        g_self[n] = '\0';
    } else {
        snprintf(g_self, sizeof g_self, "%s", argv[0]);
    }
    if (argc == 6 && strcmp(argv[1], "--region") == 0) {
        return region_main(argv + 2);
    }
    if (argc == 5 && strcmp(argv[1], "--e2e-child") == 0) {
        return e2e_child_main(argc - 2, argv + 2);
    }
    e2e_defaults(&eo, g_self);
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--smoke") == 0) {
            smoke = 1;
        } else if (strcmp(a, "--e2e-only") == 0) {
            e2e_only = 1;
        } else if (strcmp(a, "--runs") == 0 && v != NULL && atoi(v) > 0) {
            runs = atoi(v) < MAX_RUNS ? atoi(v) : MAX_RUNS;
            i++;
        } else if (strcmp(a, "--sim") == 0 && v != NULL) {
            eo.sim = v;
            i++;
        } else if (strcmp(a, "--python") == 0 && v != NULL) {
            eo.python = v;
            i++;
        } else if (strcmp(a, "--source") == 0 && v != NULL) {
            eo.source = v;
            i++;
        } else if (strcmp(a, "--help") == 0) {
            usage();
            return 0;
        } else {
            usage();
            return 2;
        }
    }
    if (smoke) {
        runs = 1;
        eo.smoke = 1;
    }
    frames = smoke ? 2000u : 40000u;
    use_cg = bench_have("valgrind");
    json_open(NULL);
    json_str("tool", "leptrino-bench");
    json_str("leptrino_version", lep_version());
    json_bool("smoke", smoke);
    machine();
    limits();
    /* A smoke run times the decoder table with the clock (36 callgrind runs
     * take most of a minute); the client step still goes through callgrind. */
    if (!e2e_only) {
        decoder(use_cg && !smoke, runs, frames);
        client_step(use_cg, runs, frames);
        json_open("encoder");
        json_num("frame_encode_msgs_per_s",
                 bench_encode_msgs_per_s(runs, smoke ? 20000u : 400000u, 0));
        json_num("sample_to_frame_msgs_per_s",
                 bench_encode_msgs_per_s(runs, smoke ? 20000u : 400000u, 1));
        json_close();
    }
    e2e_report(&eo);
    json_close();
    json_end();
    return 0;
}
