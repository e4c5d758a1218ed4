/* lep_record_fill: batch recording from a streaming client, through a real pty. */
#include <string.h>

#include "leptrino/leptrino.h"
#include "leptrino/record.h"
#include "leptrino/serial.h"
#include "leptrino/sim.h"
#include "struct_api.h"
#include "unity.h"

#define CAP 1000u

static lep_sim *sim;
static lep_serial *port;
static lep_client client;
static lep_rated rated;
static double t[CAP];
static double si[CAP * LEP_AXES];
static int16_t raw[CAP * LEP_AXES];
static uint8_t status[CAP];
static uint16_t seq[CAP];
static lep_record_batch batch;

void setUp(void)
{
    lep_sim_options o;
    char err[256];
    lep_sim_options_init(&o);
    o.overload_every_s = 0.2;
    o.overload_duration_s = 0.05;
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_start_so(&o, &sim, err, sizeof(err)), err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK,
                                  lep_serial_open(lep_sim_port(sim), &port, err, sizeof(err)), err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_serial_client_init(&client, port));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 30, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    memset(&batch, 0, sizeof(batch));
    batch.cap = CAP;
    batch.t = t;
    batch.si = si;
    batch.raw = raw;
    batch.status = status;
    batch.seq = seq;
}

void tearDown(void)
{
    lep_serial_close(port);
    lep_sim_stop(sim);
}

static void test_not_streaming_is_a_state_error(void)
{
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_record_fill_batch(&client, &rated, &batch, 0, 100));
    TEST_ASSERT_EQUAL_size_t(0, batch.n);
}

static void test_bad_arguments(void)
{
    lep_record_batch b = batch;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_record_fill_batch(NULL, &rated, &b, 0, 100));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG,
                          lep_record_fill_batch(&client, NULL, &b, 0, 100)); /* si needs rated */
    b.t = NULL;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_record_fill_batch(&client, &rated, &b, 0, 100));
    b = batch;
    b.n = b.cap + 1;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_record_fill_batch(&client, &rated, &b, 0, 100));
}

static void test_fills_every_column_in_order(void)
{
    size_t i;
    size_t a;
    size_t overloads = 0;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    /* Two calls: the second appends where the first stopped. */
    batch.cap = CAP / 2;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_record_fill_batch(&client, &rated, &batch, 0, 500));
    TEST_ASSERT_EQUAL_size_t(CAP / 2, batch.n);
    batch.cap = CAP;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_record_fill_batch(&client, &rated, &batch, 0, 500));
    TEST_ASSERT_EQUAL_size_t(CAP, batch.n);
    for (i = 0; i < CAP; i++) {
        if (i > 0) {
            TEST_ASSERT_EQUAL_UINT16((uint16_t)(seq[i - 1] + 1u), seq[i]); /* no loss */
            TEST_ASSERT_TRUE(t[i] >= t[i - 1]);
        }
        for (a = 0; a < LEP_AXES; a++) {
            double want = (double)raw[i * LEP_AXES + a] * (double)rated.axis[a] / 10000.0;
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, want, si[i * LEP_AXES + a]);
        }
        overloads += (status[i] & LEP_STATUS_OVERLOAD) != 0u;
    }
    TEST_ASSERT_TRUE(overloads > 0);
    /* 1000 samples at 1200 Hz take about 0.83 s of host time. */
    TEST_ASSERT_DOUBLE_WITHIN(0.5, 0.83, t[CAP - 1] - t[0]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
}

static void test_stops_at_the_deadline(void)
{
    double start;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    start = lep_monotonic_seconds();
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_record_fill_batch(&client, &rated, &batch, start + 0.25, 500));
    /* stopped at the deadline: a fill that ran on would fill all CAP (0.83 s
     * of samples); the time bound only catches a hang, not a loaded machine */
    TEST_ASSERT_TRUE(batch.n > 100 && batch.n < CAP);
    TEST_ASSERT_TRUE(lep_monotonic_seconds() - start < 5.0);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
}

static void test_optional_columns_and_disconnect(void)
{
    lep_record_batch b;
    memset(&b, 0, sizeof(b));
    b.cap = CAP;
    b.t = t;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_record_fill_batch(&client, NULL, &b, lep_monotonic_seconds() + 0.1, 500));
    TEST_ASSERT_TRUE(b.n > 0);
    lep_sim_hangup(sim);
    b.n = 0;
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, lep_record_fill_batch(&client, NULL, &b, 0, 500));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_not_streaming_is_a_state_error);
    RUN_TEST(test_bad_arguments);
    RUN_TEST(test_fills_every_column_in_order);
    RUN_TEST(test_stops_at_the_deadline);
    RUN_TEST(test_optional_columns_and_disconnect);
    return UNITY_END();
}
