/* Engine of leptrino's Unity-compatible test harness (see unity.h). */
#include "unity.h"

#include <setjmp.h>
#include <stdio.h>
#include <string.h>

/* Relative tolerance of TEST_ASSERT_EQUAL_FLOAT / _DOUBLE. */
#define UNITY_FLOAT_REL 0.00001f
#define UNITY_DOUBLE_REL 1e-12

static struct {
    const char *file;
    const char *test_name;
    int test_line;
    unsigned tests;
    unsigned failures;
    unsigned ignored;
    int current_failed;
    int current_ignored;
    jmp_buf abort_frame;
} U;

/* ---- output ------------------------------------------------------------ */

static void head(UNITY_LINE_TYPE line)
{
    printf("%s:%u:%s:", U.file ? U.file : "?", line, U.test_name ? U.test_name : "?");
}

static void tail(const char *msg)
{
    if (msg != NULL && msg[0] != '\0') {
        printf(". %s", msg);
    }
    printf("\n");
    fflush(stdout);
}

/* Digits of v in base 10 or 16 (upper case), at least min_digits of them,
 * into out (which has room for 20 digits and a NUL); returns out. Done by
 * hand: newlib-nano's printf has no long long (%lld, PRId64 print "ld"). */
static char *format_u64(uint64_t v, unsigned base, unsigned min_digits, char *out)
{
    char rev[24];
    unsigned n = 0, i;
    do {
        unsigned d = (unsigned)(v % base);
        rev[n++] = (char)(d < 10u ? '0' + d : 'A' + (d - 10u));
        v /= base;
    } while (v != 0u && n < sizeof rev);
    while (n < min_digits && n < sizeof rev) {
        rev[n++] = '0';
    }
    for (i = 0; i < n; i++) {
        out[i] = rev[n - 1u - i];
    }
    out[n] = '\0';
    return out;
}

size_t UnityFormatNumber(char *out, size_t cap, uint64_t bits, int is_signed,
                         UNITY_DISPLAY_STYLE_T style)
{
    char digits[24];
    char text[32];
    size_t len;
    text[0] = '\0';
    switch (style) {
    case UNITY_DISPLAY_STYLE_HEX8:
        strcpy(text, "0x");
        strcat(text, format_u64(bits & 0xFFu, 16u, 2u, digits));
        break;
    case UNITY_DISPLAY_STYLE_HEX16:
        strcpy(text, "0x");
        strcat(text, format_u64(bits & 0xFFFFu, 16u, 4u, digits));
        break;
    case UNITY_DISPLAY_STYLE_HEX32:
        strcpy(text, "0x");
        strcat(text, format_u64(bits & 0xFFFFFFFFu, 16u, 8u, digits));
        break;
    case UNITY_DISPLAY_STYLE_HEX64:
        strcpy(text, "0x");
        strcat(text, format_u64(bits, 16u, 16u, digits));
        break;
    case UNITY_DISPLAY_STYLE_CHAR:
        if (bits >= 0x20u && bits < 0x7Fu) {
            text[0] = '\'';
            text[1] = (char)bits;
            text[2] = '\'';
            text[3] = '\0';
        } else {
            strcpy(text, "'\\x");
            strcat(text, format_u64(bits & 0xFFu, 16u, 2u, digits));
            strcat(text, "'");
        }
        break;
    case UNITY_DISPLAY_STYLE_INT:
    case UNITY_DISPLAY_STYLE_UINT:
    default:
        if (is_signed && (bits >> 63) != 0u) {
            /* Two's complement magnitude, well defined for INT64_MIN too. */
            strcpy(text, "-");
            strcat(text, format_u64(~bits + 1u, 10u, 1u, digits));
        } else {
            strcpy(text, format_u64(bits, 10u, 1u, digits));
        }
        break;
    }
    len = strlen(text);
    if (cap > 0u) {
        size_t n = len < cap ? len : cap - 1u;
        memcpy(out, text, n);
        out[n] = '\0';
    }
    return len;
}

static void print_number(uint64_t bits, int is_signed, UNITY_DISPLAY_STYLE_T style)
{
    char text[32];
    UnityFormatNumber(text, sizeof text, bits, is_signed, style);
    fputs(text, stdout);
}

