/* A small Unity-compatible test harness for leptrino's tests.
 *
 * Written for this project from the public description of the Unity test
 * framework's API: the same macro names and argument order, the same summary
 * output, so the tests also build against upstream Unity (LEPTRINO_UNITY_DIR).
 * Only the subset leptrino uses is here; prefer names upstream has too
 * (TEST_ASSERT_EQUAL_size_t rather than the local alias _SIZE_T).
 *
 * Usage: define void setUp(void) and void tearDown(void) in the test file,
 * then in main(): UNITY_BEGIN(); RUN_TEST(test_x); ... return UNITY_END();
 * A failed assertion ends the current test (longjmp), runs tearDown and goes
 * on with the next test. UNITY_END() prints the summary and returns the
 * number of failed tests. */
#ifndef LEP_UNITY_H
#define LEP_UNITY_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Provided by the test file, run around every test. */
void setUp(void);
void tearDown(void);

typedef void (*UnityTestFunction)(void);

/* Number display styles for the failure text. */
typedef enum {
    UNITY_DISPLAY_STYLE_INT = 0,
    UNITY_DISPLAY_STYLE_UINT,
    UNITY_DISPLAY_STYLE_HEX8,
    UNITY_DISPLAY_STYLE_HEX16,
    UNITY_DISPLAY_STYLE_HEX32,
    UNITY_DISPLAY_STYLE_HEX64,
    UNITY_DISPLAY_STYLE_CHAR
} UNITY_DISPLAY_STYLE_T;

/* Comparison kinds for the ordering asserts: actual <op> threshold. */
typedef enum {
    UNITY_GREATER_THAN = 0,
    UNITY_GREATER_OR_EQUAL,
    UNITY_SMALLER_THAN,
    UNITY_SMALLER_OR_EQUAL,
    UNITY_NOT_EQUAL
} UNITY_COMPARISON_T;

/* Element types of the array asserts. */
typedef enum {
    UNITY_ARRAY_INT8 = 0,
    UNITY_ARRAY_INT16,
    UNITY_ARRAY_INT32,
    UNITY_ARRAY_INT64,
    UNITY_ARRAY_INT,
    UNITY_ARRAY_UINT8,
    UNITY_ARRAY_UINT16,
    UNITY_ARRAY_UINT32,
    UNITY_ARRAY_UINT64,
    UNITY_ARRAY_UINT,
    UNITY_ARRAY_HEX8,
    UNITY_ARRAY_HEX16,
    UNITY_ARRAY_HEX32
} UNITY_ARRAY_T;

/* ---- runner ------------------------------------------------------------ */

void UnityBegin(const char *file);
int UnityEnd(void);
void UnityDefaultTestRun(UnityTestFunction func, const char *name, int line);

#define UNITY_BEGIN() UnityBegin(__FILE__)
#define UNITY_END() UnityEnd()
#define RUN_TEST(func) UnityDefaultTestRun(func, #func, __LINE__)

/* ---- engine (called by the macros) ------------------------------------- */

typedef unsigned int UNITY_LINE_TYPE;

/* Bundled harness only (not in upstream Unity): the text a failure message
 * shows for a number, written into out[0..cap) (NUL-terminated, truncated to
 * fit); returns the full length. Formatted without printf's 64-bit
 * conversions, which newlib-nano lacks. */
size_t UnityFormatNumber(char *out, size_t cap, uint64_t bits, int is_signed,
                         UNITY_DISPLAY_STYLE_T style);

void UnityFail(const char *msg, UNITY_LINE_TYPE line);
void UnityIgnore(const char *msg, UNITY_LINE_TYPE line);
void UnityPass(void);
void UnityMessage(const char *msg, UNITY_LINE_TYPE line);
void UnityAssertTrue(int condition, const char *what, const char *msg, UNITY_LINE_TYPE line);
void UnityAssertEqualSigned(int64_t expected, int64_t actual, const char *msg, UNITY_LINE_TYPE line,
                            UNITY_DISPLAY_STYLE_T style);
void UnityAssertEqualUnsigned(uint64_t expected, uint64_t actual, const char *msg,
                              UNITY_LINE_TYPE line, UNITY_DISPLAY_STYLE_T style);
