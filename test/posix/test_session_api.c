/* The session, the virtual sensor, the output writer, the ROS encoder and
 * payload through their flat public functions (handles, numbers, arrays,
 * strings), as another language calls them; and, where a struct form stays
 * inside the tree, that the flat call gives the same bytes (one
 * implementation underneath). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "leptrino/leptrino.h"
#include "leptrino/options.h"
#include "leptrino/output.h"
#include "leptrino/payload.h"
#include "leptrino/ros_cdr.h"
#include "leptrino/serial.h"
#include "leptrino/session.h"
#include "leptrino/sim.h"
#include "host_os.h"
#include "struct_api.h"
#include "unity.h"

#define CAP 512

static char err[256];
static lep_options *o;
static lep_session *s;
static double t_mono[CAP], t_utc[CAP], si[CAP * 6], zeroed[CAP * 6];
static int16_t raw[CAP * 6];
static uint8_t status[CAP], flags[CAP];
static uint16_t seq[CAP];

void setUp(void)
{
    err[0] = '\0';
    s = NULL;
    o = lep_options_new();
    TEST_ASSERT_NOT_NULL(o);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_int(o, "sim", 1, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_int(o, "sim-constant", 1, err, sizeof err));
}

void tearDown(void)
{
    lep_session_close(s);
    lep_options_free(o);
}

static void open_session(void)
{
    int rc = lep_session_open(o, &s, err, sizeof err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, rc, err);
    lep_options_free(o); /* copied at open: the handle may go at once */
    o = NULL;
}

/* Read until n samples have come, into the file's arrays from index 0. */
static size_t read_n(size_t want)
{
    size_t got = 0, n;
    while (got < want) {
        int rc =
            lep_session_read(s, 1000, want - got, &n, t_mono + got, t_utc + got, si + got * 6,
                             raw + got * 6, zeroed + got * 6, status + got, flags + got, seq + got);
        TEST_ASSERT_EQUAL_INT(LEP_OK, rc);
        got += n;
    }
    return got;
}

static void test_identity_and_texts_by_key(void)
{
    char buf[64], *json;
    size_t len = 0, need = 0;
    double rated[6], md[LEP_MD_COUNT];
    open_session();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_info(s, LEP_INFO_MODEL, buf, sizeof buf, &len));
    TEST_ASSERT_EQUAL_STRING("PFS055YA501U6", buf);
    TEST_ASSERT_EQUAL_size_t(13, len);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_info(s, LEP_INFO_SERIAL, buf, sizeof buf, NULL));
    TEST_ASSERT_EQUAL_STRING("00000001", buf);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_info(s, LEP_INFO_FIRMWARE, buf, sizeof buf, NULL));
    TEST_ASSERT_EQUAL_STRING("1.13", buf);
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_session_info(s, LEP_INFO_LIBRARY_VERSION, buf, sizeof buf, NULL));
    TEST_ASSERT_EQUAL_STRING(lep_version(), buf);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_info(s, LEP_INFO_COUNT, buf, sizeof buf, NULL));
    /* the metadata JSON: ask its size, then take it */
    TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER,
                          lep_session_info(s, LEP_INFO_METADATA_JSON, NULL, 0, &need));
    TEST_ASSERT_TRUE(need > 200);
    json = malloc(need + 1);
    TEST_ASSERT_NOT_NULL(json);
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_session_info(s, LEP_INFO_METADATA_JSON, json, need + 1, &len));
    TEST_ASSERT_EQUAL_size_t(need, len);
    TEST_ASSERT_EQUAL_size_t(need, strlen(json));
    TEST_ASSERT_NOT_NULL(strstr(json, "\"model\":\"PFS055YA501U6\""));
    TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER,
                          lep_session_info(s, LEP_INFO_METADATA_JSON, json, need, &len));
    TEST_ASSERT_EQUAL_STRING("", json);
    free(json);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_rated(s, rated));
    TEST_ASSERT_EQUAL_DOUBLE(500.0, rated[LEP_FZ]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_metadata(s, md, LEP_MD_COUNT));
    TEST_ASSERT_EQUAL_DOUBLE(500.0, md[LEP_MD_RATED + LEP_FZ]);
    TEST_ASSERT_EQUAL_DOUBLE(1.0, md[LEP_MD_SIM]);
    TEST_ASSERT_EQUAL_DOUBLE(1200.0, md[LEP_MD_NOMINAL_HZ]);
    TEST_ASSERT_EQUAL_DOUBLE(1.0, md[LEP_MD_ROTATION]);
    TEST_ASSERT_EQUAL_DOUBLE(-9.80665, md[LEP_MD_GRAVITY + 2]);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, md[LEP_MD_OUTPUT_RATE_FIELD]); /* the 32-byte v1.13 form */
    TEST_ASSERT_EQUAL_size_t(LEP_MD_COUNT, lep_session_metadata_fields());
}

