/* leptrino/process.h: the exit status of every LEP_E_* code (the table the
 * `leptrino` tool and `python -m leptrino` share), and the CPU clock. */
#include "unity.h"
#include "leptrino/process.h"

void setUp(void)
{
}

void tearDown(void)
{
}

/* Every code from LEP_OK down to LEP_E_LOST, with the status docs/cli.md
 * gives it; written out here, apart from the table under test. */
static void test_every_error_code(void)
{
    static const struct {
        int err;
        int status;
    } k[] = {
        { LEP_OK, 0 },
        { LEP_E_ARG, 1 },
        { LEP_E_BUFFER, 1 },
        { LEP_E_TOO_LONG, 1 },
        { LEP_E_BCC, 1 },
        { LEP_E_ESCAPE, 1 },
        { LEP_E_LENGTH, 1 },
        { LEP_E_RESERVED, 1 },
        { LEP_E_UNEXPECTED, 1 },
        { LEP_E_VALUE, 1 },
        { LEP_E_SENSOR, 5 },
        { LEP_E_NAK, 5 },
        { LEP_E_TIMEOUT, 3 },
        { LEP_E_IO, 1 },
        { LEP_E_DISCONNECTED, 4 },
        { LEP_E_BUSY, 7 },
        { LEP_E_NOT_FOUND, 6 },
        { LEP_E_PERMISSION, 8 },
        { LEP_E_NOT_TTY, 6 },
        { LEP_E_STATE, 1 },
        { LEP_E_NO_SYNC, 3 },
        { LEP_E_UNSUPPORTED, 1 },
        { LEP_E_END, 0 },
        { LEP_E_STALLED, 3 },
        { LEP_E_LOST, 3 },
    };
    size_t i;
    for (i = 0; i < sizeof k / sizeof k[0]; ++i) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(k[i].status, lep_exit_code(k[i].err), lep_strerror(k[i].err));
    }
}

/* Values that are no LEP_E_* code are a plain failure, never success. */
static void test_unknown_codes_fail(void)
{
    TEST_ASSERT_EQUAL_INT(LEP_EXIT_FAIL, lep_exit_code(-1000));
    TEST_ASSERT_EQUAL_INT(LEP_EXIT_FAIL, lep_exit_code(1));
    TEST_ASSERT_EQUAL_INT(LEP_EXIT_FAIL, lep_exit_code(-2147483647 - 1));
}

/* The CPU clock is non-negative and does not go back across some work. */
static void test_cpu_seconds_grows(void)
{
    volatile double x = 0.0;
    double t0 = lep_cpu_seconds(), t1;
    long i;
    for (i = 0; i < 20000000L && lep_cpu_seconds() - t0 < 0.02; ++i)
        x += (double)i * 1e-9;
    t1 = lep_cpu_seconds();
    TEST_ASSERT_TRUE(t0 >= 0.0);
    TEST_ASSERT_TRUE(t1 >= t0);
    TEST_ASSERT_TRUE(x >= 0.0);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_error_code);
    RUN_TEST(test_unknown_codes_fail);
    RUN_TEST(test_cpu_seconds_grows);
    return UNITY_END();
}