static void print_unsigned(uint64_t v)
{
    print_number(v, 0, UNITY_DISPLAY_STYLE_UINT);
}

static void print_signed(int64_t v)
{
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    print_number(bits, 1, UNITY_DISPLAY_STYLE_INT);
}

/* End the running test: longjmp back to the runner. */
static void bail(void)
{
    U.current_failed = 1;
    longjmp(U.abort_frame, 1);
}

static void fail_begin(UNITY_LINE_TYPE line)
{
    head(line);
    printf("FAIL: ");
}

/* ---- runner ------------------------------------------------------------ */

void UnityBegin(const char *file)
{
    memset(&U, 0, sizeof U);
    U.file = file;
}

void UnityDefaultTestRun(UnityTestFunction func, const char *name, int line)
{
    U.test_name = name;
    U.test_line = line;
    U.current_failed = 0;
    U.current_ignored = 0;
    U.tests++;
    if (setjmp(U.abort_frame) == 0) {
        setUp();
        func();
    }
    /* tearDown runs even after a failure or an ignore. */
    if (setjmp(U.abort_frame) == 0) {
        tearDown();
    }
    if (U.current_failed) {
        U.failures++;
    } else if (U.current_ignored) {
        U.ignored++;
    } else {
        head((UNITY_LINE_TYPE)U.test_line);
        printf("PASS\n");
        fflush(stdout);
    }
    U.test_name = NULL;
}

int UnityEnd(void)
{
    printf("\n-----------------------\n");
    printf("%u Tests %u Failures %u Ignored \n", U.tests, U.failures, U.ignored);
    printf("%s\n", U.failures == 0 ? "OK" : "FAIL");
    fflush(stdout);
    return (int)U.failures;
}

/* ---- basic ------------------------------------------------------------- */

void UnityFail(const char *msg, UNITY_LINE_TYPE line)
{
    head(line);
    if (msg != NULL && msg[0] != '\0') {
        printf("FAIL: %s\n", msg);
    } else {
        printf("FAIL\n");
    }
    fflush(stdout);
    bail();
}

void UnityIgnore(const char *msg, UNITY_LINE_TYPE line)
{
    head(line);
    printf("IGNORE");
    if (msg != NULL && msg[0] != '\0') {
        printf(": %s", msg);
    }
    printf("\n");
    fflush(stdout);
    U.current_ignored = 1;
    longjmp(U.abort_frame, 1);
}

void UnityPass(void)
{
    longjmp(U.abort_frame, 1);
}

void UnityMessage(const char *msg, UNITY_LINE_TYPE line)
{
    head(line);
    printf("INFO: %s\n", msg != NULL ? msg : "");
    fflush(stdout);
}

void UnityAssertTrue(int condition, const char *what, const char *msg, UNITY_LINE_TYPE line)
{
    if (condition) {
        return;
    }
    fail_begin(line);
    printf("%s", what);
    tail(msg);
    bail();
}

/* ---- integers ---------------------------------------------------------- */

static void expected_was(uint64_t e, uint64_t a, int is_signed, UNITY_DISPLAY_STYLE_T style)
{
    printf("Expected ");
    print_number(e, is_signed, style);
    printf(" Was ");
    print_number(a, is_signed, style);
}

void UnityAssertEqualSigned(int64_t expected, int64_t actual, const char *msg, UNITY_LINE_TYPE line,
                            UNITY_DISPLAY_STYLE_T style)
{
    uint64_t e, a;
    if (expected == actual) {
        return;
    }
    memcpy(&e, &expected, sizeof e);
    memcpy(&a, &actual, sizeof a);
    fail_begin(line);
    expected_was(e, a, 1, style);
    tail(msg);
    bail();
}

void UnityAssertEqualUnsigned(uint64_t expected, uint64_t actual, const char *msg,
                              UNITY_LINE_TYPE line, UNITY_DISPLAY_STYLE_T style)
{
    if (expected == actual) {
        return;
    }
    fail_begin(line);
    expected_was(expected, actual, 0, style);
    tail(msg);
    bail();
}

static const char *cmp_text(UNITY_COMPARISON_T cmp)
{
    switch (cmp) {
    case UNITY_GREATER_THAN:
        return "greater than";
    case UNITY_GREATER_OR_EQUAL:
        return "greater than or equal to";
    case UNITY_SMALLER_THAN:
        return "less than";
    case UNITY_SMALLER_OR_EQUAL:
        return "less than or equal to";
    case UNITY_NOT_EQUAL:
    default:
        return "not equal to";
    }
}