void UnityAssertCompareSigned(int64_t threshold, int64_t actual, UNITY_COMPARISON_T cmp,
                              const char *msg, UNITY_LINE_TYPE line);
void UnityAssertCompareUnsigned(uint64_t threshold, uint64_t actual, UNITY_COMPARISON_T cmp,
                                const char *msg, UNITY_LINE_TYPE line, UNITY_DISPLAY_STYLE_T style);
void UnityAssertSignedWithin(uint64_t delta, int64_t expected, int64_t actual, const char *msg,
                             UNITY_LINE_TYPE line);
void UnityAssertUnsignedWithin(uint64_t delta, uint64_t expected, uint64_t actual, const char *msg,
                               UNITY_LINE_TYPE line, UNITY_DISPLAY_STYLE_T style);
void UnityAssertEqualString(const char *expected, const char *actual, const char *msg,
                            UNITY_LINE_TYPE line);
void UnityAssertEqualStringLen(const char *expected, const char *actual, size_t len,
                               const char *msg, UNITY_LINE_TYPE line);
void UnityAssertEqualMemory(const void *expected, const void *actual, size_t len, const char *msg,
                            UNITY_LINE_TYPE line);
void UnityAssertEqualArray(const void *expected, const void *actual, size_t count,
                           UNITY_ARRAY_T type, const char *msg, UNITY_LINE_TYPE line);
void UnityAssertFloatsWithin(float delta, float expected, float actual, const char *msg,
                             UNITY_LINE_TYPE line);
void UnityAssertEqualFloat(float expected, float actual, const char *msg, UNITY_LINE_TYPE line);
void UnityAssertDoublesWithin(double delta, double expected, double actual, const char *msg,
                              UNITY_LINE_TYPE line);
void UnityAssertEqualDouble(double expected, double actual, const char *msg, UNITY_LINE_TYPE line);
void UnityAssertFloatSpecial(double value, int want_nan, int want_inf, int negate, const char *msg,
                             UNITY_LINE_TYPE line);

#define UNITY_LINE ((UNITY_LINE_TYPE)(__LINE__))
#define UNITY_S(x) ((int64_t)(x))
#define UNITY_U(x) ((uint64_t)(x))

/* ---- basic ------------------------------------------------------------- */

#define TEST_FAIL_MESSAGE(message) UnityFail((message), UNITY_LINE)
#define TEST_FAIL() UnityFail(NULL, UNITY_LINE)
#define TEST_IGNORE_MESSAGE(message) UnityIgnore((message), UNITY_LINE)
#define TEST_IGNORE() UnityIgnore(NULL, UNITY_LINE)
#define TEST_MESSAGE(message) UnityMessage((message), UNITY_LINE)
#define TEST_PASS() UnityPass()
#define TEST_PASS_MESSAGE(message) (UnityMessage((message), UNITY_LINE), UnityPass())

#define TEST_ASSERT_MESSAGE(condition, message) \
    UnityAssertTrue((condition) ? 1 : 0, "Expression Evaluated To FALSE", (message), UNITY_LINE)
#define TEST_ASSERT(condition) TEST_ASSERT_MESSAGE(condition, NULL)
#define TEST_ASSERT_TRUE_MESSAGE(condition, message) \
    UnityAssertTrue((condition) ? 1 : 0, "Expected TRUE Was FALSE", (message), UNITY_LINE)
#define TEST_ASSERT_TRUE(condition) TEST_ASSERT_TRUE_MESSAGE(condition, NULL)
#define TEST_ASSERT_UNLESS_MESSAGE(condition, message) \
    UnityAssertTrue((condition) ? 0 : 1, "Expected FALSE Was TRUE", (message), UNITY_LINE)
#define TEST_ASSERT_UNLESS(condition) TEST_ASSERT_UNLESS_MESSAGE(condition, NULL)
#define TEST_ASSERT_FALSE_MESSAGE(condition, message) TEST_ASSERT_UNLESS_MESSAGE(condition, message)
#define TEST_ASSERT_FALSE(condition) TEST_ASSERT_UNLESS_MESSAGE(condition, NULL)
#define TEST_ASSERT_NULL_MESSAGE(pointer, message) \
    UnityAssertTrue(((pointer) == NULL) ? 1 : 0, "Expected NULL", (message), UNITY_LINE)
