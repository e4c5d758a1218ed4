/* The firmware options of include/leptrino/config.h, as this build was made
 * (CMake passes what it asked for as LEP_TEST_WANT_*): each option takes its
 * whole feature out, and what remains works (the frame, message and, with the
 * device, client tests run in the same build). */
#include <stddef.h>

#include "leptrino/leptrino.h"
#include "unity.h"

#ifndef LEP_TEST_WANT_NO_DEVICE
#error "LEP_TEST_WANT_NO_DEVICE is set by test/CMakeLists.txt"
#endif
#ifndef LEP_TEST_WANT_NO_ERROR_STRINGS
#error "LEP_TEST_WANT_NO_ERROR_STRINGS is set by test/CMakeLists.txt"
#endif

void setUp(void)
{
}

void tearDown(void)
{
}

/* The headers see the options the library was built with. */
static void test_headers_see_the_build_options(void)
{
    TEST_ASSERT_EQUAL_INT(!LEP_TEST_WANT_NO_DEVICE, LEP_HAVE_DEVICE);
    TEST_ASSERT_EQUAL_INT(!LEP_TEST_WANT_NO_ERROR_STRINGS, LEP_HAVE_ERROR_STRINGS);
}

/* Without error strings every text is "" (never NULL); with them none is. */
static void test_error_strings(void)
{
    int err;
    unsigned result;
    for (err = 1; err >= LEP_E_STALLED - 2; err--) {
        const char *s = lep_strerror(err);
        TEST_ASSERT_NOT_NULL(s);
        TEST_ASSERT_EQUAL_INT(LEP_HAVE_ERROR_STRINGS, s[0] != '\0');
    }
    for (result = 0; result <= 0xFFu; result++) {
        const char *s = lep_result_str((uint8_t)result);
        TEST_ASSERT_NOT_NULL(s);
        TEST_ASSERT_EQUAL_INT(LEP_HAVE_ERROR_STRINGS, s[0] != '\0');
    }
}

#if LEP_HAVE_DEVICE
/* With the device side, its functions are there and work. */
static void test_device_side_present(void)
{
    lep_sample s = { { 0, 0, 0, 0, 0, 0 }, 0, 0 };
    uint8_t out[LEP_MAX_FRAME];
    size_t n = 0;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_device_stream_frame(&s, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_size_t(25u, n);
}
#endif

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_headers_see_the_build_options);
    RUN_TEST(test_error_strings);
#if LEP_HAVE_DEVICE
    RUN_TEST(test_device_side_present);
#endif
    return UNITY_END();
}
