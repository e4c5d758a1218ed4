/* The session's payload compensation and limits against the in-process
 * virtual sensor: a payload identified at four orientations, compensated at a
 * fifth; a tare with a payload set; limits during the virtual sensor's
 * overload episodes; the metadata; the setters' refusals. */
#define _DEFAULT_SOURCE

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "leptrino/error.h"
#include "leptrino/payload.h"
#include "leptrino/session.h"
#include "leptrino/sim.h"
#include "session_test.h"
#include "struct_api.h"
#include "unity.h"

#define G0 LEP_STANDARD_GRAVITY
#define TOOL "1.3,0.015,-0.01,0.07"

static char err[256];
static const lep_payload tool = { 1.3, { 0.015, -0.01, 0.07 } };

void setUp(void)
{
    err[0] = '\0';
}

void tearDown(void)
{
}

/* Session options: the virtual sensor carrying the tool at gravity g, no
 * waveform, noise as given (a fraction of rated), a constant bias. */
static void sim_options(lep_session_options *o, const double g[3], const char *noise)
{
    char text[96];
    lep_session_options_init(o);
    o->use_sim = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_set(&o->sim, "amplitude", "0", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_set(&o->sim, "noise", noise, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_set(&o->sim, "payload", TOOL, err, sizeof err));
    snprintf(text, sizeof text, "%.17g,%.17g,%.17g", g[0], g[1], g[2]);
    TEST_ASSERT_EQUAL_INT_MESSAGE(
        LEP_OK, lep_sim_option_set(&o->sim, "gravity", text, err, sizeof err), err);
}

/* Read n samples; the mean of SI (and of raw counts) and the SI's RMS
 * deviation from that mean per axis; events into ev (up to evcap), *nev. */
static void read_n(lep_session *s, st_batch *x, size_t n, double mean[6], double mean_raw[6],
                   double rms[6], lep_session_event *ev, size_t evcap, size_t *nev)
{
    size_t i, cap = x->b.cap;
    int k;
    if (nev != NULL)
        *nev = 0;
    TEST_ASSERT_TRUE(n <= cap);
    x->b.cap = n; /* exactly n: the rest stays queued for the next read */
    x->b.n = 0;
    while (x->b.n < n) {
        lep_session_event e;
        int rc = lep_session_read_batch(s, &x->b, 1000);
        TEST_ASSERT_TRUE_MESSAGE(rc == LEP_OK || rc == LEP_E_END, lep_strerror(rc));
        while (lep_session_pop_event(s, &e))
            if (nev != NULL && *nev < evcap)
                ev[(*nev)++] = e;
        if (rc == LEP_E_END)
            break;
    }
    x->b.cap = cap;
    TEST_ASSERT_EQUAL_size_t(n, x->b.n);
    for (k = 0; k < 6; k++) {
        double sum = 0, sumr = 0, sq = 0;
        for (i = 0; i < n; i++) {
            sum += x->si[i * 6 + (size_t)k];
            sumr += x->raw[i * 6 + (size_t)k];
        }
        mean[k] = sum / (double)n;
        if (mean_raw != NULL)
            mean_raw[k] = sumr / (double)n;
        for (i = 0; i < n; i++) {
            double d = x->si[i * 6 + (size_t)k] - mean[k];
            sq += d * d;
        }
        if (rms != NULL)
            rms[k] = sqrt(sq / (double)n);
    }
}

/* Four orientations identified, a fifth compensated: what is left is the
 * noise (the virtual sensor has no bias), at the noise's own level. */
static void test_identified_then_compensated_at_a_fifth(void)
{
    const double r = G0 / sqrt(2.0);
    double g[5 * 3] = { 0,
                        0,
                        -G0,
                        r,
                        0,
                        -r,
                        0,
                        -r,
                        -r,
                        -r * 0.6,
                        r * 0.5,
                        -r * 0.9,
                        /* the fifth */ 0.3 * G0,
                        0.4 * G0,
                        0.866 * G0 };
    double w[4 * 6], mean[6], raw[6], rms[6], expect[6];
    lep_payload_fit fit;
    lep_rated rated;
    st_batch x;
    int i, k;
    st_batch_init(&x, 1200);
    for (i = 0; i < 4; i++) {
        lep_session_options o;
        lep_session *s;
        sim_options(&o, &g[i * 3], "0.002");
        s = open_sim(&o, &o);
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
        read_n(s, &x, 600, &w[i * 6], NULL, NULL, NULL, 0, NULL);
        lep_session_close(s);
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_payload_identify_fit(g, w, 4, &fit, err, sizeof err),
                                  err);
    TEST_ASSERT_DOUBLE_WITHIN(0.013, tool.mass_kg, fit.payload.mass_kg);
    for (k = 0; k < 3; k++)
        TEST_ASSERT_DOUBLE_WITHIN(0.002, tool.com_m[k], fit.payload.com_m[k]);

    {
        lep_session_options o;
        lep_session *s;
        double before[6];
        sim_options(&o, &g[12], "0.002");
        s = open_sim(&o, &o);
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
        read_n(s, &x, 600, before, NULL, NULL, NULL, 0, NULL);
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_payload(s, &fit.payload));
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_gravity(s, &g[12]));
        read_n(s, &x, 600, mean, raw, rms, NULL, 0, NULL);
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_payload_wrench_p(&tool, &g[12], expect));
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_model_rated_f(o.sim.model, &rated));
        printf("fifth pose: uncompensated fz %.3f N mx %.4f N m; compensated fz %.4f N mx %.5f "
               "N m; noise rms fz %.3f N mx %.4f N m\n",
               before[2], before[3], mean[2], mean[3], rms[2], rms[3]);
        for (k = 0; k < 6; k++) {
            /* before: the tool's weight; after: the mean within the noise of a
             * 600-sample mean (and the identification's error) */
            TEST_ASSERT_DOUBLE_WITHIN(3 * rms[k] + 0.06 * fabs(expect[k]), expect[k], before[k]);
            TEST_ASSERT_DOUBLE_WITHIN(0.5 * rms[k] + 0.01 * fabs(expect[k]), 0.0, mean[k]);
            /* raw counts stay as measured: the tool's weight is in them */
            TEST_ASSERT_DOUBLE_WITHIN(3.0 + 0.01 * fabs(expect[k]) * 10000 / rated.axis[k],
                                      expect[k] * 10000 / rated.axis[k], raw[k]);
        }
        lep_session_close(s);
    }
    st_batch_free(&x);
}

