/* The virtual sensor's filter: the FIR a filter code selects shapes the data
 * once a power cycle applies it (step response, noise reduction), and every
 * streamed sample equals lep_sim_stream_sample for its sequence number. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "leptrino/leptrino.h"
#include "leptrino/serial.h"
#include "leptrino/sim.h"
#include "struct_api.h"
#include "unity.h"

static lep_sim *sim;
static lep_serial *port;
static lep_client client;
static char err[256];
static char replay[64];

void setUp(void)
{
    sim = NULL;
    port = NULL;
    replay[0] = '\0';
}

void tearDown(void)
{
    lep_serial_close(port);
    lep_sim_stop(sim);
    if (replay[0] != '\0')
        (void)unlink(replay);
}

static void start(const lep_sim_options *o)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_start_so(o, &sim, err, sizeof err), err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK,
                                  lep_serial_open(lep_sim_port(sim), &port, err, sizeof err), err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_serial_client_init(&client, port));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_timeout(&client, 2000));
}

/* Stream n samples, then check each one delivered against
 * lep_sim_stream_sample for its sequence number (after the stream, so a slow
 * machine only makes gaps, which are fine here). Then the figures below come
 * from lep_sim_stream_sample alone: the same bits, no timing. */
static void stream_and_check(unsigned n, uint8_t filter)
{
    static lep_sample got[4096];
    unsigned i;
    TEST_ASSERT_TRUE(n <= 4096);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    for (i = 0; i < n; i++)
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &got[i], 2000));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    for (i = 0; i < n; i++) {
        lep_sample want;
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_sample_at(sim, got[i].reserved, filter, &want));
        TEST_ASSERT_EQUAL_MEMORY(&want, &got[i], sizeof want);
    }
}

/* Samples 0..n-1 of a stream under filter, as sent. */
static void stream(lep_sample *out, unsigned n, uint8_t filter)
{
    unsigned i;
    stream_and_check(n < 600 ? n : 600, filter);
    for (i = 0; i < n; i++)
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_sample_at(sim, i, filter, &out[i]));
}

/* Variance of axis a over samples [from, n). */
static double variance(const lep_sample *s, unsigned from, unsigned n, int a)
{
    double sum = 0, sq = 0, m;
    unsigned i;
    for (i = from; i < n; i++)
        sum += s[i].raw[a];
    m = sum / (double)(n - from);
    for (i = from; i < n; i++)
        sq += (s[i].raw[a] - m) * (s[i].raw[a] - m);
    return sq / (double)(n - from);
}

#define N_NOISE 1200u

/* White noise (uniform, +/-1000 counts: sd 577) through each filter: the sd
 * falls as the square root of the pass band, 2 * cut-off / rate. */
static void test_noise_reduction_per_code(void)
{
    static lep_sample s[N_NOISE];
    /* sd 577 * sqrt(sum of h^2): about 1/sqrt(2 fc / 1200 * 0.7) smaller
     * (the Blackman window narrows the noise band of the ideal low-pass):
     * 10 Hz 72, 100 Hz 199, 200 Hz 280; bounds allow the noise of 1200 samples */
    static const double lo[4] = { 530, 58, 170, 240 }, hi[4] = { 625, 88, 230, 320 };
    uint8_t code;
    for (code = 0; code <= 3; code++) {
        lep_sim_options o;
        char msg[96];
        double var;
        lep_sim_options_init(&o);
        o.amplitude = 0.0;
        o.noise = 0.1;
        o.filter = code;
        start(&o);
        stream(s, N_NOISE, code);
        var = variance(s, 0, N_NOISE, LEP_FX);
        snprintf(msg, sizeof msg, "filter %u: variance %.0f counts^2", (unsigned)code, var);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(var > lo[code] * lo[code] && var < hi[code] * hi[code], msg);
        lep_serial_close(port);
        port = NULL;
        lep_sim_stop(sim);
        sim = NULL;
    }
}

/* A step from 0 to 10000 counts at sample 400 (replayed): off, it is a step;
 * with the 10 Hz FIR (241 taps at 1200 Hz, linear phase) the output rises
 * from sample 400, is half way 120 samples later (the group delay) and
 * reaches 10000 when the step has passed all taps (sample 640). */
