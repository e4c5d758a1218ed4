/* The virtual sensor's write trace (lep_sim_trace_writes): one record per
 * data message written, in stream order, between a start and an end record;
 * never replaces an existing file. Orders only, never durations.
 *
 * The transport emulation seen in it, end to end: with usb-packets or
 * ftdi-latency no message is written before the frame boundary that
 * releases it and messages go out in groups; with ppm no message is
 * written before its deadline on the shifted crystal. Each holds however
 * late the sensor's thread runs (a bound from below, never a duration). */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "leptrino/leptrino.h"
#include "leptrino/serial.h"
#include "leptrino/sim.h"
#include "host_os.h"
#include "sim_trace_file.h"
#include "struct_api.h"
#include "unity.h"

static lep_sim *sim;
static lep_serial *port;
static lep_client client;
static char err[256];
static char dir[64];
static char path[96];

void setUp(void)
{
    lep_sim_options o;
    int rc;
    sim = NULL;
    port = NULL;
    err[0] = '\0';
    snprintf(dir, sizeof dir, "/tmp/lep-trace-XXXXXX");
    TEST_ASSERT_NOT_NULL(lep_test_mkdtemp(dir));
    snprintf(path, sizeof path, "%s/writes.bin", dir);
    lep_sim_options_init(&o);
    rc = lep_sim_start_so(&o, &sim, err, sizeof err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, rc, err);
}

void tearDown(void)
{
    lep_serial_close(port);
    lep_sim_stop(sim);
    (void)unlink(path);
    (void)rmdir(dir);
}

static void open_client(void)
{
    int rc = lep_serial_open(lep_sim_port(sim), &port, err, sizeof err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, rc, err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_serial_client_init(&client, port));
}

/* The whole file; *n records (malloc'd). */
static lep_sim_trace_record *load(size_t *n)
{
    return lep_test_load_trace(path, n);
}

/* One stream: START, k = 0, 1, ... in order, END; times ordered. Returns the
 * index just past its END record. */
static size_t check_stream(const lep_sim_trace_record *r, size_t n, size_t at, uint64_t *samples)
{
    uint64_t k = 0;
    int64_t last;
    TEST_ASSERT_TRUE(at < n);
    TEST_ASSERT_TRUE(r[at].k == LEP_SIM_TRACE_START);
    last = r[at].t_call_ns;
    for (at++; at < n && r[at].k != LEP_SIM_TRACE_END; at++, k++) {
        TEST_ASSERT_TRUE(r[at].k == k);
        TEST_ASSERT_TRUE(r[at].t_call_ns >= last);
        TEST_ASSERT_TRUE(r[at].t_return_ns >= r[at].t_call_ns);
        last = r[at].t_call_ns;
    }
    TEST_ASSERT_TRUE_MESSAGE(at < n, "no end record");
    TEST_ASSERT_TRUE(r[at].t_call_ns >= last);
    *samples = k;
    return at + 1u;
}

static void stream(unsigned count)
{
    lep_sample smp;
    unsigned i;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    for (i = 0; i < count; i++)
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &smp, 1000));
}

static void test_every_message_written_is_recorded_in_order(void)
{
    lep_sim_trace_record *r;
    lep_sim_counters st;
    uint64_t first = 0, second = 0;
    size_t n, at;
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_trace_writes(sim, path, err, sizeof err), err);
    open_client();
    stream(300);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    /* the end record is in the file before the stop is answered */
    r = load(&n);
    at = check_stream(r, n, 0, &first);
    TEST_ASSERT_EQUAL_size_t(n, at);
    free(r);
    stream(50);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    lep_sim_get_stats(sim, &st);
    r = load(&n);
    at = check_stream(r, n, check_stream(r, n, 0, &first), &second);
    TEST_ASSERT_EQUAL_size_t(n, at);
    TEST_ASSERT_TRUE(first >= 300 && second >= 50);
    TEST_ASSERT_EQUAL_UINT64(st.samples_sent, first + second);
    free(r);
}

static void test_power_cycle_ends_the_stream(void)
{
    lep_sim_trace_record *r;
    uint64_t k = 0;
    size_t n;
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_trace_writes(sim, path, err, sizeof err), err);
    open_client();
    stream(20);
    lep_sim_power_cycle(sim);
    for (n = 0; n < 200; n++) { /* applied by the sensor's thread */
        lep_sim_counters st;
        struct timespec ts = { 0, 10000000 };
        lep_sim_get_stats(sim, &st);
        if (st.power_cycles > 0)
            break;
        nanosleep(&ts, NULL);
    }
    {
        lep_product_info info;
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 50, &info));
    }
    r = load(&n); /* the end record is out before anything else is answered */
    TEST_ASSERT_EQUAL_size_t(n, check_stream(r, n, 0, &k));
    free(r);
    lep_serial_close(port);
    port = NULL;
    lep_sim_stop(sim); /* writes out what is buffered */
    sim = NULL;
    r = load(&n);
    TEST_ASSERT_EQUAL_size_t(n, check_stream(r, n, 0, &k));
    TEST_ASSERT_TRUE(k >= 20);
    free(r);
}

static void test_existing_file_is_kept(void)
{
    static const char mine[] = "someone's file\n";
    char back[sizeof mine];
    FILE *f = fopen(path, "w");
    TEST_ASSERT_NOT_NULL(f);
    fputs(mine, f);
    fclose(f);
    TEST_ASSERT_EQUAL_INT(LEP_E_BUSY, lep_sim_trace_writes(sim, path, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "never replaced"));
    f = fopen(path, "r");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_NOT_NULL(fgets(back, sizeof back, f));
    fclose(f);
    TEST_ASSERT_EQUAL_STRING(mine, back);
    /* the refused call did not use up the sensor's one trace */
    TEST_ASSERT_EQUAL_INT(0, unlink(path));
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_trace_writes(sim, path, err, sizeof err), err);
}