static void test_samples_into_caller_arrays_with_columns_skipped(void)
{
    size_t n = 99, i;
    double h[LEP_H_COUNT];
    open_session();
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_session_read(s, 10, CAP, &n, t_mono, NULL, NULL, NULL,
                                                        NULL, NULL, NULL, NULL));
    TEST_ASSERT_EQUAL_size_t(0, n);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(1, lep_session_streaming(s));
    TEST_ASSERT_EQUAL_size_t(240, read_n(240));
    for (i = 0; i < 240; i++) {
        TEST_ASSERT_EQUAL_UINT16((uint16_t)i, seq[i]);       /* nothing lost or doubled */
        TEST_ASSERT_EQUAL_DOUBLE(100.0, si[i * 6 + LEP_FZ]); /* 0.2 x rated, held */
        TEST_ASSERT_EQUAL_INT16(2000, raw[i * 6 + LEP_FZ]);
        if (i > 0)
            TEST_ASSERT_TRUE(t_mono[i] >= t_mono[i - 1]);
    }
    /* only SI values and nothing else: any column may be NULL */
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_session_read(s, 1000, 5, &n, NULL, NULL, si, NULL, NULL, NULL, NULL, NULL));
    TEST_ASSERT_TRUE(n >= 1 && n <= 5);
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_session_read(s, 0, 0, &n, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL));
    TEST_ASSERT_EQUAL_size_t(0, n);
    TEST_ASSERT_EQUAL_INT(
        LEP_E_ARG, lep_session_read(s, 0, 1, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_health(s, h, LEP_H_COUNT));
    TEST_ASSERT_TRUE(h[LEP_H_DELIVERED] >= 241.0);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, h[LEP_H_GAPS]);
    TEST_ASSERT_TRUE(h[LEP_H_MESSAGES] >= 241.0);
    TEST_ASSERT_EQUAL_STRING("delivered", lep_session_health_field_name(LEP_H_DELIVERED));
    TEST_ASSERT_EQUAL_STRING("stalls", lep_session_health_field_name(LEP_H_STALLS));
    TEST_ASSERT_NULL(lep_session_health_field_name(LEP_H_COUNT));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_stop(s));
    TEST_ASSERT_EQUAL_INT(0, lep_session_streaming(s));
}

/* A caller built against an older header passes fewer fields: it gets
 * those, and nothing beyond is written. */
static void test_short_arrays_get_the_fields_they_know(void)
{
    double h[5], ev[LEP_EVF_TARE + 1];
    int i;
    open_session();
    for (i = 0; i < 5; i++)
        h[i] = -1.0;
    h[4] = 12345.0;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_health(s, h, 4));
    TEST_ASSERT_EQUAL_DOUBLE(12345.0, h[4]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_untare(s));
    ev[LEP_EVF_TARE] = 777.0;
    TEST_ASSERT_EQUAL_INT(1, lep_session_next_event(s, ev, LEP_EVF_TARE));
    TEST_ASSERT_EQUAL_DOUBLE(LEP_EV_TARE, ev[LEP_EVF_TYPE]);
    TEST_ASSERT_EQUAL_DOUBLE(777.0, ev[LEP_EVF_TARE]);
    TEST_ASSERT_EQUAL_INT(0, lep_session_next_event(s, ev, LEP_EVF_TARE));
}