/* Take the rows the session processed already (they were made before what
 * the test changes next): on a loaded machine the reader falls behind, and a
 * change could otherwise show only after more rows than the test reads. */
static void drain(lep_session *s, st_batch *x)
{
    size_t cap = x->b.cap;
    int i, rc = LEP_OK;
    for (i = 0; i < 1000 && rc == LEP_OK; i++) {
        x->b.n = 0;
        rc = lep_session_read_batch(s, &x->b, 0);
    }
    x->b.cap = cap;
    x->b.n = 0;
}

/* A tare with a payload set removes the bias only: the offsets are the bias
 * (the constant level), not the tool; SI reads zero there, and moving the
 * robot (a new gravity) shows the change of the tool's wrench removed. */
static void test_tare_with_a_payload_keeps_the_tool(void)
{
    double g1[3] = { 0, 0, -G0 }, g2[3] = { G0, 0, 0 };
    double off[6], mean[6], w1[6], w2[6];
    lep_session_options o;
    lep_session *s;
    lep_session_event ev[8];
    size_t nev, i;
    lep_rated rated;
    st_batch x;
    int k;
    bool tare_seen = false;
    st_batch_init(&x, 600);
    sim_options(&o, g1, "0");
    /* a bias of 50 counts on every axis, no noise */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_set(&o.sim, "constant", NULL, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_sim_option_set(&o.sim, "amplitude", "0.005", err, sizeof err));
    o.payload = tool;
    memcpy(o.gravity, g1, sizeof g1);
    s = open_sim(&o, &o);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_model_rated_f(o.sim.model, &rated));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_tare(s, 100, 0.0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    read_n(s, &x, 200, mean, NULL, NULL, ev, 8, &nev);
    for (i = 0; i < nev; i++)
        tare_seen = tare_seen || ev[i].type == LEP_EV_TARE;
    TEST_ASSERT_TRUE(tare_seen);
    TEST_ASSERT_TRUE(lep_session_get_tare(s, off));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_payload_wrench_p(&tool, g1, w1));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_payload_wrench_p(&tool, g2, w2));
    for (k = 0; k < 6; k++) {
        /* the bias alone (50 counts), to the rounding of the tool's counts */
        TEST_ASSERT_DOUBLE_WITHIN(0.5, 50.0, off[k]);
        /* after the tare: zero */
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, x.si[150 * 6 + (size_t)k]);
        /* zeroed counts: raw less the bias, the tool's weight still in them */
        TEST_ASSERT_DOUBLE_WITHIN(0.5, w1[k] * 10000 / rated.axis[k],
                                  x.zeroed[150 * 6 + (size_t)k]);
    }
    /* the robot turns (the virtual sensor cannot): SI = w(g1) - w(g2) */
    drain(s, &x);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_gravity(s, g2));
    read_n(s, &x, 100, mean, NULL, NULL, NULL, 0, NULL);
    for (k = 0; k < 6; k++)
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, w1[k] - w2[k], x.si[90 * 6 + (size_t)k]);
    /* without the payload a tare zeroes the tool away: offsets = bias + tool */
    drain(s, &x);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_payload(s, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_tare(s, 50, 0.0));
    read_n(s, &x, 100, mean, NULL, NULL, NULL, 0, NULL);
    TEST_ASSERT_TRUE(lep_session_get_tare(s, off));
    for (k = 0; k < 6; k++)
        TEST_ASSERT_DOUBLE_WITHIN(0.5, 50.0 + w1[k] * 10000 / rated.axis[k], off[k]);
    lep_session_close(s);
    st_batch_free(&x);
}