static void test_bad_calls(void)
{
    char other[128];
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_trace_writes(NULL, path, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_trace_writes(sim, NULL, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_trace_writes(sim, "", NULL, 0));
    snprintf(other, sizeof other, "%s/no/such/dir", dir);
    TEST_ASSERT_EQUAL_INT(LEP_E_IO, lep_sim_trace_writes(sim, other, err, sizeof err));
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_trace_writes(sim, path, err, sizeof err), err);
    snprintf(other, sizeof other, "%s/second.bin", dir);
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_sim_trace_writes(sim, other, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(-1, access(other, F_OK));
}

static void test_stream_running_at_stop_is_closed(void)
{
    lep_sim_trace_record *r;
    uint64_t k = 0;
    size_t n;
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_trace_writes(sim, path, err, sizeof err), err);
    open_client();
    stream(10);
    lep_serial_close(port);
    port = NULL;
    lep_sim_stop(sim);
    sim = NULL;
    r = load(&n);
    TEST_ASSERT_EQUAL_size_t(n, check_stream(r, n, 0, &k));
    TEST_ASSERT_TRUE(k >= 10);
    free(r);
}

/* The sensor again with one option set (the one setUp made stopped). */
static void restart_with(const char *name, const char *value)
{
    lep_sim_options o;
    int rc;
    lep_sim_stop(sim);
    sim = NULL;
    lep_sim_options_init(&o);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_option_set(&o, name, value, err, sizeof err),
                                  err);
    rc = lep_sim_start_so(&o, &sim, err, sizeof err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, rc, err);
}

/* Stream count samples with the trace on, stop; the records of the stream
 * (r[0] its start, then k = 0.. in order, then its end): *n of them. */
static lep_sim_trace_record *traced_stream(unsigned count, size_t *n)
{
    lep_sim_trace_record *r;
    uint64_t k = 0;
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_trace_writes(sim, path, err, sizeof err), err);
    open_client();
    stream(count);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    r = load(n);
    TEST_ASSERT_EQUAL_size_t(*n, check_stream(r, *n, 0, &k));
    TEST_ASSERT_TRUE(k >= count);
    return r;
}

/* The sensor's deadline of sample k, as it computes it. */
static int64_t deadline(const lep_sim_trace_record *r, double rate, double ppm, uint64_t k)
{
    return r[0].t_call_ns + (int64_t)((double)(k + 1u) * (1e9 / (rate * (1.0 + ppm * 1e-6))));
}

/* Every message written at or after the first 1 ms boundary at or after its
 * deadline; how many writes carried them (one per distinct call time). */
static size_t check_frames(const lep_sim_trace_record *r, size_t n)
{
    size_t i, writes = 0;
    for (i = 1; i + 1u < n; i++) {
        int64_t due = deadline(r, 1200.0, 0.0, r[i].k);
        int64_t frame = (due + 999999) / 1000000 * 1000000;
        TEST_ASSERT_TRUE_MESSAGE(r[i].t_call_ns >= frame, "written before its frame");
        if (i == 1 || r[i].t_call_ns != r[i - 1u].t_call_ns)
            writes++;
    }
    return writes;
}

static void test_usb_packets_arrive_at_frame_boundaries(void)
{
    lep_sim_trace_record *r;
    size_t n, writes;
    restart_with("usb-packets", "1");
    r = traced_stream(600, &n);
    writes = check_frames(r, n);
    /* 1.2 samples per 1 ms frame: every fifth frame carries two (more when
     * the sensor's thread runs late), in one write: 5 writes per 6 samples */
    TEST_ASSERT_TRUE_MESSAGE(writes <= (n - 2u) * 9u / 10u, "no 1 ms groups");
    free(r);
}

static void test_ftdi_latency_sends_62_byte_packets(void)
{
    lep_sim_trace_record *r;
    size_t n, writes;
    restart_with("ftdi-latency", "16");
    r = traced_stream(600, &n);
    writes = check_frames(r, n);
    /* a 62-byte packet completes two or three messages of 20..25 bytes */
    TEST_ASSERT_TRUE_MESSAGE(writes <= (n - 2u) / 2u + 1u, "not in packets");
    free(r);
}

static void test_ppm_moves_the_rate(void)
{
    lep_sim_trace_record *r;
    size_t n, i;
    restart_with("ppm", "-1000");
    r = traced_stream(600, &n);
    /* the crystal 1000 ppm slow: sample 600 is due 0.5 ms after its nominal
     * time, and none is written before its true deadline */
    for (i = 1; i + 1u < n; i++)
        TEST_ASSERT_TRUE_MESSAGE(r[i].t_call_ns >= deadline(r, 1200.0, -1000.0, r[i].k),
                                 "written before its deadline");
    TEST_ASSERT_TRUE(deadline(r, 1200.0, -1000.0, 599) - deadline(r, 1200.0, 0.0, 599) > 490000);
    free(r);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_message_written_is_recorded_in_order);
    RUN_TEST(test_power_cycle_ends_the_stream);
    RUN_TEST(test_stream_running_at_stop_is_closed);
    RUN_TEST(test_existing_file_is_kept);
    RUN_TEST(test_bad_calls);
    RUN_TEST(test_usb_packets_arrive_at_frame_boundaries);
    RUN_TEST(test_ftdi_latency_sends_62_byte_packets);
    RUN_TEST(test_ppm_moves_the_rate);
    return UNITY_END();
}