static void test_tare_comes_back_as_an_event_with_its_offsets(void)
{
    double ev[LEP_EVF_COUNT], off[6];
    int got = 0, k;
    size_t i, n;
    open_session();
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_tare(s, -1, 0.0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_tare(s, 0, 0.0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_tare(s, 50, 0.0));
    TEST_ASSERT_EQUAL_INT(1, lep_session_taring(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    while (!got) {
        (void)read_n(20);
        while (lep_session_next_event(s, ev, LEP_EVF_COUNT) == 1)
            if (ev[LEP_EVF_TYPE] == LEP_EV_TARE)
                got = 1;
    }
    TEST_ASSERT_EQUAL_DOUBLE(2000.0, ev[LEP_EVF_TARE + LEP_FZ]);
    TEST_ASSERT_EQUAL_INT(1, lep_session_get_tare(s, off));
    for (k = 0; k < 6; k++)
        TEST_ASSERT_EQUAL_DOUBLE(ev[LEP_EVF_TARE + k], off[k]);
    TEST_ASSERT_EQUAL_INT(0, lep_session_taring(s));
    n = read_n(50);
    for (i = 0; i < n; i++)
        TEST_ASSERT_EQUAL_DOUBLE(0.0, si[i * 6 + LEP_FZ]);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_next_event(NULL, ev, LEP_EVF_COUNT));
    TEST_ASSERT_EQUAL_size_t(LEP_EVF_COUNT, lep_session_event_fields());
}

/* The events' places: LEP_EVF_SAMPLE in the stream and LEP_EVF_ROW in the
 * last read's batch, the same place (SAMPLE - ROW = the rows read before
 * that read); the tare's row is the first the new offset zeroes. */
static void test_event_rows_in_the_stream_and_the_batch(void)
{
    double ev[LEP_EVF_COUNT];
    size_t total = 0, n = 0, before = 0;
    int found = 0, rc, guard;
    open_session();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    total = read_n(30);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_tare(s, 10, 0.0));
    for (guard = 0; !found && guard < 200; guard++) {
        before = total;
        rc = lep_session_read(s, 1000, 7, &n, t_mono, t_utc, si, raw, zeroed, status, flags, seq);
        TEST_ASSERT_EQUAL_INT(LEP_OK, rc);
        total += n;
        while (lep_session_next_event(s, ev, LEP_EVF_COUNT) == 1) {
            double row = ev[LEP_EVF_ROW];
            TEST_ASSERT_EQUAL_DOUBLE(LEP_EV_TARE, ev[LEP_EVF_TYPE]);
            TEST_ASSERT_EQUAL_DOUBLE((double)before, ev[LEP_EVF_SAMPLE] - row);
            TEST_ASSERT_TRUE(row >= 0.0 && row <= (double)n);
            TEST_ASSERT_TRUE(ev[LEP_EVF_SAMPLE] >= 30.0 + 10.0);
            if (row < (double)n) /* the first row with the new offset */
                TEST_ASSERT_EQUAL_DOUBLE(0.0, zeroed[(size_t)row * 6 + LEP_FZ]);
            if (row > 0.0) /* the last with the old (none) */
                TEST_ASSERT_EQUAL_DOUBLE(2000.0, zeroed[((size_t)row - 1) * 6 + LEP_FZ]);
            found = 1;
        }
    }
    TEST_ASSERT_TRUE(found);
    /* taken two reads late: the row lies before the last batch */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_untare(s));
    total += read_n(5);
    before = total; /* one call: the last read's batch starts here */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_read(s, 1000, 5, &n, t_mono, t_utc, si, raw, zeroed,
                                                   status, flags, seq));
    TEST_ASSERT_EQUAL_INT(1, lep_session_next_event(s, ev, LEP_EVF_COUNT));
    TEST_ASSERT_EQUAL_DOUBLE(LEP_EV_TARE, ev[LEP_EVF_TYPE]);
    TEST_ASSERT_EQUAL_DOUBLE((double)before, ev[LEP_EVF_SAMPLE] - ev[LEP_EVF_ROW]);
    TEST_ASSERT_TRUE(ev[LEP_EVF_ROW] <= -5.0);
    /* queued while stopped, taken then or after the next start: row 0 of
     * the next stream (not the last stream's count) */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_stop(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_untare(s));
    TEST_ASSERT_EQUAL_INT(1, lep_session_next_event(s, ev, LEP_EVF_COUNT));
    TEST_ASSERT_EQUAL_DOUBLE(0.0, ev[LEP_EVF_SAMPLE]);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, ev[LEP_EVF_ROW]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_untare(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_read(s, 1000, 3, &n, t_mono, t_utc, si, raw, zeroed,
                                                   status, flags, seq));
    TEST_ASSERT_EQUAL_INT(1, lep_session_next_event(s, ev, LEP_EVF_COUNT));
    TEST_ASSERT_EQUAL_DOUBLE(LEP_EV_TARE, ev[LEP_EVF_TYPE]);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, ev[LEP_EVF_SAMPLE]);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, ev[LEP_EVF_ROW]);
}