static int cmp_holds_s(int64_t t, int64_t a, UNITY_COMPARISON_T cmp)
{
    switch (cmp) {
    case UNITY_GREATER_THAN:
        return a > t;
    case UNITY_GREATER_OR_EQUAL:
        return a >= t;
    case UNITY_SMALLER_THAN:
        return a < t;
    case UNITY_SMALLER_OR_EQUAL:
        return a <= t;
    case UNITY_NOT_EQUAL:
    default:
        return a != t;
    }
}

static int cmp_holds_u(uint64_t t, uint64_t a, UNITY_COMPARISON_T cmp)
{
    switch (cmp) {
    case UNITY_GREATER_THAN:
        return a > t;
    case UNITY_GREATER_OR_EQUAL:
        return a >= t;
    case UNITY_SMALLER_THAN:
        return a < t;
    case UNITY_SMALLER_OR_EQUAL:
        return a <= t;
    case UNITY_NOT_EQUAL:
    default:
        return a != t;
    }
}

void UnityAssertCompareSigned(int64_t threshold, int64_t actual, UNITY_COMPARISON_T cmp,
                              const char *msg, UNITY_LINE_TYPE line)
{
    if (cmp_holds_s(threshold, actual, cmp)) {
        return;
    }
    fail_begin(line);
    printf("Expected %s ", cmp_text(cmp));
    print_signed(threshold);
    printf(" Was ");
    print_signed(actual);
    tail(msg);
    bail();
}

void UnityAssertCompareUnsigned(uint64_t threshold, uint64_t actual, UNITY_COMPARISON_T cmp,
                                const char *msg, UNITY_LINE_TYPE line, UNITY_DISPLAY_STYLE_T style)
{
    if (cmp_holds_u(threshold, actual, cmp)) {
        return;
    }
    fail_begin(line);
    printf("Expected %s ", cmp_text(cmp));
    print_number(threshold, 0, style);
    printf(" Was ");
    print_number(actual, 0, style);
    tail(msg);
    bail();
}

void UnityAssertSignedWithin(uint64_t delta, int64_t expected, int64_t actual, const char *msg,
                             UNITY_LINE_TYPE line)
{
    /* |actual - expected| computed without overflow. */
    uint64_t diff;
    if (actual >= expected) {
        diff = (uint64_t)actual - (uint64_t)expected;
    } else {
        diff = (uint64_t)expected - (uint64_t)actual;
    }
    if (diff <= delta) {
        return;
    }
    fail_begin(line);
    printf("Values Not Within Delta ");
    print_unsigned(delta);
    printf(" Expected ");
    print_signed(expected);
    printf(" Was ");
    print_signed(actual);
    tail(msg);
    bail();
}

void UnityAssertUnsignedWithin(uint64_t delta, uint64_t expected, uint64_t actual, const char *msg,
                               UNITY_LINE_TYPE line, UNITY_DISPLAY_STYLE_T style)
{
    uint64_t diff = actual >= expected ? actual - expected : expected - actual;
    if (diff <= delta) {
        return;
    }
    fail_begin(line);
    printf("Values Not Within Delta ");
    print_unsigned(delta);
    printf(" ");
    expected_was(expected, actual, 0, style);
    tail(msg);
    bail();
}

/* ---- strings, memory, arrays ------------------------------------------ */

static void print_quoted(const char *s, size_t max)
{
    size_t i;
    if (s == NULL) {
        printf("NULL");
        return;
    }
    printf("'");
    for (i = 0; i < max && s[i] != '\0'; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c >= 0x20u && c < 0x7Fu) {
            printf("%c", (char)c);
        } else {
            printf("\\x%02X", (unsigned)c);
        }
    }
    printf("'");
}

static void string_mismatch(const char *e, const char *a, size_t max, const char *msg,
                            UNITY_LINE_TYPE line)
{
    fail_begin(line);
    printf("Expected ");
    print_quoted(e, max);
    printf(" Was ");
    print_quoted(a, max);
    tail(msg);
    bail();
}

