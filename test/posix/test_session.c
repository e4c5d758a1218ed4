/* The host session against the in-process virtual sensor: open, start, read,
 * stop; counts and durations; the start-up tare; metadata; bad arguments;
 * several sessions at once; the latency budget. No timing asserts: the
 * machine may be loaded. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <time.h>
#include <unistd.h>
#include <string.h>

#include "leptrino/error.h"
#include "leptrino/leptrino.h"
#include "leptrino/output.h"
#include "leptrino/serial.h"
#include "leptrino/session.h"
#include "session_test.h"
#include "host_os.h"
#include "struct_api.h"
#include "unity.h"

void setUp(void)
{
}

void tearDown(void)
{
}

static void test_open_start_read_stop(void)
{
    lep_session_options o;
    lep_session *s = open_sim(&o, NULL);
    st_batch b;
    lep_session_health_info h;
    size_t i;
    int rc = LEP_OK;

    st_batch_init(&b, 600);
    TEST_ASSERT_FALSE(lep_session_streaming(s));
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_session_read_batch(s, &b.b, 10));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_session_start(s));
    TEST_ASSERT_TRUE(lep_session_streaming(s));
    TEST_ASSERT_TRUE(LEP_TEST_PORT_FD_OK(lep_session_fd(s)));
    TEST_ASSERT_NOT_NULL(lep_session_client(s));
    TEST_ASSERT_NOT_NULL(lep_session_sim(s));
    while (b.b.n < 600 && (rc = lep_session_read_batch(s, &b.b, 2000)) == LEP_OK) {
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, rc);
    TEST_ASSERT_EQUAL_size_t(600, b.b.n);
    /* every sample, in order, none lost: sequence numbers 0, 1, 2, ... */
    for (i = 0; i < b.b.n; i++) {
        TEST_ASSERT_EQUAL_UINT16((uint16_t)i, b.seq[i]);
        TEST_ASSERT_EQUAL_UINT8(0, b.flags[i] & LEP_SF_GAP);
        if (i > 0)
            TEST_ASSERT_TRUE(b.t_mono[i] >= b.t_mono[i - 1]);
        /* one offset for the whole run (no jitter between batches): UTC
         * intervals equal monotonic ones, to the rounding of a double */
        TEST_ASSERT_DOUBLE_WITHIN(2e-6, b.t_utc[i] - b.t_mono[i], b.t_utc[0] - b.t_mono[0]);
        if (i > 0)
            TEST_ASSERT_TRUE(b.t_utc[i] >= b.t_utc[i - 1]);
    }
    {
        /* and that offset is the wall clock's (read here, bracketed by
         * monotonic reads; loose: the clock is not stepped during a test) */
        struct timespec m0, r, m1;
        double off;
        (void)clock_gettime(CLOCK_MONOTONIC, &m0);
        (void)clock_gettime(CLOCK_REALTIME, &r);
        (void)clock_gettime(CLOCK_MONOTONIC, &m1);
        off = (double)r.tv_sec + (double)r.tv_nsec / 1e9 -
              ((double)m0.tv_sec + (double)m0.tv_nsec / 1e9 + (double)m1.tv_sec +
               (double)m1.tv_nsec / 1e9) /
                  2.0;
        TEST_ASSERT_DOUBLE_WITHIN(0.05, off, b.t_utc[0] - b.t_mono[0]);
    }
    lep_session_get_health(s, &h);
    TEST_ASSERT_EQUAL_UINT64(0, h.lost);
    TEST_ASSERT_EQUAL_UINT64(0, h.gaps);
    TEST_ASSERT_EQUAL_UINT64(0, h.errors);
    TEST_ASSERT_TRUE(h.received >= 600);
    TEST_ASSERT_EQUAL_DOUBLE(1200.0, h.nominal_hz);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_stop(s));
    TEST_ASSERT_FALSE(lep_session_streaming(s));
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_session_read_batch(s, &b.b, 10));
    /* the client answers single commands again once the stream is stopped */
    {
        lep_sample one;
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sample(lep_session_client(s), &one));
    }
    lep_session_close(s);
    st_batch_free(&b);
}