/* The struct form appends from b.n: the batch row counts the rows it held. */
static void test_event_row_counts_the_rows_a_batch_held(void)
{
    lep_session_batch b;
    lep_session_event e;
    size_t n;
    open_session();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    n = read_n(12);
    memset(&b, 0, sizeof b);
    b.cap = CAP;
    b.n = 5; /* rows 0..4 are the caller's own */
    b.zeroed = zeroed;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_untare(s));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_read_batch(s, &b, 1000));
    TEST_ASSERT_TRUE(b.n > 5);
    TEST_ASSERT_TRUE(lep_session_pop_event(s, &e));
    TEST_ASSERT_EQUAL_INT(LEP_EV_TARE, e.type);
    TEST_ASSERT_EQUAL_INT64((int64_t)e.sample - (int64_t)n + 5, e.row);
    TEST_ASSERT_TRUE(e.row >= 5 && e.row <= (int64_t)b.n);
}

static void test_stop_wait_from_the_sessions_options(void)
{
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_int(o, "timeout", 200, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_int(o, "retries", 1, err, sizeof err));
    open_session();
    TEST_ASSERT_EQUAL_DOUBLE(0.4, lep_session_stop_wait(s)); /* 2 tries x 0.2 s */
    TEST_ASSERT_EQUAL_DOUBLE(0.0, lep_session_stop_wait(NULL));
    lep_session_close(s);
    s = NULL;
    o = lep_options_new();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_int(o, "sim", 1, err, sizeof err));
    open_session();
    /* the defaults: 500 ms, 3 retries */
    TEST_ASSERT_EQUAL_DOUBLE((LEP_CLIENT_DEFAULT_RETRIES + 1) * 0.5, lep_session_stop_wait(s));
}

static void test_live_options_by_name(void)
{
    double d = 0, r[9], got[9];
    int64_t v = 0;
    size_t n;
    char buf[128];
    const double swap[9] = { 0, 1, 0, 1, 0, 0, 0, 0, 1 };
    const double skew[9] = { 1, 0.5, 0, 0, 1, 0, 0, 0, 1 };
    open_session();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_double(s, "lowpass", 30.0, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_get_double(s, "lowpass", &d));
    TEST_ASSERT_EQUAL_DOUBLE(30.0, d);
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_session_info(s, LEP_INFO_LOWPASS_NAME, buf, sizeof buf, NULL));
    TEST_ASSERT_TRUE(strstr(buf, "Butterworth") != NULL);
    /* above 0.45 x 1200 Hz: refused by the session, with the limit named */
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE,
                          lep_session_set_double(s, "lowpass", 600.0, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "lowpass 600"), err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "540"), err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_get_double(s, "lowpass", &d));
    TEST_ASSERT_EQUAL_DOUBLE(30.0, d);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_doubles(s, "rotation", swap, 9, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE,
                          lep_session_set_doubles(s, "rotation", skew, 9, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "orthonormal"), err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_get_doubles(s, "rotation", got, 9, &n));
    TEST_ASSERT_EQUAL_MEMORY(swap, got, sizeof got);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set(s, "limit", "fz=50", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_get(s, "limit", buf, sizeof buf, NULL));
    TEST_ASSERT_EQUAL_STRING("0,0,50,0,0,0", buf);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_int(s, "latency", 20, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_get_int(s, "latency", &v));
    TEST_ASSERT_EQUAL_INT64(20, v);
    /* what cannot change on an open session says so */
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_session_set_int(s, "decimate", 2, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "decimate: cannot change on an open session"), err);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_set(s, "nope", "1", err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "unknown option 'nope'"), err);
    /* the port reads as the path opened */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_get(s, "port", buf, sizeof buf, NULL));
    TEST_ASSERT_EQUAL_STRING(lep_session_port(s), buf);
    lep_rotation_from_rpy(0, 0, 0, r);
    TEST_ASSERT_EQUAL_DOUBLE(1.0, r[0]);
}