void UnityAssertEqualString(const char *expected, const char *actual, const char *msg,
                            UNITY_LINE_TYPE line)
{
    if (expected == NULL && actual == NULL) {
        return;
    }
    if (expected == NULL || actual == NULL || strcmp(expected, actual) != 0) {
        string_mismatch(expected, actual, SIZE_MAX, msg, line);
    }
}

void UnityAssertEqualStringLen(const char *expected, const char *actual, size_t len,
                               const char *msg, UNITY_LINE_TYPE line)
{
    if (expected == NULL && actual == NULL) {
        return;
    }
    if (expected == NULL || actual == NULL || strncmp(expected, actual, len) != 0) {
        string_mismatch(expected, actual, len, msg, line);
    }
}

/* Shared start of the memory and array asserts: 1 when there is nothing more to check. */
static int pointers_settle(const void *e, const void *a, size_t count, const char *msg,
                           UNITY_LINE_TYPE line)
{
    if (count == 0) {
        /* As upstream Unity: comparing zero elements is treated as a mistake. */
        fail_begin(line);
        printf("Asked to compare zero elements");
        tail(msg);
        bail();
    }
    if (e == NULL && a == NULL) {
        return 1;
    }
    if (e == NULL || a == NULL) {
        fail_begin(line);
        printf(e == NULL ? "Expected pointer is NULL" : "Actual pointer is NULL");
        tail(msg);
        bail();
    }
    return 0;
}

void UnityAssertEqualMemory(const void *expected, const void *actual, size_t len, const char *msg,
                            UNITY_LINE_TYPE line)
{
    const unsigned char *e = (const unsigned char *)expected;
    const unsigned char *a = (const unsigned char *)actual;
    size_t i;
    if (pointers_settle(expected, actual, len, msg, line)) {
        return;
    }
    for (i = 0; i < len; i++) {
        if (e[i] != a[i]) {
            fail_begin(line);
            printf("Memory Mismatch. Byte ");
            print_unsigned(i);
            printf(" ");
            expected_was(e[i], a[i], 0, UNITY_DISPLAY_STYLE_HEX8);
            tail(msg);
            bail();
        }
    }
}

/* Element i of an array of the given type, widened; *is_signed tells how to show it. */
static uint64_t element(const void *p, size_t i, UNITY_ARRAY_T type, int *is_signed,
                        UNITY_DISPLAY_STYLE_T *style)
{
    uint64_t bits = 0;
    int64_t s = 0;
    *is_signed = 0;
    *style = UNITY_DISPLAY_STYLE_UINT;
    switch (type) {
    case UNITY_ARRAY_INT8:
        s = ((const int8_t *)p)[i];
        *is_signed = 1;
        break;
    case UNITY_ARRAY_INT16:
        s = ((const int16_t *)p)[i];
        *is_signed = 1;
        break;
    case UNITY_ARRAY_INT32:
        s = ((const int32_t *)p)[i];
        *is_signed = 1;
        break;
    case UNITY_ARRAY_INT64:
        s = ((const int64_t *)p)[i];
        *is_signed = 1;
        break;
    case UNITY_ARRAY_INT:
        s = ((const int *)p)[i];
        *is_signed = 1;
        break;
    case UNITY_ARRAY_UINT8:
        bits = ((const uint8_t *)p)[i];
        break;
    case UNITY_ARRAY_UINT16:
        bits = ((const uint16_t *)p)[i];
        break;
    case UNITY_ARRAY_UINT32:
        bits = ((const uint32_t *)p)[i];
        break;
    case UNITY_ARRAY_UINT64:
        bits = ((const uint64_t *)p)[i];
        break;
    case UNITY_ARRAY_UINT:
        bits = ((const unsigned int *)p)[i];
        break;
    case UNITY_ARRAY_HEX8:
        bits = ((const uint8_t *)p)[i];
        *style = UNITY_DISPLAY_STYLE_HEX8;
        break;
    case UNITY_ARRAY_HEX16:
        bits = ((const uint16_t *)p)[i];
        *style = UNITY_DISPLAY_STYLE_HEX16;
        break;
    case UNITY_ARRAY_HEX32:
    default:
        bits = ((const uint32_t *)p)[i];
        *style = UNITY_DISPLAY_STYLE_HEX32;
        break;
    }
    if (*is_signed) {
        memcpy(&bits, &s, sizeof bits);
        *style = UNITY_DISPLAY_STYLE_INT;
    }
    return bits;
}

