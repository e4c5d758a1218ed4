/* The session's units on their own: the sink, the chain and the timing,
 * each driven through its functions with made-up samples and times (no port,
 * no thread, no clock), checked for what they write into the sink. */
#include <math.h>
#include <string.h>

#include "leptrino/error.h"
#include "session_chain.h"
#include "session_sink.h"
#include "session_timing.h"
#include "unity.h"

static session_sink sink;
static session_chain chain;
static session_timing timing;

void setUp(void)
{
    lep_client_stats base;
    memset(&base, 0, sizeof base);
    memset(&sink, 0, sizeof sink);
    lep_priv_sink_open(&sink);
    lep_priv_sink_start(&sink, 1000.0, &base);
}

void tearDown(void)
{
}

static lep_session_event event(int type, uint64_t sample)
{
    lep_session_event ev;
    lep_priv_event_init(&ev, type, sample, 1.0);
    return ev;
}

static session_row row_at(double t, double arrived)
{
    session_row r;
    memset(&r, 0, sizeof r);
    r.t_mono = t;
    r.t_utc = t + 100.0;
    r.arrived = arrived;
    return r;
}

/* Each event counts what it implies, by its type; the rest count nothing. */
static void test_sink_counts_events_by_type(void)
{
    lep_session_event ev = event(LEP_EV_OVERLOAD_BEGIN, 0);
    lep_session_health_info h;
    lep_priv_sink_event(&sink, &ev);
    ev = event(LEP_EV_OVERLOAD_END, 0);
    lep_priv_sink_event(&sink, &ev);
    ev = event(LEP_EV_LIMIT_EXCEEDED, 0);
    lep_priv_sink_event(&sink, &ev);
    ev = event(LEP_EV_LIMIT_CLEARED, 0);
    lep_priv_sink_event(&sink, &ev);
    ev = event(LEP_EV_GAP, 0);
    ev.gap_from = 1.0;
    ev.gap_to = 1.25;
    ev.lost = 7;
    lep_priv_sink_event(&sink, &ev);
    ev = event(LEP_EV_RECONNECTED, 0);
    ev.gap_from = 2.0;
    ev.gap_to = 2.5;
    ev.lost = 3;
    lep_priv_sink_event(&sink, &ev);
    ev = event(LEP_EV_TARE, 0);
    lep_priv_sink_event(&sink, &ev);
    lep_priv_sink_health(&sink, &h);
    TEST_ASSERT_EQUAL_UINT64(1, h.overloads);
    TEST_ASSERT_EQUAL_UINT64(1, h.limit_episodes);
    TEST_ASSERT_EQUAL_UINT64(2, h.gaps);
    TEST_ASSERT_EQUAL_UINT64(10, h.lost);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 0.5, h.max_gap_s);
    TEST_ASSERT_EQUAL_UINT64(7, lep_priv_sink_pushed(&sink));
}

/* An event waits for the rows before its sample; a kept row is numbered. */
static void test_sink_gates_events_on_rows_returned(void)
{
    double t[4], first = -1.0;
    lep_session_batch b;
    lep_session_event ev = event(LEP_EV_TARE, 2), out;
    session_row r = row_at(1.0, 1.0);
    int k;
    for (k = 0; k < 3; k++)
        lep_priv_sink_row(&sink, &r);
    TEST_ASSERT_EQUAL_UINT64(3, lep_priv_sink_processed(&sink));
    lep_priv_sink_event(&sink, &ev);
    TEST_ASSERT_FALSE(lep_priv_sink_pop(&sink, &out));
    memset(&b, 0, sizeof b);
    b.cap = 1;
    b.t_mono = t;
    TEST_ASSERT_EQUAL_size_t(1, lep_priv_sink_deliver(&sink, &b, &first));
    lep_priv_sink_returned(&sink, 1);
    TEST_ASSERT_FALSE(lep_priv_sink_pop(&sink, &out)); /* 1 row returned, the event is at 2 */
    b.cap = 2;
    TEST_ASSERT_EQUAL_size_t(1, lep_priv_sink_deliver(&sink, &b, &first));
    lep_priv_sink_returned(&sink, 1);
    TEST_ASSERT_TRUE(lep_priv_sink_pop(&sink, &out));
    TEST_ASSERT_EQUAL_INT(LEP_EV_TARE, out.type);
}