static void test_step_response(void)
{
    static lep_sample s[1000];
    lep_sim_options o;
    FILE *f;
    unsigned i;
    snprintf(replay, sizeof replay, "/tmp/lep-step-%ld.csv", (long)getpid());
    f = fopen(replay, "w");
    TEST_ASSERT_NOT_NULL(f);
    for (i = 0; i < 1000; i++)
        fprintf(f, "%d,0,0,0,0,0\n", i < 400 ? 0 : 10000);
    fclose(f);
    lep_sim_options_init(&o);
    snprintf(o.replay_csv, sizeof o.replay_csv, "%s", replay);
    start(&o);
    stream(s, 1000, 0);
    TEST_ASSERT_EQUAL_INT16(0, s[399].raw[LEP_FX]);
    TEST_ASSERT_EQUAL_INT16(10000, s[400].raw[LEP_FX]);

    /* set the filter: nothing changes until the power cycle */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_set(&client, 1));
    stream(s, 1000, 0);
    TEST_ASSERT_EQUAL_INT16(10000, s[400].raw[LEP_FX]);
    lep_sim_power_cycle(sim);
    {
        lep_sim_counters st;
        for (i = 0; i < 2000; i++) { /* 20 s bound the wait */
            lep_sim_get_stats(sim, &st);
            if (st.filter == 1)
                break;
            usleep(10000);
        }
        TEST_ASSERT_EQUAL_UINT8(1, st.filter);
    }
    stream(s, 1000, 1);
    for (i = 0; i < 400; i++) /* causal: nothing before the step */
        TEST_ASSERT_EQUAL_INT16(0, s[i].raw[LEP_FX]);
    /* half way at the group delay, 120 samples: symmetric around it */
    TEST_ASSERT_TRUE(s[519].raw[LEP_FX] < 5000 && s[520].raw[LEP_FX] > 5000);
    TEST_ASSERT_INT_WITHIN(1, 10000, s[519].raw[LEP_FX] + s[520].raw[LEP_FX]);
    TEST_ASSERT_TRUE(s[480].raw[LEP_FX] > 0 && s[480].raw[LEP_FX] < 5000);
    TEST_ASSERT_TRUE(s[560].raw[LEP_FX] > 5000 && s[560].raw[LEP_FX] < 10000);
    for (i = 400 + 240; i < 1000; i++) /* the step has passed all 241 taps */
        TEST_ASSERT_EQUAL_INT16(10000, s[i].raw[LEP_FX]);
    for (i = 0; i < 1000; i++) { /* the design's overshoot: 1.4 % of the step */
        char msg[64];
        snprintf(msg, sizeof msg, "sample %u: %d", i, s[i].raw[LEP_FX]);
        TEST_ASSERT_TRUE_MESSAGE(s[i].raw[LEP_FX] >= -140 && s[i].raw[LEP_FX] <= 10140, msg);
    }
}

/* A constant load passes every filter unchanged (unity gain at 0 Hz). */
static void test_constant_passes(void)
{
    static lep_sample s[300];
    lep_sim_options o;
    unsigned i;
    lep_sim_options_init(&o);
    o.constant = true;
    o.amplitude = 0.5;
    o.filter = 1;
    start(&o);
    stream(s, 300, 1);
    for (i = 0; i < 300; i++)
        TEST_ASSERT_EQUAL_INT16(5000, s[i].raw[LEP_MZ]);
}

static void test_stream_sample_arguments(void)
{
    lep_sim_options o;
    lep_sample smp;
    lep_sim_options_init(&o);
    start(&o);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_sample_at(sim, 0, 4, &smp));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_sample_at(NULL, 0, 0, &smp));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_sample_at(sim, 0, 0, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_sample_at(sim, 70000, 0, &smp));
    TEST_ASSERT_EQUAL_UINT16(70000 - 65536, smp.reserved);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_noise_reduction_per_code);
    RUN_TEST(test_step_response);
    RUN_TEST(test_constant_passes);
    RUN_TEST(test_stream_sample_arguments);
    return UNITY_END();
}