/* The 38-byte product info shows in the metadata; the resend budget is an
 * option of its own, kept by the session. */
static void test_product_info_form_and_retries(void)
{
    double md[LEP_MD_COUNT];
    int64_t v = 0;
    char buf[16];
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_options_set_int(o, "sim-output-rate-field", 1, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_int(o, "retries", 7, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_set_int(o, "retries", 256, err, sizeof err));
    open_session();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_metadata(s, md, LEP_MD_COUNT));
    TEST_ASSERT_EQUAL_DOUBLE(1.0, md[LEP_MD_OUTPUT_RATE_FIELD]);
    TEST_ASSERT_EQUAL_DOUBLE(1200.0, md[LEP_MD_OUTPUT_RATE_HZ]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_info(s, LEP_INFO_OUTPUT_RATE, buf, sizeof buf, NULL));
    TEST_ASSERT_EQUAL_STRING("1200", buf);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_get_int(s, "retries", &v));
    TEST_ASSERT_EQUAL_INT64(7, v);
}

static void test_missing_port_says_which(void)
{
    int rc;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_int(o, "sim", 0, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_options_set(o, "port", "/dev/leptrino-none", err, sizeof err));
    rc = lep_session_open(o, &s, err, sizeof err);
    TEST_ASSERT_EQUAL_INT(LEP_E_NOT_FOUND, rc);
    TEST_ASSERT_NULL(s);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "/dev/leptrino-none"), err);
}

static void test_sim_by_options_stats_and_models(void)
{
    lep_sim *sim = NULL;
    uint64_t st[LEP_SIMST_COUNT];
    int16_t r6[6];
    uint8_t stat = 9;
    uint16_t sq = 9;
    double rated[6];
    size_t i;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "sim-serial", "4242", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_start(o, &sim, err, sizeof err));
    TEST_ASSERT_NOT_NULL(lep_sim_port(sim));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_stats(sim, st, LEP_SIMST_COUNT));
    TEST_ASSERT_EQUAL_UINT64(0, st[LEP_SIMST_SAMPLES_SENT]);
    TEST_ASSERT_EQUAL_UINT64(0, st[LEP_SIMST_STREAMING]);
    TEST_ASSERT_EQUAL_STRING("samples_sent", lep_sim_stats_field_name(LEP_SIMST_SAMPLES_SENT));
    TEST_ASSERT_EQUAL_STRING("stalls", lep_sim_stats_field_name(LEP_SIMST_STALLS));
    TEST_ASSERT_NULL(lep_sim_stats_field_name(LEP_SIMST_COUNT));
    TEST_ASSERT_EQUAL_size_t(LEP_SIMST_COUNT, lep_sim_stats_fields());
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_stream_sample(sim, 70000, 0, r6, &stat, &sq));
    TEST_ASSERT_EQUAL_UINT16(70000 % 65536, sq);
    TEST_ASSERT_EQUAL_INT16(2000, r6[LEP_FZ]);
    TEST_ASSERT_EQUAL_UINT8(0, stat);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_stream_sample(sim, 0, 4, r6, NULL, NULL));
    lep_sim_stop(sim);
    TEST_ASSERT_EQUAL_size_t(4, lep_sim_model_count());
    for (i = 0; i < lep_sim_model_count(); i++)
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_model_rated(lep_sim_model_name(i), rated));
    TEST_ASSERT_NULL(lep_sim_model_name(4));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_model_rated("PFS999", rated));
}