#define TEST_ASSERT_NULL(pointer) TEST_ASSERT_NULL_MESSAGE(pointer, NULL)
#define TEST_ASSERT_NOT_NULL_MESSAGE(pointer, message) \
    UnityAssertTrue(((pointer) != NULL) ? 1 : 0, "Expected Non-NULL", (message), UNITY_LINE)
#define TEST_ASSERT_NOT_NULL(pointer) TEST_ASSERT_NOT_NULL_MESSAGE(pointer, NULL)

/* ---- integers: equality ------------------------------------------------ */

#define UNITY_EQ_S(e, a, m, T)                                                \
    UnityAssertEqualSigned(UNITY_S((T)(e)), UNITY_S((T)(a)), (m), UNITY_LINE, \
                           UNITY_DISPLAY_STYLE_INT)
#define UNITY_EQ_U(e, a, m, T, style) \
    UnityAssertEqualUnsigned(UNITY_U((T)(e)), UNITY_U((T)(a)), (m), UNITY_LINE, (style))

#define TEST_ASSERT_EQUAL_INT_MESSAGE(e, a, m) UNITY_EQ_S(e, a, m, int)
#define TEST_ASSERT_EQUAL_INT8_MESSAGE(e, a, m) UNITY_EQ_S(e, a, m, int8_t)
#define TEST_ASSERT_EQUAL_INT16_MESSAGE(e, a, m) UNITY_EQ_S(e, a, m, int16_t)
#define TEST_ASSERT_EQUAL_INT32_MESSAGE(e, a, m) UNITY_EQ_S(e, a, m, int32_t)
#define TEST_ASSERT_EQUAL_INT64_MESSAGE(e, a, m) UNITY_EQ_S(e, a, m, int64_t)
#define TEST_ASSERT_EQUAL_UINT_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, unsigned int, UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_EQUAL_UINT8_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, uint8_t, UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_EQUAL_UINT16_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, uint16_t, UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_EQUAL_UINT32_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, uint32_t, UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_EQUAL_UINT64_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, uint64_t, UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_EQUAL_size_t_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, size_t, UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_EQUAL_HEX8_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, uint8_t, UNITY_DISPLAY_STYLE_HEX8)
#define TEST_ASSERT_EQUAL_HEX16_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, uint16_t, UNITY_DISPLAY_STYLE_HEX16)
#define TEST_ASSERT_EQUAL_HEX32_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, uint32_t, UNITY_DISPLAY_STYLE_HEX32)
#define TEST_ASSERT_EQUAL_HEX64_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, uint64_t, UNITY_DISPLAY_STYLE_HEX64)
#define TEST_ASSERT_EQUAL_CHAR_MESSAGE(e, a, m) \
    UNITY_EQ_U(e, a, m, unsigned char, UNITY_DISPLAY_STYLE_CHAR)
#define TEST_ASSERT_EQUAL_MESSAGE(e, a, m) TEST_ASSERT_EQUAL_INT_MESSAGE(e, a, m)
#define TEST_ASSERT_EQUAL_PTR_MESSAGE(e, a, m)                                       \
    UnityAssertEqualUnsigned(UNITY_U((uintptr_t)(const void *)(e)),                  \
                             UNITY_U((uintptr_t)(const void *)(a)), (m), UNITY_LINE, \
                             UNITY_DISPLAY_STYLE_HEX64)

