/* The virtual sensor's punctual deadlines (sim_punctual.h): the margin's
 * rule from given wake-up lateness (no clock), and the sleep's one promise
 * that holds on any machine, loaded or not: it never returns before its
 * deadline. */
#include "host/platform/posix_clock.h"
#include "host/sim/sim_punctual.h"
#include "unity.h"

#define US 1000LL

static sim_punctual p;

void setUp(void)
{
    lep_priv_sim_punctual_init(&p);
}

void tearDown(void)
{
}

/* n wake-ups with lateness spread evenly over [lo, lo + span) us, in a
 * scrambled order (a stride prime to the span). */
static void learn_spread(int n, int64_t lo, int64_t span)
{
    int i;
    for (i = 0; i < n; i++)
        lep_priv_sim_punctual_learn(&p, (lo + ((int64_t)i * 17) % span) * US);
}

static void test_starts_at_the_ceiling(void)
{
    TEST_ASSERT_EQUAL_INT64(SIM_PUNCTUAL_MAX_NS, p.margin_ns);
    TEST_ASSERT_EQUAL_INT64(5000000 - SIM_PUNCTUAL_MAX_NS, lep_priv_sim_punctual_wake(&p, 5000000));
}

static void test_margin_settles_at_the_80th_percentile(void)
{
    /* lateness 0..99 us: its 80th percentile is 80 us */
    learn_spread(20000, 0, 100);
    TEST_ASSERT_INT64_WITHIN(8 * US, 80 * US, p.margin_ns);
    /* a VM's lateness, 30..69 us: 80th percentile 62 us */
    learn_spread(20000, 30, 40);
    TEST_ASSERT_INT64_WITHIN(8 * US, 62 * US, p.margin_ns);
}

static void test_margin_rises_four_times_as_fast_as_it_falls(void)
{
    int i;
    int64_t risen;
    learn_spread(20000, 30, 40); /* settled near 62 us */
    /* the machine gets loaded: every wake-up 150 us late; 25 wake-ups
     * (21 ms at 1.2 kHz) later the margin covers it */
    for (i = 0; i < 25; i++)
        lep_priv_sim_punctual_learn(&p, 150 * US);
    TEST_ASSERT_TRUE(p.margin_ns >= 150 * US);
    risen = p.margin_ns;
    /* quiet again: down by 1 us a wake-up */
    for (i = 0; i < 50; i++)
        lep_priv_sim_punctual_learn(&p, 40 * US);
    TEST_ASSERT_EQUAL_INT64(risen - 50 * SIM_PUNCTUAL_DOWN_NS, p.margin_ns);
    learn_spread(20000, 30, 40);
    TEST_ASSERT_INT64_WITHIN(8 * US, 62 * US, p.margin_ns);
}

static void test_margin_stays_within_bounds(void)
{
    int i;
    for (i = 0; i < 100; i++)
        lep_priv_sim_punctual_learn(&p, 10000 * US); /* 10 ms late: a starved thread */
    TEST_ASSERT_EQUAL_INT64(SIM_PUNCTUAL_MAX_NS, p.margin_ns);
    for (i = 0; i < 1000; i++)
        lep_priv_sim_punctual_learn(&p, -5 * US); /* woken early (a signal) */
    TEST_ASSERT_EQUAL_INT64(0, p.margin_ns);
    TEST_ASSERT_EQUAL_INT64(777, lep_priv_sim_punctual_wake(&p, 777));
    lep_priv_sim_punctual_learn(&p, 1);
    TEST_ASSERT_EQUAL_INT64(SIM_PUNCTUAL_UP_NS, p.margin_ns);
}

/* The real clock: only the lower bound is asserted (a loaded machine may
 * return late, never early). */
static void test_sleep_never_returns_before_its_deadline(void)
{
    int i;
    for (i = 0; i < 200; i++) {
        int64_t deadline = lep_priv_monotonic_ns() + (i % 4) * 300 * US;
        lep_priv_sim_punctual_sleep(&p, deadline);
        TEST_ASSERT_TRUE(lep_priv_monotonic_ns() >= deadline);
        TEST_ASSERT_TRUE(p.margin_ns >= 0 && p.margin_ns <= SIM_PUNCTUAL_MAX_NS);
    }
}

static void test_a_deadline_passed_is_not_slept_for_and_teaches_nothing(void)
{
    int64_t before = p.margin_ns;
    lep_priv_sim_punctual_sleep(&p, lep_priv_monotonic_ns() - 1000 * US);
    TEST_ASSERT_EQUAL_INT64(before, p.margin_ns);
    /* within the margin: no sleep either, only the clock watched */
    lep_priv_sim_punctual_sleep(&p, lep_priv_monotonic_ns() + SIM_PUNCTUAL_MAX_NS / 4);
    TEST_ASSERT_EQUAL_INT64(before, p.margin_ns);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_starts_at_the_ceiling);
    RUN_TEST(test_margin_settles_at_the_80th_percentile);
    RUN_TEST(test_margin_rises_four_times_as_fast_as_it_falls);
    RUN_TEST(test_margin_stays_within_bounds);
    RUN_TEST(test_sleep_never_returns_before_its_deadline);
    RUN_TEST(test_a_deadline_passed_is_not_slept_for_and_teaches_nothing);
    return UNITY_END();
}
