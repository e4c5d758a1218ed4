/* The session's processing against the virtual sensor: tare while streaming
 * (exact offsets, before/after), un-tare and set, the host low-pass's step
 * response against the analog Butterworth, rotation and moment-point shift,
 * decimation. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "leptrino/error.h"
#include "leptrino/session.h"
#include "session_test.h"
#include "struct_api.h"
#include "unity.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static char replay[64];

void setUp(void)
{
}

void tearDown(void)
{
}

/* Read until b holds want samples (or the session ends). */
static void read_until(lep_session *s, st_batch *b, size_t want)
{
    while (b->b.n < want) {
        int rc = lep_session_read_batch(s, &b->b, 3000);
        if (rc == LEP_E_END)
            break;
        TEST_ASSERT_EQUAL_INT(LEP_OK, rc);
    }
}

static void test_tare_while_streaming_is_exact_and_never_stalls(void)
{
    lep_session_options o;
    lep_session *s = open_sim(&o, NULL);
    st_batch b;
    lep_session_event ev;
    lep_rated rated;
    lep_session_meta m;
    double sum[LEP_AXES] = { 0 }, off[LEP_AXES];
    size_t i, first_taring = 0, n_taring = 0, start;
    int k;

    lep_session_get_metadata(s, &m);
    rated = m.rated;
    st_batch_init(&b, 3000);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    read_until(s, &b, 100);
    /* before any tare: zeroed is raw, SI is raw x rated / 10000 */
    for (i = 0; i < b.b.n; i++)
        for (k = 0; k < LEP_AXES; k++) {
            double z = b.zeroed[i * 6 + (size_t)k];
            TEST_ASSERT_EQUAL_DOUBLE((double)b.raw[i * 6 + (size_t)k], z);
            TEST_ASSERT_EQUAL_DOUBLE(z * (double)rated.axis[k] / 10000.0, b.si[i * 6 + (size_t)k]);
        }
    start = b.b.n;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_tare(s, 50, 0.0));
    TEST_ASSERT_TRUE(lep_session_taring(s));
    read_until(s, &b, start + 200);
    TEST_ASSERT_FALSE(lep_session_taring(s));
    /* the 50 samples averaged are delivered (flagged), with the old offset */
    for (i = start; i < b.b.n; i++) {
        if (b.flags[i] & LEP_SF_TARING) {
            if (n_taring == 0)
                first_taring = i;
            n_taring++;
            for (k = 0; k < LEP_AXES; k++) {
                sum[k] += (double)b.raw[i * 6 + (size_t)k];
                TEST_ASSERT_EQUAL_DOUBLE((double)b.raw[i * 6 + (size_t)k],
                                         b.zeroed[i * 6 + (size_t)k]);
            }
        }
    }
    TEST_ASSERT_EQUAL_size_t(50, n_taring);
    /* no hole in the stream while taring */
    for (i = 1; i < b.b.n; i++)
        TEST_ASSERT_EQUAL_UINT16((uint16_t)(b.seq[i - 1] + 1u), b.seq[i]);
    TEST_ASSERT_TRUE(lep_session_get_tare(s, off));
    for (k = 0; k < LEP_AXES; k++)
        TEST_ASSERT_EQUAL_DOUBLE(sum[k] / 50.0, off[k]); /* the exact mean, not rounded */
    /* after: zeroed = raw - mean exactly, SI from it */
    for (i = first_taring + 50; i < b.b.n; i++)
        for (k = 0; k < LEP_AXES; k++) {
            double z = (double)b.raw[i * 6 + (size_t)k] - off[k];
            TEST_ASSERT_EQUAL_DOUBLE(z, b.zeroed[i * 6 + (size_t)k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, z * (double)rated.axis[k] / 10000.0,
                                      b.si[i * 6 + (size_t)k]);
        }
    TEST_ASSERT_TRUE(lep_session_pop_event(s, &ev));
    TEST_ASSERT_EQUAL_INT(LEP_EV_TARE, ev.type);
    TEST_ASSERT_EQUAL_UINT64(first_taring + 50, ev.sample); /* the first sample it applies to */
    for (k = 0; k < LEP_AXES; k++)
        TEST_ASSERT_EQUAL_DOUBLE(off[k], ev.tare[k]);

    /* un-tare: zeroed is raw again, an event with zero offsets */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_untare(s));
    TEST_ASSERT_FALSE(lep_session_get_tare(s, off));
    TEST_ASSERT_TRUE(lep_session_pop_event(s, &ev));
    TEST_ASSERT_EQUAL_INT(LEP_EV_TARE, ev.type);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, ev.tare[0]);
    start = b.b.n;
    read_until(s, &b, start + 50);
    for (i = start; i < b.b.n; i++)
        TEST_ASSERT_EQUAL_DOUBLE((double)b.raw[i * 6], b.zeroed[i * 6]);

    /* set offsets explicitly */
    {
        const double set[LEP_AXES] = { 100.5, -200.25, 0.0, 1.0, 2.0, 3.0 };
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_tare(s, set));
        start = b.b.n;
        read_until(s, &b, start + 50);
        for (i = start; i < b.b.n; i++)
            for (k = 0; k < LEP_AXES; k++)
                TEST_ASSERT_EQUAL_DOUBLE((double)b.raw[i * 6 + (size_t)k] - set[k],
                                         b.zeroed[i * 6 + (size_t)k]);
    }

    /* by duration: every sample of 0.1 s is averaged */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_tare(s, 0, 0.1));
    start = b.b.n;
    read_until(s, &b, start + 400);
    memset(sum, 0, sizeof sum);
    n_taring = 0;
    for (i = start; i < b.b.n; i++)
        if (b.flags[i] & LEP_SF_TARING) {
            n_taring++;
            for (k = 0; k < LEP_AXES; k++)
                sum[k] += (double)b.raw[i * 6 + (size_t)k];
        }
    TEST_ASSERT_UINT_WITHIN(100, 120, n_taring); /* about 0.1 s of samples */
    TEST_ASSERT_TRUE(lep_session_get_tare(s, off));
    for (k = 0; k < LEP_AXES; k++)
        TEST_ASSERT_EQUAL_DOUBLE(sum[k] / (double)n_taring, off[k]);

    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_tare(s, 0, 0.0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_tare(s, 0, NAN));
    lep_session_close(s);
    st_batch_free(&b);
}