static void test_count_and_start_tare_are_exact(void)
{
    lep_session_options o;
    lep_session *s;
    st_batch b;
    lep_session_event ev;
    double off[LEP_AXES], sum[LEP_AXES] = { 0 };
    int k, rc;
    lep_session_options_init(&o);
    o.count = 250;
    o.tare_samples = 40;
    s = open_sim(&o, &o);
    st_batch_init(&b, 1000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    while ((rc = lep_session_read_batch(s, &b.b, 2000)) == LEP_OK) {
    }
    TEST_ASSERT_EQUAL_INT(LEP_E_END, rc);
    TEST_ASSERT_EQUAL_INT(LEP_E_END, lep_session_read_batch(s, &b.b, 10)); /* and stays there */
    TEST_ASSERT_EQUAL_size_t(250, b.b.n);
    /* the tare samples (sequence 0..39) are not delivered */
    TEST_ASSERT_EQUAL_UINT16(40, b.seq[0]);
    TEST_ASSERT_EQUAL_UINT16(289, b.seq[249]);
    TEST_ASSERT_TRUE(lep_session_get_tare(s, off));
    TEST_ASSERT_TRUE(lep_session_pop_event(s, &ev));
    TEST_ASSERT_EQUAL_INT(LEP_EV_TARE, ev.type);
    TEST_ASSERT_EQUAL_UINT64(0, ev.sample);
    for (k = 0; k < LEP_AXES; k++)
        TEST_ASSERT_EQUAL_DOUBLE(off[k], ev.tare[k]);
    /* zeroed = raw - offset, exactly; the offset is a double mean, not rounded */
    for (k = 0; k < LEP_AXES; k++) {
        size_t i;
        for (i = 0; i < b.b.n; i++)
            TEST_ASSERT_EQUAL_DOUBLE((double)b.raw[i * 6 + (size_t)k] - off[k],
                                     b.zeroed[i * 6 + (size_t)k]);
        sum[k] = off[k] * 40.0;
        TEST_ASSERT_DOUBLE_WITHIN(1e-6, floor(sum[k] + 0.5), sum[k]); /* a sum of counts / 40 */
    }
    lep_session_close(s);
    st_batch_free(&b);
}

static void test_duration_counts_from_the_first_delivered_sample(void)
{
    lep_session_options o;
    lep_session *s;
    st_batch b;
    int rc;
    size_t i;
    lep_session_options_init(&o);
    o.duration_s = 0.5;
    o.tare_samples = 120;
    s = open_sim(&o, &o);
    st_batch_init(&b, 2000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    while ((rc = lep_session_read_batch(s, &b.b, 2000)) == LEP_OK) {
    }
    TEST_ASSERT_EQUAL_INT(LEP_E_END, rc);
    /* arrival times are reconstructed per period, so half a second of a
     * steady stream is about 600 samples (loose: a loaded machine bunches them) */
    TEST_ASSERT_UINT_WITHIN(250, 600, b.b.n);
    TEST_ASSERT_EQUAL_UINT16(120, b.seq[0]);
    for (i = 0; i < b.b.n; i++)
        TEST_ASSERT_TRUE(b.t_mono[i] - b.t_mono[0] < 0.5);
    lep_session_close(s);
    st_batch_free(&b);
}

static void test_metadata_and_json(void)
{
    lep_session_options o;
    lep_session *s;
    lep_session_meta m;
    char json[4096], small[16];
    size_t len = 0;
    lep_session_options_init(&o);
    snprintf(o.sim.serial, sizeof o.sim.serial, "%s", "4242");
    snprintf(o.sim.model, sizeof o.sim.model, "%s", "CFS034CA301U");
    s = open_sim(&o, &o);
    lep_session_get_metadata(s, &m);
    TEST_ASSERT_EQUAL_STRING("CFS034CA301U", m.info.model);
    TEST_ASSERT_EQUAL_STRING("4242", m.info.serial);
    TEST_ASSERT_EQUAL_STRING("v1.13 (32-byte info)", m.protocol);
    TEST_ASSERT_EQUAL_INT(0, m.sensor_filter);
    TEST_ASSERT_EQUAL_STRING("off", m.sensor_filter_label);
    TEST_ASSERT_EQUAL_STRING(lep_version(), m.library_version);
    TEST_ASSERT_TRUE(m.sim);
    /* before a stream, the start is the open (`leptrino read` says when) */
    TEST_ASSERT_TRUE(m.start_utc > 1.6e9 && m.start_mono > 0.0);
    {
        double opened = m.start_mono;
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
        lep_session_get_metadata(s, &m);
        TEST_ASSERT_TRUE(m.start_utc > 1.6e9 && m.start_mono >= opened);
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_metadata_json(s, json, sizeof json, &len));
    TEST_ASSERT_EQUAL_size_t(strlen(json), len);
    TEST_ASSERT_EQUAL_CHAR('{', json[0]);
    TEST_ASSERT_EQUAL_CHAR('}', json[len - 1]);
    TEST_ASSERT_NOT_NULL(strstr(json, "\"model\":\"CFS034CA301U\""));
    TEST_ASSERT_NOT_NULL(strstr(json, "\"serial\":\"4242\""));
    TEST_ASSERT_NOT_NULL(strstr(json, "\"sensor_filter\":0,\"sensor_filter_label\":\"off\""));
    TEST_ASSERT_NOT_NULL(strstr(json, "\"start_utc_iso\":\"20"));
    TEST_ASSERT_NOT_NULL(strstr(json, "\"sim\":true"));
    TEST_ASSERT_NOT_NULL(strstr(json, "\"tared\":false"));
    {
        size_t need = 0;
        TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER,
                              lep_session_metadata_json(s, small, sizeof small, &need));
        TEST_ASSERT_EQUAL_size_t(strlen(json), need); /* the room it needs, without the NUL */
        TEST_ASSERT_EQUAL_STRING("", small);
    }
    lep_session_close(s);
}

static void test_bad_options_are_refused_with_a_message(void)
{
    lep_session_options o;
    lep_session *s = (lep_session *)&o;
    char err[256];
    lep_session_options_init(&o);
    err[0] = '\0';
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_open_so(&o, &s, err, sizeof err));
    TEST_ASSERT_NULL(s);
    TEST_ASSERT_NOT_NULL(strstr(err, "no port"));
    o.use_sim = true;
    o.decimate = 0;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_open_so(&o, &s, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "decimate"));
    o.decimate = 1;
    o.lowpass_hz = 1000.0; /* above 0.45 x 1200 Hz */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_open_so(&o, &s, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "lowpass"));
    o.lowpass_hz = -3.0; /* the message names lowpass alone, with the value */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_open_so(&o, &s, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "lowpass_hz -3"));
    TEST_ASSERT_NULL(strstr(err, "duration"));
    o.lowpass_hz = 0.0;
    o.duration_s = -1.0;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_open_so(&o, &s, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "duration_s -1"));
    TEST_ASSERT_NULL(strstr(err, "lowpass"));
    o.duration_s = 0.0;
    o.rotation[0] = 2.0;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_open_so(&o, &s, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "rotation"));
    lep_session_options_init(&o);
    o.port = "/dev/leptrino-no-such-port";
    TEST_ASSERT_EQUAL_INT(LEP_E_NOT_FOUND, lep_session_open_so(&o, &s, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "/dev/leptrino-no-such-port"));
    TEST_ASSERT_NULL(s);
    lep_session_close(NULL);
}

