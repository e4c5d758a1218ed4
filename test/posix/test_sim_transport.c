/* The virtual sensor's transport rule (sim_transport.h), from given times:
 * no clock, no pty, no threads. Times are ns; T is an arbitrary origin on a
 * frame boundary, M one millisecond (a USB full-speed frame). */
#include <string.h>

#include "host/sim/sim_transport.h"
#include "unity.h"

#define M 1000000LL
#define T (1000LL * M)

static sim_transport tr;

void setUp(void)
{
}

void tearDown(void)
{
}

static void in_at(double ms, size_t n)
{
    lep_priv_sim_transport_in(&tr, T + (int64_t)(ms * (double)M), n);
}

/* Advance to T + ms; the bytes the port may take then. */
static size_t ready_at(double ms)
{
    lep_priv_sim_transport_advance(&tr, T + (int64_t)(ms * (double)M));
    return lep_priv_sim_transport_ready(&tr);
}

static void test_none_releases_at_once(void)
{
    lep_priv_sim_transport_init(&tr, SIM_TRANSPORT_NONE, 0);
    in_at(0.3, 25);
    TEST_ASSERT_EQUAL_size_t(25, lep_priv_sim_transport_ready(&tr));
    TEST_ASSERT_EQUAL_INT64(0, lep_priv_sim_transport_next(&tr));
    lep_priv_sim_transport_written(&tr, 10);
    TEST_ASSERT_EQUAL_size_t(15, lep_priv_sim_transport_ready(&tr));
}

static void test_usb_releases_at_frame_boundaries(void)
{
    lep_priv_sim_transport_init(&tr, SIM_TRANSPORT_USB, 0);
    TEST_ASSERT_EQUAL_size_t(0, ready_at(0.0));
    in_at(0.2, 25);
    in_at(0.9, 25);
    TEST_ASSERT_EQUAL_INT64(T + M, lep_priv_sim_transport_next(&tr));
    TEST_ASSERT_EQUAL_size_t(0, ready_at(0.95));
    /* everything written since the previous frame arrives together */
    TEST_ASSERT_EQUAL_size_t(50, ready_at(1.0));
    TEST_ASSERT_EQUAL_INT64(0, lep_priv_sim_transport_next(&tr));
    in_at(1.7, 25);
    TEST_ASSERT_EQUAL_INT64(T + 2 * M, lep_priv_sim_transport_next(&tr));
    /* looked at late: the frame at 2 ms has passed, the bytes are out */
    TEST_ASSERT_EQUAL_size_t(75, ready_at(2.6));
    lep_priv_sim_transport_written(&tr, 75);
    TEST_ASSERT_EQUAL_size_t(0, lep_priv_sim_transport_ready(&tr));
    /* a byte at a boundary goes with it; one after, at the next */
    in_at(3.0, 1);
    in_at(3.1, 1);
    TEST_ASSERT_EQUAL_size_t(1, ready_at(3.05));
    TEST_ASSERT_EQUAL_size_t(2, ready_at(4.0));
}

static void test_usb_bytes_made_late_go_at_the_next_frame(void)
{
    lep_priv_sim_transport_init(&tr, SIM_TRANSPORT_USB, 0);
    TEST_ASSERT_EQUAL_size_t(0, ready_at(5.5));
    /* due at 4.8 ms (made late): the frames up to 5 ms are done, so the
     * next one, at 6 ms */
    in_at(4.8, 25);
    TEST_ASSERT_EQUAL_INT64(T + 6 * M, lep_priv_sim_transport_next(&tr));
    TEST_ASSERT_EQUAL_size_t(0, ready_at(5.9));
    TEST_ASSERT_EQUAL_size_t(25, ready_at(6.0));
}

static void test_usb_fifo_nothing_overtakes(void)
{
    lep_priv_sim_transport_init(&tr, SIM_TRANSPORT_USB, 0);
    TEST_ASSERT_EQUAL_size_t(0, ready_at(0.0));
    in_at(1.5, 10);
    in_at(0.5, 10); /* earlier than the bytes before it: goes with them */
    TEST_ASSERT_EQUAL_size_t(0, ready_at(1.0));
    TEST_ASSERT_EQUAL_size_t(20, ready_at(2.0));
}

static void test_ftdi_timer_sends_what_it_holds(void)
{
    lep_priv_sim_transport_init(&tr, SIM_TRANSPORT_FTDI, 16);
    TEST_ASSERT_EQUAL_size_t(0, ready_at(0.0)); /* the timer counts from here */
    in_at(0.2, 20);
    TEST_ASSERT_EQUAL_INT64(T + 16 * M, lep_priv_sim_transport_next(&tr));
    TEST_ASSERT_EQUAL_size_t(0, ready_at(15.9));
    TEST_ASSERT_EQUAL_size_t(20, ready_at(16.0));
}

static void test_ftdi_full_packets_go_at_the_next_frame(void)
{
    lep_priv_sim_transport_init(&tr, SIM_TRANSPORT_FTDI, 16);
    TEST_ASSERT_EQUAL_size_t(0, ready_at(0.0));
    in_at(0.1, 20);
    in_at(0.9, 20);
    in_at(1.7, 20); /* 60: not a packet yet */
    TEST_ASSERT_EQUAL_size_t(0, ready_at(2.0));
    in_at(2.5, 20); /* 80: one packet of 62, at the frame at 3 ms */
    TEST_ASSERT_EQUAL_INT64(T + 3 * M, lep_priv_sim_transport_next(&tr));
    TEST_ASSERT_EQUAL_size_t(0, ready_at(2.9));
    TEST_ASSERT_EQUAL_size_t(62, ready_at(3.0));
    /* the 18 left wait for the timer, restarted by that packet */
    TEST_ASSERT_EQUAL_INT64(T + 19 * M, lep_priv_sim_transport_next(&tr));
    TEST_ASSERT_EQUAL_size_t(62, ready_at(18.9));
    TEST_ASSERT_EQUAL_size_t(80, ready_at(19.0));
    /* idle, the chip sends its status bytes alone every 16 ms (35, 51):
     * bytes at 41.5 ms go out with the one at 51 ms */
    in_at(41.5, 20);
    TEST_ASSERT_EQUAL_INT64(T + 51 * M, lep_priv_sim_transport_next(&tr));
    TEST_ASSERT_EQUAL_size_t(80, ready_at(50.9));
    TEST_ASSERT_EQUAL_size_t(100, ready_at(51.0));
}