#define TEST_ASSERT_EQUAL_INT(e, a) TEST_ASSERT_EQUAL_INT_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_INT8(e, a) TEST_ASSERT_EQUAL_INT8_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_INT16(e, a) TEST_ASSERT_EQUAL_INT16_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_INT32(e, a) TEST_ASSERT_EQUAL_INT32_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_INT64(e, a) TEST_ASSERT_EQUAL_INT64_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_UINT(e, a) TEST_ASSERT_EQUAL_UINT_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_UINT8(e, a) TEST_ASSERT_EQUAL_UINT8_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_UINT16(e, a) TEST_ASSERT_EQUAL_UINT16_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_UINT32(e, a) TEST_ASSERT_EQUAL_UINT32_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_UINT64(e, a) TEST_ASSERT_EQUAL_UINT64_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_size_t(e, a) TEST_ASSERT_EQUAL_size_t_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_HEX8(e, a) TEST_ASSERT_EQUAL_HEX8_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_HEX16(e, a) TEST_ASSERT_EQUAL_HEX16_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_HEX32(e, a) TEST_ASSERT_EQUAL_HEX32_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_HEX64(e, a) TEST_ASSERT_EQUAL_HEX64_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_CHAR(e, a) TEST_ASSERT_EQUAL_CHAR_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL(e, a) TEST_ASSERT_EQUAL_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_PTR(e, a) TEST_ASSERT_EQUAL_PTR_MESSAGE(e, a, NULL)
/* Local aliases (not in upstream Unity). */
#define TEST_ASSERT_EQUAL_SIZE_T_MESSAGE(e, a, m) TEST_ASSERT_EQUAL_size_t_MESSAGE(e, a, m)
#define TEST_ASSERT_EQUAL_SIZE_T(e, a) TEST_ASSERT_EQUAL_size_t(e, a)

#define TEST_ASSERT_NOT_EQUAL_MESSAGE(e, a, m) \
    UnityAssertCompareSigned(UNITY_S(e), UNITY_S(a), UNITY_NOT_EQUAL, (m), UNITY_LINE)