static void test_two_sessions_at_once(void)
{
    lep_session_options o1, o2;
    lep_session *a, *b;
    st_batch ba, bb;
    lep_session_health_info ha, hb;
    lep_session_options_init(&o1);
    lep_session_options_init(&o2);
    o1.count = 300;
    o2.count = 300;
    o2.tare_samples = 10;
    snprintf(o2.sim.serial, sizeof o2.sim.serial, "%s", "2");
    a = open_sim(&o1, &o1);
    b = open_sim(&o2, &o2);
    st_batch_init(&ba, 400);
    st_batch_init(&bb, 400);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(a));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(b));
    while (ba.b.n < 300 || bb.b.n < 300) {
        if (ba.b.n < 300)
            TEST_ASSERT_TRUE(lep_session_read_batch(a, &ba.b, 2000) >= LEP_E_END);
        if (bb.b.n < 300)
            TEST_ASSERT_TRUE(lep_session_read_batch(b, &bb.b, 2000) >= LEP_E_END);
    }
    TEST_ASSERT_EQUAL_UINT16(299, ba.seq[299]);
    TEST_ASSERT_EQUAL_UINT16(309, bb.seq[299]);
    TEST_ASSERT_FALSE(lep_session_get_tare(a, NULL));
    TEST_ASSERT_TRUE(lep_session_get_tare(b, NULL));
    lep_session_get_health(a, &ha);
    lep_session_get_health(b, &hb);
    TEST_ASSERT_EQUAL_UINT64(0, ha.lost + hb.lost);
    TEST_ASSERT_TRUE(strcmp(lep_session_port(a), lep_session_port(b)) != 0);
    lep_session_close(a);
    lep_session_close(b);
    st_batch_free(&ba);
    st_batch_free(&bb);
}