static void test_ftdi_many_packets_in_one_frame(void)
{
    lep_priv_sim_transport_init(&tr, SIM_TRANSPORT_FTDI, 16);
    TEST_ASSERT_EQUAL_size_t(0, ready_at(0.0));
    in_at(0.5, 200); /* three packets (186) now, 14 after the timer */
    TEST_ASSERT_EQUAL_size_t(186, ready_at(1.0));
    TEST_ASSERT_EQUAL_size_t(186, ready_at(16.5));
    TEST_ASSERT_EQUAL_size_t(200, ready_at(17.0));
}

static void test_ftdi_timer_of_1_ms_sends_every_frame(void)
{
    lep_priv_sim_transport_init(&tr, SIM_TRANSPORT_FTDI, 1);
    TEST_ASSERT_EQUAL_size_t(0, ready_at(0.0));
    in_at(0.4, 20);
    TEST_ASSERT_EQUAL_INT64(T + M, lep_priv_sim_transport_next(&tr));
    TEST_ASSERT_EQUAL_size_t(20, ready_at(1.0));
    in_at(1.2, 20);
    in_at(7.3, 20);
    TEST_ASSERT_EQUAL_size_t(40, ready_at(2.0));
    TEST_ASSERT_EQUAL_INT64(T + 8 * M, lep_priv_sim_transport_next(&tr));
    TEST_ASSERT_EQUAL_size_t(60, ready_at(8.0));
}

/* A stream as the sensor sends it: 25-byte messages at 1200 Hz for 2 s,
 * looked at every 0.1 ms. Every byte goes out at the first boundary the rule
 * allows, in order, never before it entered. */
static void test_ftdi_stream_against_the_rule(void)
{
    const double period_ms = 1000.0 / 1200.0;
    size_t made = 0, out_bytes = 0;
    double t, last_packet = 0.0, released_at[2400];
    int step;
    lep_priv_sim_transport_init(&tr, SIM_TRANSPORT_FTDI, 16);
    TEST_ASSERT_EQUAL_size_t(0, ready_at(0.0));
    for (step = 1; step <= 20200; step++) { /* 2 s and the timer after */
        size_t ready, i;
        t = step * 0.1;
        /* the messages due by the previous look enter (at their deadlines) */
        while (made < 2400 && (double)(made + 1u) * period_ms <= t) {
            in_at((double)(made + 1u) * period_ms, 25);
            made++;
        }
        ready = ready_at(t);
        if (ready == 0)
            continue;
        /* released only at a boundary: t is one (steps of 0.1 ms) */
        TEST_ASSERT_TRUE(step % 10 == 0);
        /* a full packet, or the timer ran out since the last packet */
        TEST_ASSERT_TRUE(ready % SIM_FTDI_PAYLOAD == 0 || t - last_packet >= 16.0 - 1e-9);
        for (i = out_bytes / 25u; i < (out_bytes + ready) / 25u; i++) {
            released_at[i] = t;
            TEST_ASSERT_TRUE((double)(i + 1u) * period_ms <= t + 1e-9);
        }
        out_bytes += ready;
        last_packet = t;
        lep_priv_sim_transport_written(&tr, ready);
    }
    TEST_ASSERT_EQUAL_size_t(2400u * 25u, out_bytes);
    /* at 30 kB/s the packets fill in about 2 ms: the timer hardly matters */
    TEST_ASSERT_TRUE(released_at[2399] - 2400.0 * period_ms <= 16.0);
}

static void test_clear_forgets_what_was_in_flight(void)
{
    lep_priv_sim_transport_init(&tr, SIM_TRANSPORT_USB, 0);
    TEST_ASSERT_EQUAL_size_t(0, ready_at(0.0));
    in_at(0.5, 30);
    TEST_ASSERT_EQUAL_size_t(30, ready_at(1.0));
    in_at(1.5, 30);
    lep_priv_sim_transport_clear(&tr);
    TEST_ASSERT_EQUAL_size_t(0, lep_priv_sim_transport_ready(&tr));
    TEST_ASSERT_EQUAL_INT64(0, lep_priv_sim_transport_next(&tr));
    TEST_ASSERT_EQUAL_size_t(0, ready_at(2.0));
    in_at(2.5, 5);
    TEST_ASSERT_EQUAL_size_t(5, ready_at(3.0));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_none_releases_at_once);
    RUN_TEST(test_usb_releases_at_frame_boundaries);
    RUN_TEST(test_usb_bytes_made_late_go_at_the_next_frame);
    RUN_TEST(test_usb_fifo_nothing_overtakes);
    RUN_TEST(test_ftdi_timer_sends_what_it_holds);
    RUN_TEST(test_ftdi_full_packets_go_at_the_next_frame);
    RUN_TEST(test_ftdi_many_packets_in_one_frame);
    RUN_TEST(test_ftdi_timer_of_1_ms_sends_every_frame);
    RUN_TEST(test_ftdi_stream_against_the_rule);
    RUN_TEST(test_clear_forgets_what_was_in_flight);
    return UNITY_END();
}