static void test_port_list_is_a_handle(void)
{
    lep_port_list *l = NULL;
    size_t i;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_port_list_new(&l));
    for (i = 0; i < lep_port_list_count(l); i++) {
        TEST_ASSERT_TRUE(LEP_TEST_PORT_PATH_OK(lep_port_list_path(l, i)));
        TEST_ASSERT_TRUE(lep_port_list_vid(l, i) >= 0 && lep_port_list_vid(l, i) <= 0xFFFF);
    }
    TEST_ASSERT_EQUAL_STRING("", lep_port_list_path(l, i));
    TEST_ASSERT_EQUAL_INT(0, lep_port_list_likely_sensor(l, i));
    lep_port_list_free(l);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_port_list_new(NULL));
    TEST_ASSERT_EQUAL_size_t(0, lep_port_list_count(NULL));
}

static void test_payload_flat_equals_the_struct_form(void)
{
    const double g[4 * 3] = { 0, 0, -9.8, 9.8, 0, 0, 0, 9.8, 0, 0, -6.9, -6.9 };
    double w[4 * 6], fit[LEP_FIT_COUNT], pw[6];
    const double p[4] = { 1.5, 0.01, -0.02, 0.05 };
    lep_payload ps = { 1.5, { 0.01, -0.02, 0.05 } };
    lep_payload_fit f;
    double w2[6];
    int i, k;
    for (i = 0; i < 4; i++) {
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_payload_wrench(p, g + i * 3, w + i * 6));
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_payload_wrench_p(&ps, g + i * 3, w2));
        TEST_ASSERT_EQUAL_MEMORY(w2, w + i * 6, sizeof w2);
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_payload_identify(g, w, 4, fit, LEP_FIT_COUNT, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_payload_identify_fit(g, w, 4, &f, err, sizeof err));
    TEST_ASSERT_EQUAL_DOUBLE(f.payload.mass_kg, fit[LEP_FIT_PAYLOAD]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 1.5, fit[LEP_FIT_PAYLOAD]);
    for (k = 0; k < 3; k++)
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, p[1 + k], fit[LEP_FIT_PAYLOAD + 1 + k]);
    TEST_ASSERT_EQUAL_DOUBLE(f.spread, fit[LEP_FIT_SPREAD]);
    TEST_ASSERT_EQUAL_DOUBLE(4.0, fit[LEP_FIT_POSES]);
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE,
                          lep_payload_identify(g, w, 2, fit, LEP_FIT_COUNT, err, sizeof err));
    TEST_ASSERT_EQUAL_DOUBLE(9.80665, lep_standard_gravity());
    TEST_ASSERT_EQUAL_DOUBLE(0.02, lep_payload_min_spread());
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_payload_wrench(NULL, g, pw));
}