/* The same samples, whatever the latency budget: only the wake-ups differ. */
static void test_latency_budget_delivers_the_same_samples(void)
{
    int budgets[2] = { 0, 100 };
    int j;
    for (j = 0; j < 2; j++) {
        lep_session_options o;
        lep_session *s;
        st_batch b;
        int rc, calls = 0;
        size_t i;
        lep_session_options_init(&o);
        o.latency_ms = budgets[j];
        o.count = 700;
        s = open_sim(&o, &o);
        st_batch_init(&b, 700);
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
        while ((rc = lep_session_read_batch(s, &b.b, 2000)) == LEP_OK)
            calls++;
        TEST_ASSERT_EQUAL_INT(LEP_E_END, rc);
        TEST_ASSERT_EQUAL_size_t(700, b.b.n);
        for (i = 0; i < b.b.n; i++) {
            TEST_ASSERT_EQUAL_UINT16((uint16_t)i, b.seq[i]);
            if (i > 0)
                TEST_ASSERT_TRUE(b.t_mono[i] >= b.t_mono[i - 1]);
        }
        if (budgets[j] > 0) /* about 0.58 s of data at 100 ms per call */
            TEST_ASSERT_TRUE_MESSAGE(calls < 60, "the budget should batch many samples per call");
        lep_session_close(s);
        st_batch_free(&b);
    }
}

typedef struct poker {
    lep_session *s;
    st_flag stop;
    unsigned calls;
} poker;

/* Another thread changing and reading the settings while the stream runs. */
static void *poke(void *arg)
{
    poker *p = arg;
    double r[9], off[LEP_AXES];
    lep_session_health_info h;
    lep_session_meta m;
    char json[4096];
    size_t len;
    lep_rotation_from_rpy(0.1, 0.2, 0.3, r);
    while (!st_flag_is_up(&p->stop)) {
        (void)lep_session_tare(p->s, 20, 0.0);
        (void)lep_session_set_lowpass(p->s, (p->calls % 2u) ? 50.0 : 0.0);
        (void)lep_session_set_rotation(p->s, r, NULL);
        lep_session_get_health(p->s, &h);
        lep_session_get_metadata(p->s, &m);
        (void)lep_session_metadata_json(p->s, json, sizeof json, &len);
        (void)lep_session_get_tare(p->s, off);
        if (p->calls % 7u == 0u)
            (void)lep_session_untare(p->s);
        p->calls++;
        {
            struct timespec ts = { 0, 2000000 };
            nanosleep(&ts, NULL);
        }
    }
    return NULL;
}