/* A hole before the held rows: their stamps move, each no later than its
 * read's return, the first is flagged; held rows are not delivered. */
static void test_sink_moves_held_rows_after_a_gap(void)
{
    double t[4], first = -1.0;
    uint8_t flags[4];
    lep_session_batch b;
    session_row r = row_at(1.000, 1.010);
    lep_priv_sink_row(&sink, &r);
    r = row_at(1.001, 1.010);
    lep_priv_sink_row(&sink, &r);
    r = row_at(1.002, 1.004);
    lep_priv_sink_row(&sink, &r);
    TEST_ASSERT_EQUAL_size_t(2, lep_priv_sink_hold_since(&sink, 1, false));
    memset(&b, 0, sizeof b);
    b.cap = 4;
    b.t_mono = t;
    b.flags = flags;
    TEST_ASSERT_EQUAL_size_t(1, lep_priv_sink_deliver(&sink, &b, &first));
    TEST_ASSERT_TRUE(lep_priv_sink_judged(&sink, true, 0.005));
    TEST_ASSERT_EQUAL_size_t(0, lep_priv_sink_held(&sink));
    TEST_ASSERT_EQUAL_size_t(2, lep_priv_sink_deliver(&sink, &b, &first));
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1.006, t[1]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1.004, t[2]); /* capped at its read's return */
    TEST_ASSERT_EQUAL_HEX8(LEP_SF_GAP, flags[1]);
    TEST_ASSERT_EQUAL_HEX8(0, flags[2]);
}

static void chain_open(unsigned tare_samples, unsigned decimate, uint64_t count)
{
    lep_session_options o;
    session_chain_config cfg;
    int k;
    lep_session_options_init(&o);
    o.decimate = decimate;
    memset(&cfg, 0, sizeof cfg);
    for (k = 0; k < LEP_AXES; k++)
        cfg.rated.axis[k] = 100.0f;
    cfg.saturation = 32000;
    cfg.tare_samples = tare_samples;
    cfg.count = count;
    lep_priv_chain_init(&chain, &o, &cfg);
    lep_priv_chain_start(&chain);
}

static lep_sample sample_of(int16_t raw)
{
    lep_sample s;
    int k;
    memset(&s, 0, sizeof s);
    for (k = 0; k < LEP_AXES; k++)
        s.raw[k] = raw;
    return s;
}

/* The start-up tare's samples are averaged and not kept; the rows after it
 * carry the offset, and its event goes before the first of them. */
static void test_chain_start_up_tare_into_the_sink(void)
{
    lep_session_batch b;
    double zeroed[2 * LEP_AXES], first = -1.0;
    lep_session_event ev;
    lep_sample s;
    chain_open(2, 1, 0);
    s = sample_of(100);
    lep_priv_chain_sample(&chain, &sink, &s, 0.001, 0.001, 0.001, 0);
    s = sample_of(300);
    lep_priv_chain_sample(&chain, &sink, &s, 0.002, 0.002, 0.002, 0);
    TEST_ASSERT_EQUAL_UINT64(0, lep_priv_sink_processed(&sink));
    s = sample_of(250);
    lep_priv_chain_sample(&chain, &sink, &s, 0.003, 0.003, 0.003, 0);
    TEST_ASSERT_EQUAL_UINT64(1, lep_priv_sink_processed(&sink));
    memset(&b, 0, sizeof b);
    b.cap = 2;
    b.zeroed = zeroed;
    TEST_ASSERT_EQUAL_size_t(1, lep_priv_sink_deliver(&sink, &b, &first));
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 50.0, zeroed[0]); /* 250 - mean(100, 300) */
    TEST_ASSERT_TRUE(lep_priv_sink_pop(&sink, &ev));
    TEST_ASSERT_EQUAL_INT(LEP_EV_TARE, ev.type);
    TEST_ASSERT_EQUAL_UINT64(0, ev.sample);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 200.0, ev.tare[0]);
}

/* Decimation keeps every 2nd sample and carries a dropped sample's gap flag
 * to the next row kept; an overload is an event and a flag; the count ends
 * the run. */