void UnityAssertEqualArray(const void *expected, const void *actual, size_t count,
                           UNITY_ARRAY_T type, const char *msg, UNITY_LINE_TYPE line)
{
    size_t i;
    if (pointers_settle(expected, actual, count, msg, line)) {
        return;
    }
    for (i = 0; i < count; i++) {
        int is_signed;
        UNITY_DISPLAY_STYLE_T style;
        uint64_t e = element(expected, i, type, &is_signed, &style);
        uint64_t a = element(actual, i, type, &is_signed, &style);
        if (e != a) {
            fail_begin(line);
            printf("Element ");
            print_unsigned(i);
            printf(" ");
            expected_was(e, a, is_signed, style);
            tail(msg);
            bail();
        }
    }
}

/* ---- floating point ---------------------------------------------------- */

/* NaN and infinity tests on a double without <math.h>'s isnan/isinf: those are
 * type-generic macros, and mingw-w64's convert a double to float in one branch
 * (-Werror=float-conversion). NaN is the one value unequal to itself; x - x is
 * NaN only for an infinity. */
static int double_is_nan(double x)
{
    return x != x;
}

static int double_is_inf(double x)
{
    return !double_is_nan(x) && double_is_nan(x - x);
}

/* 1 when actual is within delta of expected; equal infinities match, NaN never does. */
static int within_double(double delta, double expected, double actual)
{
    double diff;
    if (double_is_nan(expected) || double_is_nan(actual)) {
        return 0;
    }
    if (double_is_inf(expected) || double_is_inf(actual)) {
        return double_is_inf(expected) && double_is_inf(actual) && (expected > 0) == (actual > 0);
    }
    diff = actual - expected;
    if (diff < 0) {
        diff = -diff;
    }
    if (delta < 0) {
        delta = -delta;
    }
    return !(diff > delta);
}

/* digits: 9 for float, 17 for double (enough to tell any two values apart). */
static void float_fail(double delta, double expected, double actual, int show_delta, int digits,
                       const char *msg, UNITY_LINE_TYPE line)
{
    fail_begin(line);
    if (show_delta) {
        printf("Values Not Within Delta %.*g ", digits, delta);
    }
    printf("Expected %.*g Was %.*g", digits, expected, digits, actual);
    tail(msg);
    bail();
}

void UnityAssertFloatsWithin(float delta, float expected, float actual, const char *msg,
                             UNITY_LINE_TYPE line)
{
    if (!within_double((double)delta, (double)expected, (double)actual)) {
        float_fail((double)delta, (double)expected, (double)actual, 1, 9, msg, line);
    }
}

void UnityAssertEqualFloat(float expected, float actual, const char *msg, UNITY_LINE_TYPE line)
{
    float delta = expected * UNITY_FLOAT_REL;
    if (expected == actual) {
        return;
    }
    if (!within_double((double)delta, (double)expected, (double)actual)) {
        float_fail((double)delta, (double)expected, (double)actual, 0, 9, msg, line);
    }
}

void UnityAssertDoublesWithin(double delta, double expected, double actual, const char *msg,
                              UNITY_LINE_TYPE line)
{
    if (!within_double(delta, expected, actual)) {
        float_fail(delta, expected, actual, 1, 17, msg, line);
    }
}

void UnityAssertEqualDouble(double expected, double actual, const char *msg, UNITY_LINE_TYPE line)
{
    double delta = expected * UNITY_DOUBLE_REL;
    if (expected == actual) {
        return;
    }
    if (!within_double(delta, expected, actual)) {
        float_fail(delta, expected, actual, 0, 17, msg, line);
    }
}

void UnityAssertFloatSpecial(double value, int want_nan, int want_inf, int negate, const char *msg,
                             UNITY_LINE_TYPE line)
{
    int is = 0;
    if (want_nan) {
        is = double_is_nan(value);
    } else if (want_inf) {
        is = double_is_inf(value);
    }
    if (is != negate) {
        return;
    }
    fail_begin(line);
    printf("Expected %s%s Was %.17g", negate ? "not " : "", want_nan ? "NaN" : "Inf", value);
    tail(msg);
    bail();
}