static void test_settings_from_another_thread(void)
{
    lep_session_options o;
    lep_session *s;
    st_batch b;
    poker p;
    pthread_t th;
    lep_session_event ev;
    size_t i, tares = 0;
    lep_session_options_init(&o);
    o.count = 1200;
    s = open_sim(&o, &o);
    st_batch_init(&b, 1200);
    memset(&p, 0, sizeof p);
    st_flag_init(&p.stop);
    p.s = s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(0, pthread_create(&th, NULL, poke, &p));
    while (lep_session_read_batch(s, &b.b, 2000) == LEP_OK) {
    }
    st_flag_raise(&p.stop);
    pthread_join(th, NULL);
    TEST_ASSERT_EQUAL_size_t(1200, b.b.n);
    for (i = 1; i < b.b.n; i++) /* nothing lost, nothing stalled */
        TEST_ASSERT_EQUAL_UINT16((uint16_t)(b.seq[i - 1] + 1u), b.seq[i]);
    while (lep_session_pop_event(s, &ev))
        tares += ev.type == LEP_EV_TARE;
    TEST_ASSERT_TRUE(p.calls > 10);
    TEST_ASSERT_TRUE(tares > 0);
    lep_session_close(s);
    st_batch_free(&b);
}

/* A session written by the writer: the header comes at the first write, so
 * the start-up tare is in the metadata; one row per delivered sample. */
static void test_recording_from_a_session(void)
{
    lep_session_options o;
    lep_session *s;
    lep_output_options oo;
    lep_output *w = NULL;
    lep_session_meta m;
    st_batch b;
    char path[64], err[256] = "", line[8192], want[256];
    FILE *f;
    int rc, rows = 0;
    lep_session_options_init(&o);
    o.count = 5;
    o.tare_samples = 10;
    s = open_sim(&o, &o);
    snprintf(path, sizeof path, "/tmp/lep-session-rec-%ld.csv", (long)getpid());
    (void)unlink(path);
    lep_output_options_init(&oo);
    oo.columns = LEP_COL_RAW | LEP_COL_SI | LEP_COL_SEQ;
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_output_open_opts(path, &oo, &w, err, sizeof err),
                                  err);
    TEST_ASSERT_EQUAL_INT(0, lep_output_add_session(w, s, "a"));
    st_batch_init(&b, 16);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    while ((rc = lep_session_read_batch(s, &b.b, 2000)) == LEP_OK) {
    }
    TEST_ASSERT_EQUAL_INT(LEP_E_END, rc);
    lep_session_get_metadata(s, &m);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_write_batch(w, 0, &b.b, 0, NULL, 0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_close(w));
    f = fopen(path, "r");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_NOT_NULL(fgets(line, sizeof line, f));
    {
        static const char head[] = "# leptrino-metadata: {\"library_version\":";
        TEST_ASSERT_EQUAL_INT(0, strncmp(line, head, sizeof head - 1));
    }
    TEST_ASSERT_NOT_NULL(strstr(line, "\"tared\":true"));
    TEST_ASSERT_NOT_NULL(fgets(line, sizeof line, f));
    TEST_ASSERT_EQUAL_STRING("t_s,fx_counts,fy_counts,fz_counts,mx_counts,my_counts,mz_counts,"
                             "fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm,seq\n",
                             line);
    while (fgets(line, sizeof line, f) != NULL) {
        const char *last = strrchr(line, ',');
        TEST_ASSERT_NOT_NULL(last);
        snprintf(want, sizeof want, ",%u\n", (unsigned)b.seq[rows]);
        TEST_ASSERT_EQUAL_STRING(want, last);
        /* t_s counts from the session's start */
        snprintf(want, sizeof want, "%.6f,%d,", b.t_mono[rows] - m.start_mono, b.raw[rows * 6]);
        TEST_ASSERT_EQUAL_INT(0, strncmp(line, want, strlen(want)));
        rows++;
    }
    fclose(f);
    TEST_ASSERT_EQUAL_INT(5, rows);
    TEST_ASSERT_EQUAL_UINT16(10, b.seq[0]);
    (void)unlink(path);
    lep_session_close(s);
    st_batch_free(&b);
}

/* One handshake sample through the session's tare, units and output frame;
 * only outside the stream; the stream's counters untouched. */