#define TEST_ASSERT_NOT_EQUAL(e, a) TEST_ASSERT_NOT_EQUAL_MESSAGE(e, a, NULL)
#define TEST_ASSERT_NOT_EQUAL_INT_MESSAGE(e, a, m) TEST_ASSERT_NOT_EQUAL_MESSAGE(e, a, m)
#define TEST_ASSERT_NOT_EQUAL_INT(e, a) TEST_ASSERT_NOT_EQUAL_MESSAGE(e, a, NULL)
#define TEST_ASSERT_NOT_EQUAL_UINT_MESSAGE(e, a, m)                                      \
    UnityAssertCompareUnsigned(UNITY_U(e), UNITY_U(a), UNITY_NOT_EQUAL, (m), UNITY_LINE, \
                               UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_NOT_EQUAL_UINT(e, a) TEST_ASSERT_NOT_EQUAL_UINT_MESSAGE(e, a, NULL)

/* ---- integers: ordering (passes when actual <op> threshold) ------------ */

#define UNITY_CMP_S(t, a, op, m, T) \
    UnityAssertCompareSigned(UNITY_S((T)(t)), UNITY_S((T)(a)), (op), (m), UNITY_LINE)
#define UNITY_CMP_U(t, a, op, m, T)                                                     \
    UnityAssertCompareUnsigned(UNITY_U((T)(t)), UNITY_U((T)(a)), (op), (m), UNITY_LINE, \
                               UNITY_DISPLAY_STYLE_UINT)

#define TEST_ASSERT_GREATER_THAN_MESSAGE(t, a, m) UNITY_CMP_S(t, a, UNITY_GREATER_THAN, m, int)
#define TEST_ASSERT_GREATER_THAN_INT_MESSAGE(t, a, m) UNITY_CMP_S(t, a, UNITY_GREATER_THAN, m, int)
#define TEST_ASSERT_GREATER_THAN_INT32_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_GREATER_THAN, m, int32_t)
#define TEST_ASSERT_GREATER_THAN_INT64_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_GREATER_THAN, m, int64_t)
#define TEST_ASSERT_GREATER_THAN_UINT_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_GREATER_THAN, m, unsigned int)
#define TEST_ASSERT_GREATER_THAN_UINT32_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_GREATER_THAN, m, uint32_t)
#define TEST_ASSERT_GREATER_THAN_UINT64_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_GREATER_THAN, m, uint64_t)
#define TEST_ASSERT_GREATER_THAN_size_t_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_GREATER_THAN, m, size_t)
#define TEST_ASSERT_LESS_THAN_MESSAGE(t, a, m) UNITY_CMP_S(t, a, UNITY_SMALLER_THAN, m, int)
#define TEST_ASSERT_LESS_THAN_INT_MESSAGE(t, a, m) UNITY_CMP_S(t, a, UNITY_SMALLER_THAN, m, int)
#define TEST_ASSERT_LESS_THAN_INT32_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_SMALLER_THAN, m, int32_t)
#define TEST_ASSERT_LESS_THAN_INT64_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_SMALLER_THAN, m, int64_t)
#define TEST_ASSERT_LESS_THAN_UINT_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_SMALLER_THAN, m, unsigned int)
#define TEST_ASSERT_LESS_THAN_UINT32_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_SMALLER_THAN, m, uint32_t)
#define TEST_ASSERT_LESS_THAN_UINT64_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_SMALLER_THAN, m, uint64_t)
#define TEST_ASSERT_LESS_THAN_size_t_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_SMALLER_THAN, m, size_t)
#define TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_GREATER_OR_EQUAL, m, int)
#define TEST_ASSERT_GREATER_OR_EQUAL_INT_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_GREATER_OR_EQUAL, m, int)
#define TEST_ASSERT_GREATER_OR_EQUAL_INT32_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_GREATER_OR_EQUAL, m, int32_t)
#define TEST_ASSERT_GREATER_OR_EQUAL_INT64_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_GREATER_OR_EQUAL, m, int64_t)
#define TEST_ASSERT_GREATER_OR_EQUAL_UINT_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_GREATER_OR_EQUAL, m, unsigned int)
#define TEST_ASSERT_GREATER_OR_EQUAL_UINT32_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_GREATER_OR_EQUAL, m, uint32_t)
#define TEST_ASSERT_GREATER_OR_EQUAL_UINT64_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_GREATER_OR_EQUAL, m, uint64_t)
#define TEST_ASSERT_GREATER_OR_EQUAL_size_t_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_GREATER_OR_EQUAL, m, size_t)
#define TEST_ASSERT_LESS_OR_EQUAL_MESSAGE(t, a, m) UNITY_CMP_S(t, a, UNITY_SMALLER_OR_EQUAL, m, int)
#define TEST_ASSERT_LESS_OR_EQUAL_INT_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_SMALLER_OR_EQUAL, m, int)
#define TEST_ASSERT_LESS_OR_EQUAL_INT32_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_SMALLER_OR_EQUAL, m, int32_t)
#define TEST_ASSERT_LESS_OR_EQUAL_INT64_MESSAGE(t, a, m) \
    UNITY_CMP_S(t, a, UNITY_SMALLER_OR_EQUAL, m, int64_t)
#define TEST_ASSERT_LESS_OR_EQUAL_UINT_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_SMALLER_OR_EQUAL, m, unsigned int)
#define TEST_ASSERT_LESS_OR_EQUAL_UINT32_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_SMALLER_OR_EQUAL, m, uint32_t)
#define TEST_ASSERT_LESS_OR_EQUAL_UINT64_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_SMALLER_OR_EQUAL, m, uint64_t)
#define TEST_ASSERT_LESS_OR_EQUAL_size_t_MESSAGE(t, a, m) \
    UNITY_CMP_U(t, a, UNITY_SMALLER_OR_EQUAL, m, size_t)

#define TEST_ASSERT_GREATER_THAN(t, a) TEST_ASSERT_GREATER_THAN_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_THAN_INT(t, a) TEST_ASSERT_GREATER_THAN_INT_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_THAN_INT32(t, a) TEST_ASSERT_GREATER_THAN_INT32_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_THAN_INT64(t, a) TEST_ASSERT_GREATER_THAN_INT64_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_THAN_UINT(t, a) TEST_ASSERT_GREATER_THAN_UINT_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_THAN_UINT32(t, a) TEST_ASSERT_GREATER_THAN_UINT32_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_THAN_UINT64(t, a) TEST_ASSERT_GREATER_THAN_UINT64_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_THAN_size_t(t, a) TEST_ASSERT_GREATER_THAN_size_t_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_THAN(t, a) TEST_ASSERT_LESS_THAN_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_THAN_INT(t, a) TEST_ASSERT_LESS_THAN_INT_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_THAN_INT32(t, a) TEST_ASSERT_LESS_THAN_INT32_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_THAN_INT64(t, a) TEST_ASSERT_LESS_THAN_INT64_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_THAN_UINT(t, a) TEST_ASSERT_LESS_THAN_UINT_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_THAN_UINT32(t, a) TEST_ASSERT_LESS_THAN_UINT32_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_THAN_UINT64(t, a) TEST_ASSERT_LESS_THAN_UINT64_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_THAN_size_t(t, a) TEST_ASSERT_LESS_THAN_size_t_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL(t, a) TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL_INT(t, a) TEST_ASSERT_GREATER_OR_EQUAL_INT_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL_INT32(t, a) \
    TEST_ASSERT_GREATER_OR_EQUAL_INT32_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL_INT64(t, a) \
    TEST_ASSERT_GREATER_OR_EQUAL_INT64_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL_UINT(t, a) \
    TEST_ASSERT_GREATER_OR_EQUAL_UINT_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL_UINT32(t, a) \
    TEST_ASSERT_GREATER_OR_EQUAL_UINT32_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL_UINT64(t, a) \
    TEST_ASSERT_GREATER_OR_EQUAL_UINT64_MESSAGE(t, a, NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL_size_t(t, a) \
    TEST_ASSERT_GREATER_OR_EQUAL_size_t_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_OR_EQUAL(t, a) TEST_ASSERT_LESS_OR_EQUAL_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_OR_EQUAL_INT(t, a) TEST_ASSERT_LESS_OR_EQUAL_INT_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_OR_EQUAL_INT32(t, a) TEST_ASSERT_LESS_OR_EQUAL_INT32_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_OR_EQUAL_INT64(t, a) TEST_ASSERT_LESS_OR_EQUAL_INT64_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_OR_EQUAL_UINT(t, a) TEST_ASSERT_LESS_OR_EQUAL_UINT_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_OR_EQUAL_UINT32(t, a) TEST_ASSERT_LESS_OR_EQUAL_UINT32_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_OR_EQUAL_UINT64(t, a) TEST_ASSERT_LESS_OR_EQUAL_UINT64_MESSAGE(t, a, NULL)
#define TEST_ASSERT_LESS_OR_EQUAL_size_t(t, a) TEST_ASSERT_LESS_OR_EQUAL_size_t_MESSAGE(t, a, NULL)

/* ---- integers: within a delta ----------------------------------------- */

#define TEST_ASSERT_INT_WITHIN_MESSAGE(d, e, a, m) \
    UnityAssertSignedWithin(UNITY_U(d), UNITY_S((int)(e)), UNITY_S((int)(a)), (m), UNITY_LINE)
#define TEST_ASSERT_INT32_WITHIN_MESSAGE(d, e, a, m)                                       \
    UnityAssertSignedWithin(UNITY_U(d), UNITY_S((int32_t)(e)), UNITY_S((int32_t)(a)), (m), \
                            UNITY_LINE)
#define TEST_ASSERT_INT64_WITHIN_MESSAGE(d, e, a, m)                                       \
    UnityAssertSignedWithin(UNITY_U(d), UNITY_S((int64_t)(e)), UNITY_S((int64_t)(a)), (m), \
                            UNITY_LINE)
#define TEST_ASSERT_UINT_WITHIN_MESSAGE(d, e, a, m)                                               \
    UnityAssertUnsignedWithin(UNITY_U(d), UNITY_U((unsigned int)(e)), UNITY_U((unsigned int)(a)), \
                              (m), UNITY_LINE, UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_UINT32_WITHIN_MESSAGE(d, e, a, m)                                          \
    UnityAssertUnsignedWithin(UNITY_U(d), UNITY_U((uint32_t)(e)), UNITY_U((uint32_t)(a)), (m), \
                              UNITY_LINE, UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_UINT64_WITHIN_MESSAGE(d, e, a, m)                                          \
    UnityAssertUnsignedWithin(UNITY_U(d), UNITY_U((uint64_t)(e)), UNITY_U((uint64_t)(a)), (m), \
                              UNITY_LINE, UNITY_DISPLAY_STYLE_UINT)
#define TEST_ASSERT_INT_WITHIN(d, e, a) TEST_ASSERT_INT_WITHIN_MESSAGE(d, e, a, NULL)
#define TEST_ASSERT_INT32_WITHIN(d, e, a) TEST_ASSERT_INT32_WITHIN_MESSAGE(d, e, a, NULL)
#define TEST_ASSERT_INT64_WITHIN(d, e, a) TEST_ASSERT_INT64_WITHIN_MESSAGE(d, e, a, NULL)
#define TEST_ASSERT_UINT_WITHIN(d, e, a) TEST_ASSERT_UINT_WITHIN_MESSAGE(d, e, a, NULL)
#define TEST_ASSERT_UINT32_WITHIN(d, e, a) TEST_ASSERT_UINT32_WITHIN_MESSAGE(d, e, a, NULL)
#define TEST_ASSERT_UINT64_WITHIN(d, e, a) TEST_ASSERT_UINT64_WITHIN_MESSAGE(d, e, a, NULL)

/* ---- bits -------------------------------------------------------------- */

#define TEST_ASSERT_BITS_MESSAGE(mask, e, a, m)                                           \
    UnityAssertEqualUnsigned(UNITY_U(e) & UNITY_U(mask), UNITY_U(a) & UNITY_U(mask), (m), \
                             UNITY_LINE, UNITY_DISPLAY_STYLE_HEX32)
#define TEST_ASSERT_BITS(mask, e, a) TEST_ASSERT_BITS_MESSAGE(mask, e, a, NULL)
#define TEST_ASSERT_BITS_HIGH(mask, a) TEST_ASSERT_BITS_MESSAGE(mask, UINT64_MAX, a, NULL)
#define TEST_ASSERT_BITS_LOW(mask, a) TEST_ASSERT_BITS_MESSAGE(mask, 0u, a, NULL)
#define TEST_ASSERT_BIT_HIGH(bit, a) \
    TEST_ASSERT_BITS_MESSAGE(UNITY_U(1) << (bit), UINT64_MAX, a, NULL)
#define TEST_ASSERT_BIT_LOW(bit, a) TEST_ASSERT_BITS_MESSAGE(UNITY_U(1) << (bit), 0u, a, NULL)

/* ---- strings, memory, arrays ------------------------------------------ */

#define TEST_ASSERT_EQUAL_STRING_MESSAGE(e, a, m) UnityAssertEqualString((e), (a), (m), UNITY_LINE)
#define TEST_ASSERT_EQUAL_STRING(e, a) TEST_ASSERT_EQUAL_STRING_MESSAGE(e, a, NULL)
#define TEST_ASSERT_EQUAL_STRING_LEN_MESSAGE(e, a, n, m) \
    UnityAssertEqualStringLen((e), (a), (size_t)(n), (m), UNITY_LINE)
#define TEST_ASSERT_EQUAL_STRING_LEN(e, a, n) TEST_ASSERT_EQUAL_STRING_LEN_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_MEMORY_MESSAGE(e, a, n, m) \
    UnityAssertEqualMemory((e), (a), (size_t)(n), (m), UNITY_LINE)
#define TEST_ASSERT_EQUAL_MEMORY(e, a, n) TEST_ASSERT_EQUAL_MEMORY_MESSAGE(e, a, n, NULL)

#define UNITY_ARR(e, a, n, T, m) UnityAssertEqualArray((e), (a), (size_t)(n), (T), (m), UNITY_LINE)
#define TEST_ASSERT_EQUAL_INT8_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_INT8, m)
#define TEST_ASSERT_EQUAL_INT16_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_INT16, m)
#define TEST_ASSERT_EQUAL_INT32_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_INT32, m)
#define TEST_ASSERT_EQUAL_INT64_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_INT64, m)
#define TEST_ASSERT_EQUAL_INT_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_INT, m)
#define TEST_ASSERT_EQUAL_UINT8_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_UINT8, m)
#define TEST_ASSERT_EQUAL_UINT16_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_UINT16, m)
#define TEST_ASSERT_EQUAL_UINT32_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_UINT32, m)
#define TEST_ASSERT_EQUAL_UINT64_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_UINT64, m)
#define TEST_ASSERT_EQUAL_UINT_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_UINT, m)
#define TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_HEX8, m)
#define TEST_ASSERT_EQUAL_HEX16_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_HEX16, m)
#define TEST_ASSERT_EQUAL_HEX32_ARRAY_MESSAGE(e, a, n, m) UNITY_ARR(e, a, n, UNITY_ARRAY_HEX32, m)
#define TEST_ASSERT_EQUAL_INT8_ARRAY(e, a, n) TEST_ASSERT_EQUAL_INT8_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_INT16_ARRAY(e, a, n) TEST_ASSERT_EQUAL_INT16_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_INT32_ARRAY(e, a, n) TEST_ASSERT_EQUAL_INT32_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_INT64_ARRAY(e, a, n) TEST_ASSERT_EQUAL_INT64_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_INT_ARRAY(e, a, n) TEST_ASSERT_EQUAL_INT_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_UINT8_ARRAY(e, a, n) TEST_ASSERT_EQUAL_UINT8_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_UINT16_ARRAY(e, a, n) \
    TEST_ASSERT_EQUAL_UINT16_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_UINT32_ARRAY(e, a, n) \
    TEST_ASSERT_EQUAL_UINT32_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_UINT64_ARRAY(e, a, n) \
    TEST_ASSERT_EQUAL_UINT64_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_UINT_ARRAY(e, a, n) TEST_ASSERT_EQUAL_UINT_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_HEX8_ARRAY(e, a, n) TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_HEX16_ARRAY(e, a, n) TEST_ASSERT_EQUAL_HEX16_ARRAY_MESSAGE(e, a, n, NULL)
#define TEST_ASSERT_EQUAL_HEX32_ARRAY(e, a, n) TEST_ASSERT_EQUAL_HEX32_ARRAY_MESSAGE(e, a, n, NULL)

/* ---- floating point ---------------------------------------------------- */

#define TEST_ASSERT_FLOAT_WITHIN_MESSAGE(d, e, a, m) \
    UnityAssertFloatsWithin((float)(d), (float)(e), (float)(a), (m), UNITY_LINE)
#define TEST_ASSERT_FLOAT_WITHIN(d, e, a) TEST_ASSERT_FLOAT_WITHIN_MESSAGE(d, e, a, NULL)
#define TEST_ASSERT_EQUAL_FLOAT_MESSAGE(e, a, m) \
    UnityAssertEqualFloat((float)(e), (float)(a), (m), UNITY_LINE)
#define TEST_ASSERT_EQUAL_FLOAT(e, a) TEST_ASSERT_EQUAL_FLOAT_MESSAGE(e, a, NULL)
#define TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(d, e, a, m) \
    UnityAssertDoublesWithin((double)(d), (double)(e), (double)(a), (m), UNITY_LINE)
#define TEST_ASSERT_DOUBLE_WITHIN(d, e, a) TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(d, e, a, NULL)
#define TEST_ASSERT_EQUAL_DOUBLE_MESSAGE(e, a, m) \
    UnityAssertEqualDouble((double)(e), (double)(a), (m), UNITY_LINE)
#define TEST_ASSERT_EQUAL_DOUBLE(e, a) TEST_ASSERT_EQUAL_DOUBLE_MESSAGE(e, a, NULL)
#define TEST_ASSERT_FLOAT_IS_NAN(a) UnityAssertFloatSpecial((double)(a), 1, 0, 0, NULL, UNITY_LINE)
#define TEST_ASSERT_FLOAT_IS_NOT_NAN(a) \
    UnityAssertFloatSpecial((double)(a), 1, 0, 1, NULL, UNITY_LINE)
#define TEST_ASSERT_FLOAT_IS_INF(a) UnityAssertFloatSpecial((double)(a), 0, 1, 0, NULL, UNITY_LINE)
#define TEST_ASSERT_FLOAT_IS_NOT_INF(a) \
    UnityAssertFloatSpecial((double)(a), 0, 1, 1, NULL, UNITY_LINE)
#define TEST_ASSERT_DOUBLE_IS_NAN(a) TEST_ASSERT_FLOAT_IS_NAN(a)
#define TEST_ASSERT_DOUBLE_IS_NOT_NAN(a) TEST_ASSERT_FLOAT_IS_NOT_NAN(a)
#define TEST_ASSERT_DOUBLE_IS_INF(a) TEST_ASSERT_FLOAT_IS_INF(a)
#define TEST_ASSERT_DOUBLE_IS_NOT_INF(a) TEST_ASSERT_FLOAT_IS_NOT_INF(a)

#ifdef __cplusplus
}
#endif

#endif