static void test_chain_decimation_overload_and_count(void)
{
    lep_session_batch b;
    uint8_t flags[4];
    double first = -1.0;
    lep_session_event ev;
    lep_sample s = sample_of(10);
    chain_open(0, 2, 2);
    lep_priv_chain_sample(&chain, &sink, &s, 0.001, 0.001, 0.001, 0);
    lep_priv_chain_sample(&chain, &sink, &s, 0.002, 0.002, 0.002, LEP_SF_GAP); /* dropped */
    s.status = LEP_STATUS_OVERLOAD;
    lep_priv_chain_sample(&chain, &sink, &s, 0.003, 0.003, 0.003, 0);
    TEST_ASSERT_TRUE(lep_priv_chain_ended(&chain));
    lep_priv_chain_sample(&chain, &sink, &s, 0.005, 0.005, 0.005, 0);
    TEST_ASSERT_EQUAL_UINT64(2, lep_priv_sink_processed(&sink));
    memset(&b, 0, sizeof b);
    b.cap = 4;
    b.flags = flags;
    TEST_ASSERT_EQUAL_size_t(2, lep_priv_sink_deliver(&sink, &b, &first));
    TEST_ASSERT_EQUAL_HEX8(0, flags[0]);
    TEST_ASSERT_EQUAL_HEX8(LEP_SF_GAP | LEP_SF_OVERLOAD, flags[1]);
    lep_priv_sink_returned(&sink, 2);
    TEST_ASSERT_TRUE(lep_priv_sink_pop(&sink, &ev));
    TEST_ASSERT_EQUAL_INT(LEP_EV_OVERLOAD_BEGIN, ev.type);
    TEST_ASSERT_EQUAL_UINT64(1, ev.sample);
}

/* The timing stamps a read's samples and hands them to the chain; after a
 * reconnect it queues the gap into the sink (the samples lost estimated at
 * the nominal rate) before the first row, which is flagged LEP_SF_GAP. */
static void test_timing_feeds_the_chain_and_queues_a_reconnect(void)
{
    lep_sample got[1];
    lep_session_batch b;
    double t[2], first = -1.0;
    uint8_t flags[2];
    lep_session_event ev;
    lep_session_health_info h;
    chain_open(0, 1, 0);
    got[0] = sample_of(10);
    lep_priv_timing_start(&timing, 1000.0, 3.0, false);
    lep_priv_timing_resume(&timing, 0.0);
    lep_priv_timing_feed(&timing, &chain, &sink, got, 1, 1.0);
    lep_priv_timing_reconnected(&timing, LEP_E_DISCONNECTED);
    lep_priv_timing_feed(&timing, &chain, &sink, got, 1, 1.5);
    memset(&b, 0, sizeof b);
    b.cap = 2;
    b.t_mono = t;
    b.flags = flags;
    TEST_ASSERT_EQUAL_size_t(2, lep_priv_sink_deliver(&sink, &b, &first));
    lep_priv_sink_returned(&sink, 2);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 1.0, t[0]);
    TEST_ASSERT_TRUE(t[1] > t[0] && t[1] <= 1.5); /* never after the read's return */
    TEST_ASSERT_EQUAL_HEX8(0, flags[0]);
    TEST_ASSERT_EQUAL_HEX8(LEP_SF_GAP, flags[1]);
    TEST_ASSERT_TRUE(lep_priv_sink_pop(&sink, &ev));
    TEST_ASSERT_EQUAL_INT(LEP_EV_RECONNECTED, ev.type);
    TEST_ASSERT_EQUAL_UINT64(1, ev.sample);
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, ev.error);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, t[0], ev.gap_from);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, t[1], ev.gap_to);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)floor((t[1] - t[0]) * 1000.0 - 1.0 + 0.5), ev.lost);
    lep_priv_sink_health(&sink, &h);
    TEST_ASSERT_EQUAL_UINT64(1, h.gaps);
    TEST_ASSERT_EQUAL_UINT64(2, h.received);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sink_counts_events_by_type);
    RUN_TEST(test_sink_gates_events_on_rows_returned);
    RUN_TEST(test_sink_moves_held_rows_after_a_gap);
    RUN_TEST(test_chain_start_up_tare_into_the_sink);
    RUN_TEST(test_chain_decimation_overload_and_count);
    RUN_TEST(test_timing_feeds_the_chain_and_queues_a_reconnect);
    return UNITY_END();
}
