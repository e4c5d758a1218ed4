/* Error and result texts: the result codes that share an error's text, the
 * texts of codes outside both lists, and every text's wording. */
#include <limits.h>
#include <string.h>

#include "unity.h"
#include "leptrino/leptrino.h"

void setUp(void)
{
}

void tearDown(void)
{
}

/* A result code whose meaning an error states answers with that very text. */
static void test_result_shares_error_text(void)
{
    TEST_ASSERT_EQUAL_PTR(lep_strerror(LEP_OK), lep_result_str(LEP_RESULT_OK));
    TEST_ASSERT_EQUAL_PTR(lep_strerror(LEP_E_LENGTH), lep_result_str(LEP_RESULT_LENGTH));
    TEST_ASSERT_EQUAL_PTR(lep_strerror(LEP_E_VALUE), lep_result_str(LEP_RESULT_VALUE));
}

static void test_error_texts(void)
{
    static const struct {
        int err;
        const char *text;
    } k[] = { { LEP_OK, "success" },
              { LEP_E_ARG, "invalid argument" },
              { LEP_E_BUFFER, "buffer too small" },
              { LEP_E_TOO_LONG, "message too long" },
              { LEP_E_BCC, "bad frame check (BCC)" },
              { LEP_E_ESCAPE, "bad byte after DLE" },
              { LEP_E_LENGTH, "length error" },
              { LEP_E_RESERVED, "bad reserved byte" },
              { LEP_E_UNEXPECTED, "unexpected message" },
              { LEP_E_VALUE, "invalid value" },
              { LEP_E_SENSOR, "sensor reported an error" },
              { LEP_E_NAK, "sensor kept answering NAK" },
              { LEP_E_TIMEOUT, "sensor timed out" },
              { LEP_E_IO, "I/O error" },
              { LEP_E_DISCONNECTED, "port disconnected" },
              { LEP_E_BUSY, "port in use" },
              { LEP_E_NOT_FOUND, "no such port" },
              { LEP_E_PERMISSION, "permission denied" },
              { LEP_E_NOT_TTY, "not a terminal" },
              { LEP_E_STATE, "not allowed in this state" },
              { LEP_E_NO_SYNC, "line never went quiet" },
              { LEP_E_UNSUPPORTED, "not supported" },
              { LEP_E_END, "duration or count reached" },
              { LEP_E_STALLED, "no stream data within the watchdog time" },
              { LEP_E_LOST, "stream lost" } };
    size_t i;
    for (i = 0; i < sizeof(k) / sizeof(k[0]); i++) {
        TEST_ASSERT_EQUAL_STRING(k[i].text, lep_strerror(k[i].err));
    }
}

/* Codes outside the list, up to the ends of int (no overflow negating them). */
static void test_unknown_errors(void)
{
    static const int k[] = { 1,    2,        127,         INT_MAX, LEP_E_LOST - 1,
                             -100, -1000000, INT_MIN + 1, INT_MIN };
    size_t i;
    for (i = 0; i < sizeof(k) / sizeof(k[0]); i++) {
        TEST_ASSERT_EQUAL_STRING("unknown error", lep_strerror(k[i]));
    }
}

static void test_result_texts(void)
{
    unsigned r;
    TEST_ASSERT_EQUAL_STRING("success", lep_result_str(LEP_RESULT_OK));
    TEST_ASSERT_EQUAL_STRING("length error", lep_result_str(LEP_RESULT_LENGTH));
    TEST_ASSERT_EQUAL_STRING("undefined command", lep_result_str(LEP_RESULT_UNDEFINED));
    TEST_ASSERT_EQUAL_STRING("invalid value", lep_result_str(LEP_RESULT_VALUE));
    TEST_ASSERT_EQUAL_STRING("state error", lep_result_str(LEP_RESULT_STATE));
    for (r = LEP_RESULT_STATE + 1u; r <= 0xFFu; r++) {
        TEST_ASSERT_EQUAL_STRING("unknown result code", lep_result_str((uint8_t)r));
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_result_shares_error_text);
    RUN_TEST(test_error_texts);
    RUN_TEST(test_unknown_errors);
    RUN_TEST(test_result_texts);
    return UNITY_END();
}
