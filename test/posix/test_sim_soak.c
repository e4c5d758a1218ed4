/* leptrino-soak: a short run with every fault passes and says so in JSON; a
 * check against the wrong filter fails it (the check can fail); the two-bit
 * error measurement gives its figures. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "unity.h"

#ifndef LEP_SOAK_EXE
#error "LEP_SOAK_EXE must name the leptrino-soak executable"
#endif

static char out[4096];

void setUp(void)
{
}

void tearDown(void)
{
}

/* Run leptrino-soak with args; its stdout into out; returns the exit status. */
static int run(const char *args)
{
    char cmd[512];
    FILE *p;
    size_t n;
    int st;
    snprintf(cmd, sizeof cmd, "'%s' %s", LEP_SOAK_EXE, args);
    p = popen(cmd, "r");
    TEST_ASSERT_NOT_NULL(p);
    n = fread(out, 1, sizeof out - 1, p);
    out[n] = '\0';
    st = pclose(p);
    TEST_ASSERT_TRUE(WIFEXITED(st));
    return WEXITSTATUS(st);
}

/* The number after "key": in out (the first occurrence). */
static double field(const char *key)
{
    char pat[64];
    const char *p;
    snprintf(pat, sizeof pat, "\"%s\":", key);
    p = strstr(out, pat);
    TEST_ASSERT_NOT_NULL_MESSAGE(p, key);
    return strtod(p + strlen(pat), NULL);
}

static void test_short_soak_with_every_fault(void)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, run("--duration 5 --hangup-every 2 --stall-every 1"), out);
    TEST_MESSAGE(out);
    TEST_ASSERT_EQUAL_PTR(strchr(out, '\n'), out + strlen(out) - 1); /* one line */
    TEST_ASSERT_EQUAL_DOUBLE(0, field("delivered_wrong"));
    TEST_ASSERT_EQUAL_DOUBLE(0, field("duplicated"));
    TEST_ASSERT_EQUAL_DOUBLE(0, field("out_of_order"));
    TEST_ASSERT_TRUE(field("delivered") > 500);
    TEST_ASSERT_TRUE(field("sent") >= field("delivered"));
    TEST_ASSERT_TRUE(field("commands") > 10);
    TEST_ASSERT_TRUE(field("reconnects") >= 1);
    TEST_ASSERT_TRUE(field("hangups") >= 1);
    TEST_ASSERT_TRUE(field("stalls") >= 1);
    TEST_ASSERT_TRUE(field("corrupted") >= 1);
    /* every sample generated is sent or lost to a named cause */
    TEST_ASSERT_EQUAL_DOUBLE(field("generated"), field("sent") + field("dropped") +
                                                     field("stalled") + field("blocked"));
    TEST_ASSERT_NOT_NULL(strstr(out, "\"max_gap_ms\":"));
    TEST_ASSERT_NOT_NULL(strstr(out, "\"resent\":"));
    TEST_ASSERT_NOT_NULL(strstr(out, "\"failed\":"));
    TEST_ASSERT_NOT_NULL(strstr(out, "\"line\":"));
}

static void test_the_check_can_fail(void)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(1, run("--duration 1 --hangup-every 0 --check-filter 1"), out);
    TEST_ASSERT_TRUE_MESSAGE(field("delivered_wrong") > 100, out);
}

static void test_two_bit_errors(void)
{
    double rate;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, run("--bit-errors 20000"), out);
    TEST_MESSAGE(out);
    TEST_ASSERT_EQUAL_DOUBLE(20000, field("trials"));
    /* two bits in the same position of two bytes pass an XOR (about 1 in 8);
     * many of those are then a plausible message */
    rate = field("passed_bcc_rate");
    TEST_ASSERT_TRUE_MESSAGE(rate > 0.04 && rate < 0.15, out);
    rate = field("accepted_rate");
    TEST_ASSERT_TRUE_MESSAGE(rate > 0.01 && rate < 0.1, out);
}

static void test_bad_arguments(void)
{
    TEST_ASSERT_EQUAL_INT(2, run("--duration -1 2>/dev/null"));
    TEST_ASSERT_EQUAL_INT(2, run("--amplitude 9 2>/dev/null"));
    TEST_ASSERT_EQUAL_INT(2, run("--bogus 2>/dev/null"));
    TEST_ASSERT_EQUAL_INT(2, run("--bit-errors 0 2>/dev/null"));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_short_soak_with_every_fault);
    RUN_TEST(test_the_check_can_fail);
    RUN_TEST(test_two_bit_errors);
    RUN_TEST(test_bad_arguments);
    return UNITY_END();
}