/* Analog 2nd-order Butterworth step response at t seconds. */
static double butter_step(double fc, double t)
{
    double wn = 2.0 * M_PI * fc, z = 1.0 / sqrt(2.0), wd = wn * sqrt(1.0 - z * z);
    if (t <= 0.0)
        return 0.0;
    return 1.0 - exp(-z * wn * t) * (cos(wd * t) + z / sqrt(1.0 - z * z) * sin(wd * t));
}

static void test_lowpass_step_response_is_a_butterworth(void)
{
    lep_session_options o;
    lep_session *s;
    lep_session_meta m;
    st_batch b;
    FILE *f;
    size_t i, step = 0;
    int row;
    const double fc = 20.0, fs = 1200.0, level = 1000.0;
    double scale;

    /* 400 rows: 200 at zero, then a step of 1000 counts on Fz (row = sequence % 400) */
    snprintf(replay, sizeof replay, "/tmp/lep-step-%ld.csv", (long)getpid());
    f = fopen(replay, "w");
    TEST_ASSERT_NOT_NULL(f);
    for (row = 0; row < 400; row++)
        fprintf(f, "0,0,%d,0,0,0\n", row < 200 ? 0 : (int)level);
    fclose(f);
    lep_session_options_init(&o);
    snprintf(o.sim.replay_csv, sizeof o.sim.replay_csv, "%s", replay);
    o.lowpass_hz = fc;
    s = open_sim(&o, &o);
    lep_session_get_metadata(s, &m);
    TEST_ASSERT_EQUAL_DOUBLE(fc, m.lowpass_hz);
    TEST_ASSERT_EQUAL_STRING("2nd-order Butterworth (bilinear, prewarped)", m.lowpass_name);
    /* group delay at 0 Hz of the analog prototype: sqrt(2) / (2 pi fc) */
    TEST_ASSERT_DOUBLE_WITHIN(0.02 * sqrt(2.0) / (2.0 * M_PI * fc), sqrt(2.0) / (2.0 * M_PI * fc),
                              m.lowpass_delay_s);
    scale = (double)m.rated.axis[LEP_FZ] / 10000.0;
    st_batch_init(&b, 800);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    read_until(s, &b, 800);
    /* the first samples are flagged while the filter settles (1/fc s) */
    TEST_ASSERT_TRUE(b.flags[0] & LEP_SF_SETTLING);
    TEST_ASSERT_FALSE(b.flags[100] & LEP_SF_SETTLING);
    for (i = 0; i < b.b.n; i++)
        if (b.seq[i] == 200) {
            step = i;
            break;
        }
    TEST_ASSERT_EQUAL_size_t(200, step); /* no sample lost before it */
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, b.si[(step - 1) * 6 + LEP_FZ]);
    for (i = step; i < step + 200; i++) {
        /* the bilinear transform's response lies within half a sample of
         * the analog one: between y(mT) and y((m+1)T), +/- 0.5 % */
        double m0 = (double)(i - step), y = b.si[i * 6 + LEP_FZ] / (level * scale);
        double lo = butter_step(fc, m0 / fs), hi = butter_step(fc, (m0 + 1.0) / fs);
        if (lo > hi) {
            double t = lo;
            lo = hi;
            hi = t;
        }
        TEST_ASSERT_TRUE_MESSAGE(y >= lo - 0.005 && y <= hi + 0.005,
                                 "step response off the Butterworth");
        /* the raw and zeroed columns are not filtered */
        TEST_ASSERT_EQUAL_DOUBLE(level, b.zeroed[i * 6 + LEP_FZ]);
    }
    /* overshoot of a 2nd-order Butterworth: 4.3 % */
    {
        double peak = 0.0;
        for (i = step; i < step + 200; i++)
            if (b.si[i * 6 + LEP_FZ] > peak)
                peak = b.si[i * 6 + LEP_FZ];
        TEST_ASSERT_DOUBLE_WITHIN(0.005, 1.0432, peak / (level * scale));
    }
    /* off again: SI follows the raw counts at once */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_lowpass(s, 0.0));
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_session_set_lowpass(s, 600.0));
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_session_set_lowpass(s, -1.0));
    b.b.n = 0;
    read_until(s, &b, 800); /* samples already received when it changed may be filtered */
    for (i = 700; i < b.b.n; i++)
        TEST_ASSERT_EQUAL_DOUBLE(b.zeroed[i * 6 + LEP_FZ] * scale, b.si[i * 6 + LEP_FZ]);
    lep_session_close(s);
    st_batch_free(&b);
    (void)unlink(replay);
}