/* Limits during the virtual sensor's overload episodes: every episode is a
 * limit episode (one exceeded, one cleared, the axis named, the samples
 * flagged, the wrench carried), none outside them. The episodes are 0.05 s
 * of the virtual sensor's sample numbers, so they are checked by sequence
 * number, whatever the timing of the reads. */
static void test_limits_with_overload_episodes(void)
{
    double g[3] = { 0, 0, -G0 }, mean[6];
    double lim[6] = { 100, 100, 100, 2, 2, 2 };
    lep_session_options o;
    lep_session *s;
    lep_session_event ev[64];
    lep_session_health_info h;
    size_t nev, i, exceeded = 0, cleared = 0, overloads = 0, runs = 0, first = 0, checked = 0;
    uint64_t processed, queued;
    st_batch x;
    st_batch_init(&x, 1800);
    sim_options(&o, g, "0.002");
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_sim_option_set(&o.sim, "overload-every", "0.25", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_sim_option_set(&o.sim, "overload-duration", "0.05", err, sizeof err));
    o.payload = tool;
    s = open_sim(&o, &o);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_limits(s, lim));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    read_n(s, &x, 1500, mean, NULL, NULL, ev, 64, &nev);
    TEST_ASSERT_TRUE(nev < 64);
    for (i = 0; i < nev; i++) {
        size_t at = (size_t)ev[i].sample;
        TEST_ASSERT_TRUE(at <= x.b.n); /* returned once the samples before it are read */
        if (at == x.b.n)
            continue; /* it applies to the next sample, not read yet */
        if (ev[i].type == LEP_EV_OVERLOAD_BEGIN)
            overloads++;
        if (ev[i].type == LEP_EV_LIMIT_EXCEEDED) {
            int axis;
            exceeded++;
            TEST_ASSERT_TRUE(ev[i].axes != 0u);
            TEST_ASSERT_TRUE((x.flags[at] & LEP_SF_LIMIT) != 0u);
            TEST_ASSERT_TRUE(at == 0 || (x.flags[at - 1] & LEP_SF_LIMIT) == 0u);
            for (axis = 0; axis < 6; axis++) {
                TEST_ASSERT_EQUAL_DOUBLE(x.si[at * 6 + (size_t)axis], ev[i].wrench[axis]);
                TEST_ASSERT_EQUAL_INT(((unsigned)ev[i].axes >> axis) & 1u,
                                      fabs(ev[i].wrench[axis]) > lim[axis]);
            }
        }
        if (ev[i].type == LEP_EV_LIMIT_CLEARED) {
            cleared++;
            TEST_ASSERT_TRUE((x.flags[at] & LEP_SF_LIMIT) == 0u);
            TEST_ASSERT_TRUE(at > 0 && (x.flags[at - 1] & LEP_SF_LIMIT) != 0u);
        }
    }
    /* Sample by sample, the session's limit is the virtual sensor's overload
     * (4x rated is beyond every limit, the tool's weight within them), and each
     * run of them is one episode: 60 sequence numbers (0.05 s at 1.2 kHz), the
     * samples the virtual sensor skipped under load included. */
    for (i = 0; i < x.b.n; i++) {
        bool limit = (x.flags[i] & LEP_SF_LIMIT) != 0u;
        TEST_ASSERT_EQUAL_INT(limit, (x.flags[i] & LEP_SF_OVERLOAD) != 0u);
        if (limit && (i == 0 || (x.flags[i - 1] & LEP_SF_LIMIT) == 0u))
            first = i;
        if (limit && (i + 1 == x.b.n || (x.flags[i + 1] & LEP_SF_LIMIT) == 0u)) {
            unsigned span = (uint16_t)(x.seq[i] - x.seq[first]) + 1u;
            runs++;
            if (first > 0 && i + 1 < x.b.n) /* whole: begun and ended within the batch */
                TEST_ASSERT_EQUAL_UINT(60, span);
        }
    }
    printf("1500 samples: %zu overload episodes, %zu limit exceeded, %zu cleared, %zu runs of "
           "flagged samples\n",
           overloads, exceeded, cleared, runs);
    TEST_ASSERT_TRUE(overloads >= 4);
    TEST_ASSERT_EQUAL_size_t(overloads, exceeded);
    TEST_ASSERT_EQUAL_size_t(runs, exceeded);
    TEST_ASSERT_TRUE(cleared == exceeded || cleared + 1 == exceeded);
    /* The health counts every episode begun as it is queued: those taken so
     * far, and any of rows processed but not yet returned (none dropped). */
    lep_session_get_health(s, &h);
    for (i = 0, queued = 0; i < nev; i++)
        queued += ev[i].type == LEP_EV_LIMIT_EXCEEDED;
    TEST_ASSERT_EQUAL_UINT64(0, h.events_dropped);
    TEST_ASSERT_TRUE(h.limit_episodes >= queued);
    TEST_ASSERT_TRUE(queued >= exceeded);
    /* No limits: no flags, no events, from the first sample processed after. */
    lep_session_get_health(s, &h);
    TEST_ASSERT_EQUAL_UINT64(1500, h.delivered);
    processed = h.received; /* every sample a row (no tare, no decimation): 1500 read, the
                               rest queued, processed under the limits */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_limits(s, NULL));
    read_n(s, &x, 1800, mean, NULL, NULL, ev, 64, &nev);
    for (i = 0; i < x.b.n; i++) {
        if (1500u + i < processed)
            continue;
        checked++;
        TEST_ASSERT_EQUAL_UINT8(0, x.flags[i] & LEP_SF_LIMIT);
    }
    TEST_ASSERT_TRUE(checked >= 1800 - 16384 / 25); /* one port read (16 KiB) may stay queued */
    for (i = 0; i < nev; i++)
        TEST_ASSERT_TRUE(ev[i].type != LEP_EV_LIMIT_EXCEEDED || ev[i].sample < processed);
    /* none begun without limits: the events taken since are those of rows
     * processed before, and every one is now taken */
    for (i = 0; i < nev; i++)
        queued += ev[i].type == LEP_EV_LIMIT_EXCEEDED;
    lep_session_get_health(s, &h);
    TEST_ASSERT_EQUAL_UINT64(queued, h.limit_episodes);
    lep_session_close(s);
    st_batch_free(&x);
}

