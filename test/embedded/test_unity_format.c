/* The bundled harness's number text (UnityFormatNumber): 64-bit values must
 * print in full on every C library, newlib-nano included, whose printf lacks
 * %lld and PRId64. Run on the host and on every emulated target. */
#include <stdint.h>
#include <string.h>

#include "unity.h"

void setUp(void)
{
}
void tearDown(void)
{
}

static const char *fmt(uint64_t bits, int is_signed, UNITY_DISPLAY_STYLE_T style)
{
    static char out[40];
    size_t len = UnityFormatNumber(out, sizeof out, bits, is_signed, style);
    TEST_ASSERT_EQUAL_size_t(strlen(out), len);
    return out;
}

static uint64_t bits_of(int64_t v)
{
    uint64_t b;
    memcpy(&b, &v, sizeof b);
    return b;
}

static void test_signed_extremes(void)
{
    TEST_ASSERT_EQUAL_STRING("-9223372036854775808",
                             fmt(bits_of(INT64_MIN), 1, UNITY_DISPLAY_STYLE_INT));
    TEST_ASSERT_EQUAL_STRING("9223372036854775807",
                             fmt(bits_of(INT64_MAX), 1, UNITY_DISPLAY_STYLE_INT));
    TEST_ASSERT_EQUAL_STRING("-1", fmt(bits_of(-1), 1, UNITY_DISPLAY_STYLE_INT));
    TEST_ASSERT_EQUAL_STRING("0", fmt(0u, 1, UNITY_DISPLAY_STYLE_INT));
    TEST_ASSERT_EQUAL_STRING("-4294967296",
                             fmt(bits_of(-4294967296LL), 1, UNITY_DISPLAY_STYLE_INT));
}

static void test_unsigned(void)
{
    TEST_ASSERT_EQUAL_STRING("18446744073709551615", fmt(UINT64_MAX, 0, UNITY_DISPLAY_STYLE_UINT));
    TEST_ASSERT_EQUAL_STRING("4294967296", fmt(4294967296ULL, 0, UNITY_DISPLAY_STYLE_UINT));
    TEST_ASSERT_EQUAL_STRING("7", fmt(7u, 0, UNITY_DISPLAY_STYLE_UINT));
}

static void test_hex_widths(void)
{
    TEST_ASSERT_EQUAL_STRING("0x8000000000000001",
                             fmt(0x8000000000000001ULL, 0, UNITY_DISPLAY_STYLE_HEX64));
    TEST_ASSERT_EQUAL_STRING("0x0000000000000000", fmt(0u, 0, UNITY_DISPLAY_STYLE_HEX64));
    TEST_ASSERT_EQUAL_STRING("0xDEADBEEF", fmt(0x12DEADBEEFULL, 0, UNITY_DISPLAY_STYLE_HEX32));
    TEST_ASSERT_EQUAL_STRING("0x00AB", fmt(0xAB, 0, UNITY_DISPLAY_STYLE_HEX16));
    TEST_ASSERT_EQUAL_STRING("0x05", fmt(0x105, 0, UNITY_DISPLAY_STYLE_HEX8));
}

static void test_chars(void)
{
    TEST_ASSERT_EQUAL_STRING("'A'", fmt('A', 0, UNITY_DISPLAY_STYLE_CHAR));
    TEST_ASSERT_EQUAL_STRING("'\\x10'", fmt(0x10, 0, UNITY_DISPLAY_STYLE_CHAR));
}

static void test_truncation(void)
{
    char small[5];
    TEST_ASSERT_EQUAL_size_t(
        20u, UnityFormatNumber(small, sizeof small, UINT64_MAX, 0, UNITY_DISPLAY_STYLE_UINT));
    TEST_ASSERT_EQUAL_STRING("1844", small);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_signed_extremes);
    RUN_TEST(test_unsigned);
    RUN_TEST(test_hex_widths);
    RUN_TEST(test_chars);
    RUN_TEST(test_truncation);
    return UNITY_END();
}