static void test_rotation_and_moment_point(void)
{
    lep_session_options o;
    lep_session *s;
    lep_session_meta m;
    st_batch b;
    double r[9];
    const double p[3] = { 0.01, -0.02, 0.1 };
    size_t i;
    int k;

    lep_rotation_from_rpy(0.0, 0.0, M_PI / 2.0, r); /* yaw 90 deg: x -> y */
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 0.0, r[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, -1.0, r[1]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1.0, r[3]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1.0, r[8]);
    lep_session_options_init(&o);
    memcpy(o.rotation, r, sizeof r);
    memcpy(o.shift_m, p, sizeof p);
    s = open_sim(&o, &o);
    lep_session_get_metadata(s, &m);
    st_batch_init(&b, 300);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    read_until(s, &b, 300);
    for (i = 0; i < b.b.n; i++) {
        double v[LEP_AXES], f[3], mm[3];
        for (k = 0; k < LEP_AXES; k++)
            v[k] = b.zeroed[i * 6 + (size_t)k] * (double)m.rated.axis[k] / 10000.0;
        /* yaw 90: f' = (-fy, fx, fz), m' = (-my, mx, mz) - p x f' */
        f[0] = -v[1];
        f[1] = v[0];
        f[2] = v[2];
        mm[0] = -v[4] - (p[1] * f[2] - p[2] * f[1]);
        mm[1] = v[3] - (p[2] * f[0] - p[0] * f[2]);
        mm[2] = v[5] - (p[0] * f[1] - p[1] * f[0]);
        for (k = 0; k < 3; k++) {
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, f[k], b.si[i * 6 + (size_t)k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, mm[k], b.si[i * 6 + 3 + (size_t)k]);
        }
    }
    /* a matrix that is not a rotation is refused; NULL means identity */
    r[0] = 1.5;
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_session_set_rotation(s, r, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_rotation(s, NULL, NULL));
    /* samples already received when it changed may carry the old frame */
    b.b.n = 0;
    read_until(s, &b, 300);
    for (i = 250; i < b.b.n; i++)
        TEST_ASSERT_EQUAL_DOUBLE(b.zeroed[i * 6] * (double)m.rated.axis[0] / 10000.0, b.si[i * 6]);
    lep_session_close(s);
    st_batch_free(&b);
}

static void test_decimation_keeps_every_nth(void)
{
    lep_session_options o;
    lep_session *s;
    st_batch b;
    size_t i;
    lep_session_options_init(&o);
    o.decimate = 4;
    o.count = 100;
    o.lowpass_hz = 100.0;
    s = open_sim(&o, &o);
    st_batch_init(&b, 200);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    read_until(s, &b, 200);
    TEST_ASSERT_EQUAL_size_t(100, b.b.n); /* count is of delivered samples */
    for (i = 0; i < b.b.n; i++)
        TEST_ASSERT_EQUAL_UINT16((uint16_t)(4u * i), b.seq[i]);
    lep_session_close(s);
    st_batch_free(&b);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_tare_while_streaming_is_exact_and_never_stalls);
    RUN_TEST(test_lowpass_step_response_is_a_butterworth);
    RUN_TEST(test_rotation_and_moment_point);
    RUN_TEST(test_decimation_keeps_every_nth);
    return UNITY_END();
}