/* Two writers, one fed the flat arrays and one the batch: the same bytes. */
static void test_output_flat_writes_the_batch_bytes(void)
{
    char pa[64], pb[64];
    lep_output *a = NULL, *b = NULL;
    lep_output_options oo;
    lep_session_batch bt;
    lep_session_event ev[2];
    double evf[2 * LEP_EVF_COUNT];
    size_t n, i;
    char fa[8192], fb[8192];
    FILE *f;
    size_t la, lb;
    open_session();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    n = read_n(30);
    snprintf(pa, sizeof pa, "/tmp/lep-flat-a-%ld.csv", (long)getpid());
    snprintf(pb, sizeof pb, "/tmp/lep-flat-b-%ld.csv", (long)getpid());
    unlink(pa);
    unlink(pb);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG,
                          lep_output_open(pa, 7, 0, LEP_COL_DEFAULT, 0, 0, &a, err, sizeof err));
    TEST_ASSERT_NULL(a);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_open(pa, LEP_OUTPUT_CSV, LEP_TIME_MONO, 0x3F, 0, 0, &a,
                                                  err, sizeof err));
    lep_output_options_init(&oo);
    oo.time = LEP_TIME_MONO;
    oo.columns = 0x3F;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_open_opts(pb, &oo, &b, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(0, lep_output_add_session(a, s, "x"));
    TEST_ASSERT_EQUAL_INT(0, lep_output_add_session(b, s, "x"));
    memset(ev, 0, sizeof ev);
    ev[0].type = LEP_EV_GAP;
    ev[0].sample = 10;
    ev[0].gap_from = t_mono[9];
    ev[0].gap_to = t_mono[10];
    ev[0].lost = 3;
    ev[1].type = LEP_EV_TARE;
    ev[1].sample = 20;
    ev[1].t_mono = t_mono[20];
    ev[1].tare[2] = 1234.5;
    for (i = 0; i < 2; i++)
        lep_event_to_fields(&ev[i], evf + i * LEP_EVF_COUNT);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_write(a, 0, n, t_mono, t_utc, si, raw, zeroed, status,
                                                   flags, seq, evf, 2, LEP_EVF_COUNT));
    memset(&bt, 0, sizeof bt);
    bt.cap = bt.n = n;
    bt.t_mono = t_mono;
    bt.t_utc = t_utc;
    bt.si = si;
    bt.raw = raw;
    bt.zeroed = zeroed;
    bt.status = status;
    bt.flags = flags;
    bt.seq = seq;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_write_batch(b, 0, &bt, 0, ev, 2));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_close(a));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_close(b));
    f = fopen(pa, "rb");
    la = fread(fa, 1, sizeof fa, f);
    fclose(f);
    f = fopen(pb, "rb");
    lb = fread(fb, 1, sizeof fb, f);
    fclose(f);
    unlink(pa);
    unlink(pb);
    TEST_ASSERT_TRUE(la > 1000);
    TEST_ASSERT_EQUAL_size_t(lb, la);
    TEST_ASSERT_EQUAL_MEMORY(fb, fa, la);
    TEST_ASSERT_NOT_NULL(strstr(fa, "# gap "));
    TEST_ASSERT_NOT_NULL(strstr(fa, "# tare "));
}

static void test_ros_flat_writes_the_batch_bytes(void)
{
    uint8_t a[40 * 120], b[40 * 120], ra[40 * 120], rb[40 * 120];
    int64_t la = 0, lb = 0, sa[40], sb[40];
    double rated[6];
    lep_rated r;
    lep_session_batch bt;
    size_t n, sz = lep_ros_wrench_size(6);
    int k;
    open_session();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    n = read_n(40);
    lep_session_rated(s, rated);
    for (k = 0; k < 6; k++)
        r.axis[k] = (float)rated[k];
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_ros_wrench_cdr(n, t_utc, si, raw, rated, "sensor", &la, a, ra, sizeof a, sa));
    memset(&bt, 0, sizeof bt);
    bt.cap = bt.n = n;
    bt.t_utc = t_utc;
    bt.si = si;
    bt.raw = raw;
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_ros_wrench_cdr_batch(&bt, 0, n, &r, "sensor", &lb, b, rb, sizeof b, sb));
    TEST_ASSERT_EQUAL_MEMORY(b, a, n * sz);
    TEST_ASSERT_EQUAL_MEMORY(rb, ra, n * sz);
    TEST_ASSERT_EQUAL_MEMORY(sb, sa, sizeof(int64_t) * n);
    TEST_ASSERT_EQUAL_INT64(lb, la);
    rated[3] = -1.0;
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_ros_wrench_cdr(n, t_utc, si, raw, rated, "sensor", &la,
                                                          a, ra, sizeof a, sa));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_identity_and_texts_by_key);
    RUN_TEST(test_samples_into_caller_arrays_with_columns_skipped);
    RUN_TEST(test_short_arrays_get_the_fields_they_know);
    RUN_TEST(test_tare_comes_back_as_an_event_with_its_offsets);
    RUN_TEST(test_event_rows_in_the_stream_and_the_batch);
    RUN_TEST(test_event_row_counts_the_rows_a_batch_held);
    RUN_TEST(test_stop_wait_from_the_sessions_options);
    RUN_TEST(test_live_options_by_name);
    RUN_TEST(test_product_info_form_and_retries);
    RUN_TEST(test_missing_port_says_which);
    RUN_TEST(test_sim_by_options_stats_and_models);
    RUN_TEST(test_port_list_is_a_handle);
    RUN_TEST(test_payload_flat_equals_the_struct_form);
    RUN_TEST(test_output_flat_writes_the_batch_bytes);
    RUN_TEST(test_ros_flat_writes_the_batch_bytes);
    return UNITY_END();
}