/* The --limit text: what is accepted, and refusals that leave the limits as
 * they were. */
static void test_limits_parse(void)
{
    static const char *const bad[] = { "",      "fz",     "fz=",        "fz=0",
                                       "fz=-1", "fz=nan", "fz=inf",     "fz=1e999",
                                       "fq=3",  "fz=5,",  "fz=5;mz=2",  "fz=5 ",
                                       "Fz=5",  ",fz=5",  "fz=5,,mz=2", "fz=5,mz=2,fz=6" };
    double lim[6] = { 1, 2, 3, 4, 5, 6 };
    size_t i;
    int k;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_limits_parse("fz=50,mz=2", lim));
    for (k = 0; k < 6; k++)
        TEST_ASSERT_EQUAL_DOUBLE(k == 2 ? 50.0 : k == 5 ? 2.0 : 0.0, lim[k]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_limits_parse("fy=2e1,fz=3,mx=4,my=5,mz=6,fx=7", lim));
    TEST_ASSERT_EQUAL_DOUBLE(7.0, lim[0]);
    TEST_ASSERT_EQUAL_DOUBLE(20.0, lim[1]);
    TEST_ASSERT_EQUAL_DOUBLE(6.0, lim[5]);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_E_ARG, lep_limits_parse(bad[i], lim), bad[i]);
        TEST_ASSERT_EQUAL_DOUBLE(7.0, lim[0]);
        TEST_ASSERT_EQUAL_DOUBLE(6.0, lim[5]);
    }
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_limits_parse(NULL, lim));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_limits_parse("fz=1", NULL));
}

