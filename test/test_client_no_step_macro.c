/* LEP_CONFIG_NO_STEP_MACRO: with it defined before the headers, a member
 * named lep_client_step (a table of operations) compiles and calls the
 * library's function, fed one byte at a time like the macro's callers. */
#define LEP_CONFIG_NO_STEP_MACRO 1

#include <string.h>

#include "script_io.h"
#include "unity.h"

#if defined(lep_client_step)
#error "LEP_CONFIG_NO_STEP_MACRO must leave lep_client_step a function"
#endif

struct client_ops {
    int (*lep_client_step)(lep_client *c, const uint8_t *data, size_t len, size_t *consumed);
};

static script_io sio;
static lep_client client;

void setUp(void)
{
    script_io_client(&sio, &client);
}

void tearDown(void)
{
}

static void test_member_of_the_same_name_calls_the_function(void)
{
    const struct client_ops ops = { lep_client_step };
    uint8_t wire[3 * 29];
    size_t len;
    size_t used;
    size_t i;
    unsigned got = 0;
    lep_sample s;
    static const uint8_t dle = 0x10;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, ops.lep_client_step(NULL, &dle, 1, &used));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    len = script_take_data(&sio, 3, wire, sizeof(wire));
    for (i = 0; i < len; i++) {
        int rc = ops.lep_client_step(&client, wire + i, 1, &used);
        TEST_ASSERT_EQUAL_size_t(1, used);
        if (rc == LEP_STEP_SAMPLE) {
            TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_get_sample(&client, &s));
            TEST_ASSERT_EQUAL_UINT16(got, s.reserved);
            got++;
        } else {
            TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, rc);
        }
    }
    TEST_ASSERT_EQUAL_UINT(3, got);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_member_of_the_same_name_calls_the_function);
    return UNITY_END();
}