static void test_read_one_uses_the_sessions_processing(void)
{
    static const double yaw90[9] = { 0, -1, 0, 1, 0, 0, 0, 0, 1 };
    static const double offset[LEP_AXES] = { 100, -50, 25, 10, -10, 5 };
    lep_session_options o;
    lep_session *s = open_sim(&o, NULL);
    lep_session_meta m;
    lep_session_health_info h;
    st_batch b;
    double v[LEP_AXES];
    int k;

    st_batch_init(&b, 2);
    lep_session_get_metadata(s, &m);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_read_one_batch(s, &b.b));
    TEST_ASSERT_EQUAL_size_t(1, b.b.n);
    TEST_ASSERT_TRUE(b.t_mono[0] > 0.0 && b.t_utc[0] > 1e9);
    for (k = 0; k < LEP_AXES; k++) {
        TEST_ASSERT_EQUAL_DOUBLE((double)b.raw[k], b.zeroed[k]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, (double)b.raw[k] * (double)m.rated.axis[k] / 10000.0,
                                  b.si[k]);
    }
    TEST_ASSERT_EQUAL_UINT8(0, b.flags[0]);

    /* a tare and a frame: x' = -y, y' = x, z' = z for forces and moments */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_tare(s, offset));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_rotation(s, yaw90, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_read_one_batch(s, &b.b));
    TEST_ASSERT_EQUAL_size_t(2, b.b.n);
    for (k = 0; k < LEP_AXES; k++) {
        double zeroed = (double)b.raw[LEP_AXES + k] - offset[k];
        TEST_ASSERT_EQUAL_DOUBLE(zeroed, b.zeroed[LEP_AXES + k]);
        v[k] = zeroed * (double)m.rated.axis[k] / 10000.0;
    }
    for (k = 0; k < 6; k += 3) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, -v[k + 1], b.si[LEP_AXES + k]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, v[k], b.si[LEP_AXES + k + 1]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, v[k + 2], b.si[LEP_AXES + k + 2]);
    }

    /* a full batch, NULLs; refused while streaming; the health untouched */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_read_one_batch(s, &b.b));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_read_one_batch(s, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_read_one_batch(NULL, &b.b));
    b.b.n = 0;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_session_read_one_batch(s, &b.b));
    TEST_ASSERT_EQUAL_size_t(0, b.b.n);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_stop(s));
    lep_session_get_health(s, &h);
    TEST_ASSERT_EQUAL_UINT64(0, h.delivered);
    lep_session_close(s);
    st_batch_free(&b);
}

/* A full event queue drops its oldest and counts them; none is lost silently. */
static void test_a_full_event_queue_counts_what_it_drops(void)
{
    lep_session_options o;
    lep_session *s = open_sim(&o, NULL);
    lep_session_health_info h;
    lep_session_event ev;
    unsigned i, popped = 0;

    for (i = 0; i < 1030; i++)
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_untare(s)); /* one LEP_EV_TARE each */
    lep_session_get_health(s, &h);
    TEST_ASSERT_EQUAL_UINT64(6, h.events_dropped);
    while (lep_session_pop_event(s, &ev)) {
        TEST_ASSERT_EQUAL_INT(LEP_EV_TARE, ev.type);
        popped++;
    }
    TEST_ASSERT_EQUAL_UINT(1024, popped);
    lep_session_get_health(s, &h);
    TEST_ASSERT_EQUAL_UINT64(6, h.events_dropped);
    /* health counts since start */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    lep_session_get_health(s, &h);
    TEST_ASSERT_EQUAL_UINT64(0, h.events_dropped);
    lep_session_close(s);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_open_start_read_stop);
    RUN_TEST(test_count_and_start_tare_are_exact);
    RUN_TEST(test_duration_counts_from_the_first_delivered_sample);
    RUN_TEST(test_metadata_and_json);
    RUN_TEST(test_bad_options_are_refused_with_a_message);
    RUN_TEST(test_two_sessions_at_once);
    RUN_TEST(test_latency_budget_delivers_the_same_samples);
    RUN_TEST(test_settings_from_another_thread);
    RUN_TEST(test_recording_from_a_session);
    RUN_TEST(test_read_one_uses_the_sessions_processing);
    RUN_TEST(test_a_full_event_queue_counts_what_it_drops);
    return UNITY_END();
}