/* Several --limit texts: the axes add up, an axis limited twice is refused
 * and the limits stay as they were. */
static void test_limits_add_merges_texts(void)
{
    double lim[6] = { 0 }, bad[6] = { 0, 0, -1, 0, 0, 0 }, inf[6] = { 0, 0, INFINITY, 0, 0, 0 };
    int k;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_limits_add("fz=50", lim));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_limits_add("mz=2,fx=7", lim));
    for (k = 0; k < 6; k++)
        TEST_ASSERT_EQUAL_DOUBLE(k == 0 ? 7.0 : k == 2 ? 50.0 : k == 5 ? 2.0 : 0.0, lim[k]);
    /* fz again, alone or beside a new axis: refused whole (my not added) */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_limits_add("fz=60", lim));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_limits_add("my=1,fz=60", lim));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_limits_add("my=1,my=2", lim));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_limits_add("my=x", lim));
    for (k = 0; k < 6; k++)
        TEST_ASSERT_EQUAL_DOUBLE(k == 0 ? 7.0 : k == 2 ? 50.0 : k == 5 ? 2.0 : 0.0, lim[k]);
    /* what the limits hold must be limits */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_limits_add("fx=1", bad));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_limits_add("fx=1", inf));
    TEST_ASSERT_EQUAL_DOUBLE(0.0, bad[0]);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_limits_add(NULL, lim));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_limits_add("fz=1", NULL));
}

static void test_metadata_and_refusals(void)
{
    double g[3] = { 0, 0, -G0 }, bad3[3] = { 0, NAN, 0 };
    double lim[6] = { 0, 0, 50, 0, 0, 2 };
    lep_payload neg = { -1.0, { 0, 0, 0 } }, inf = { 1.0, { 0, INFINITY, 0 } };
    lep_session_options o;
    lep_session *s;
    lep_session_meta m;
    char json[4096];
    size_t len;
    sim_options(&o, g, "0.002");
    o.limit[1] = -1.0;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_open_so(&o, &s, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "limit fy -1"), err);
    o.limit[1] = 0.0;
    o.payload = neg;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_open_so(&o, &s, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "payload"), err);
    o.payload = tool;
    o.gravity[0] = 1.0;
    memcpy(o.limit, lim, sizeof lim);
    s = open_sim(&o, &o);
    lep_session_get_metadata(s, &m);
    TEST_ASSERT_EQUAL_DOUBLE(1.3, m.payload.mass_kg);
    TEST_ASSERT_EQUAL_DOUBLE(1.0, m.gravity[0]);
    TEST_ASSERT_EQUAL_DOUBLE(50.0, m.limit[2]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_metadata_json(s, json, sizeof json, &len));
    TEST_ASSERT_NOT_NULL_MESSAGE(
        strstr(json, "\"payload\":{\"mass_kg\":1.3,\"com_m\":[0.015,-0.01,0.07]},"
                     "\"gravity\":[1,0,-9.80665],\"limit\":[0,0,50,0,0,2]"),
        json);
    /* refusals change nothing */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_set_payload(s, &neg));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_set_payload(s, &inf));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_set_gravity(s, bad3));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_set_gravity(s, NULL));
    lim[0] = NAN;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_set_limits(s, lim));
    lim[0] = -3;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_set_limits(s, lim));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_set_payload(NULL, &tool));
    lep_session_get_metadata(s, &m);
    TEST_ASSERT_EQUAL_DOUBLE(1.3, m.payload.mass_kg);
    TEST_ASSERT_EQUAL_DOUBLE(1.0, m.gravity[0]);
    TEST_ASSERT_EQUAL_DOUBLE(50.0, m.limit[2]);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, m.limit[0]);
    /* none: null in the metadata */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_set_payload(s, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_metadata_json(s, json, sizeof json, &len));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(json, "\"payload\":null,"), json);
    lep_session_close(s);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_identified_then_compensated_at_a_fifth);
    RUN_TEST(test_tare_with_a_payload_keeps_the_tool);
    RUN_TEST(test_limits_with_overload_episodes);
    RUN_TEST(test_limits_parse);
    RUN_TEST(test_limits_add_merges_texts);
    RUN_TEST(test_metadata_and_refusals);
    return UNITY_END();
}
