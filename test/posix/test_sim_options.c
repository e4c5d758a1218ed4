/* The virtual sensor's option table: one description, parsing and checks. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "leptrino/leptrino.h"
#include "leptrino/sim.h"
#include "struct_api.h"
#include "unity.h"

static lep_sim_options o;
static char err[256];

void setUp(void)
{
    lep_sim_options_init(&o);
    err[0] = '\0';
}

void tearDown(void)
{
}

static void set_ok(const char *name, const char *value)
{
    int rc = lep_sim_option_set(&o, name, value, err, sizeof err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, rc, err);
}

/* A rejected value: LEP_E_ARG, o unchanged, one line naming the option and needle. */
static void set_bad(const char *name, const char *value, const char *needle)
{
    lep_sim_options before = o;
    const lep_sim_option_info *in = lep_sim_option_find(name);
    int rc = lep_sim_option_set(&o, name, value, err, sizeof err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_E_ARG, rc, name);
    TEST_ASSERT_EQUAL_MEMORY(&before, &o, sizeof o);
    TEST_ASSERT_NULL_MESSAGE(strchr(err, '\n'), err);
    if (in != NULL)
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, strncmp(err, in->name, strlen(in->name)), err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, needle), err);
}

static void test_table_is_complete_and_consistent(void)
{
    size_t i, n = lep_sim_option_count();
    TEST_ASSERT_EQUAL_size_t(28, n); /* one row per field of lep_sim_options */
    TEST_ASSERT_NULL(lep_sim_option_at(n));
    for (i = 0; i < n; i++) {
        const lep_sim_option_info *in = lep_sim_option_at(i);
        char buf[600];
        TEST_ASSERT_NOT_NULL(in);
        TEST_ASSERT_NOT_NULL(in->name);
        TEST_ASSERT_NULL_MESSAGE(strchr(in->name, '_'), in->name); /* dash-separated */
        TEST_ASSERT_NOT_NULL(in->help);
        TEST_ASSERT_TRUE_MESSAGE(strlen(in->help) > 10, in->name);
        TEST_ASSERT_EQUAL_PTR(in, lep_sim_option_find(in->name));
        TEST_ASSERT_EQUAL_INT_MESSAGE(in->type == LEP_SIM_OPT_FLAG, in->arg == NULL, in->name);
        TEST_ASSERT_TRUE_MESSAGE(in->min <= in->max, in->name);
        /* the defaults are the table's default texts, and read back as them */
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_get(&o, in->name, buf, sizeof buf));
        if (in->default_text != NULL)
            TEST_ASSERT_EQUAL_STRING_MESSAGE(in->default_text, buf, in->name);
        else
            TEST_ASSERT_TRUE_MESSAGE(strcmp(buf, "0") == 0 || buf[0] == '\0', in->name);
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_options_check(&o, err, sizeof err));
}

static void test_defaults(void)
{
    TEST_ASSERT_EQUAL_STRING("PFS055YA501U6", o.model);
    TEST_ASSERT_EQUAL_STRING("00000001", o.serial);
    TEST_ASSERT_EQUAL_STRING("1.13", o.firmware);
    TEST_ASSERT_EQUAL_DOUBLE(1200.0, o.rate_hz);
    TEST_ASSERT_EQUAL_DOUBLE(0.2, o.amplitude);
    TEST_ASSERT_EQUAL_DOUBLE(0.005, o.noise);
    TEST_ASSERT_EQUAL_DOUBLE(0.1, o.overload_duration_s);
    TEST_ASSERT_EQUAL_UINT64(1, o.seed);
    TEST_ASSERT_EQUAL_INT(-1, o.reopen_after_ms);
    TEST_ASSERT_EQUAL_STRING("", o.link);
    TEST_ASSERT_EQUAL_STRING("", o.replay_csv);
    TEST_ASSERT_FALSE(o.constant);
}

/* payload and gravity: comma-separated numbers, each range-checked, read back
 * as set; a negative mass is refused by the one check. */
static void test_payload_and_gravity(void)
{
    char buf[128];
    TEST_ASSERT_EQUAL_INT(LEP_SIM_OPT_NUMBERS, lep_sim_option_find("payload")->type);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, o.payload[0]);
    TEST_ASSERT_EQUAL_DOUBLE(-9.80665, o.gravity[2]);
    set_ok("payload", "1.5,0.01,-0.02,0.1");
    TEST_ASSERT_EQUAL_DOUBLE(1.5, o.payload[0]);
    TEST_ASSERT_EQUAL_DOUBLE(-0.02, o.payload[2]);
    TEST_ASSERT_EQUAL_DOUBLE(0.1, o.payload[3]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_get(&o, "payload", buf, sizeof buf));
    TEST_ASSERT_EQUAL_STRING("1.5,0.01,-0.02,0.1", buf);
    TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER, lep_sim_option_get(&o, "payload", buf, 8));
    TEST_ASSERT_EQUAL_STRING("", buf);
    set_ok("gravity", "9.80665,0,0");
    TEST_ASSERT_EQUAL_DOUBLE(9.80665, o.gravity[0]);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, o.gravity[2]);
    set_bad("payload", "1,2,3", "4 comma-separated numbers (M,CX,CY,CZ)");
    set_bad("payload", "1,2,3,4,5", "4 comma-separated");
    set_bad("payload", "1,nan,0,0", "each from -1000 to 1000");
    set_bad("payload", "1,0,0,inf", "comma-separated");
    set_bad("payload", "1,,0,0", "comma-separated");
    set_bad("payload", "1, 0,0,0", "comma-separated");
    set_bad("gravity", "0,0", "3 comma-separated numbers (GX,GY,GZ)");
    set_bad("gravity", "0,0,-200", "from -100 to 100");
    set_bad("gravity", NULL, "needs a value");
    set_ok("payload", "-1,0,0,0"); /* in range; the mass is checked with the whole */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(&o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "payload mass -1: expected >= 0"), err);
    o.gravity[1] = NAN;
    set_ok("payload", "0,0,0,0");
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(&o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "gravity: value 2 is nan"), err);
}

static void test_find_accepts_python_names(void)
{
    const lep_sim_option_info *in = lep_sim_option_find("output-rate-field");
    TEST_ASSERT_NOT_NULL(in);
    TEST_ASSERT_EQUAL_PTR(in, lep_sim_option_find("output_rate_field"));
    TEST_ASSERT_EQUAL_PTR(lep_sim_option_find("rate"), lep_sim_option_find("rate_hz"));
    TEST_ASSERT_EQUAL_PTR(lep_sim_option_find("nak"), lep_sim_option_find("p_nak"));
    TEST_ASSERT_EQUAL_PTR(lep_sim_option_find("replay"), lep_sim_option_find("replay_csv"));
    TEST_ASSERT_EQUAL_PTR(lep_sim_option_find("stall-after"), lep_sim_option_find("stall_after_s"));
    TEST_ASSERT_EQUAL_PTR(lep_sim_option_find("stall-after"), lep_sim_option_find("stall_after"));
    TEST_ASSERT_NULL(lep_sim_option_find("stall-after-s"));
    TEST_ASSERT_NULL(lep_sim_option_find("bogus"));
    TEST_ASSERT_NULL(lep_sim_option_find(""));
    TEST_ASSERT_NULL(lep_sim_option_find(NULL));
    TEST_ASSERT_NULL(lep_sim_option_find("rate-hz")); /* field names as written only */
}

static void test_set_every_type(void)
{
    set_ok("model", "CFS018CA201U");
    TEST_ASSERT_EQUAL_STRING("CFS018CA201U", o.model);
    set_ok("serial", "1234");
    TEST_ASSERT_EQUAL_STRING("1234", o.serial);
    set_ok("firmware", "2.0a");
    TEST_ASSERT_EQUAL_STRING("2.0a", o.firmware);
    set_ok("output-rate-field", NULL);
    TEST_ASSERT_TRUE(o.output_rate_field);
    set_ok("output_rate_field", "false");
    TEST_ASSERT_FALSE(o.output_rate_field);
    set_ok("constant", "1");
    TEST_ASSERT_TRUE(o.constant);
    set_ok("constant", "0");
    TEST_ASSERT_FALSE(o.constant);
    set_ok("filter", "3");
    TEST_ASSERT_EQUAL_UINT8(3, o.filter);
    set_ok("rate", "2500.5");
    TEST_ASSERT_EQUAL_DOUBLE(2500.5, o.rate_hz);
    set_ok("seed", "18446744073709551615");
    TEST_ASSERT_EQUAL_UINT64(UINT64_MAX, o.seed);
    set_ok("amplitude", "3.5"); /* the drift of issue 9: accepted everywhere now */
    TEST_ASSERT_EQUAL_DOUBLE(3.5, o.amplitude);
    set_ok("p_nak", "0.25");
    TEST_ASSERT_EQUAL_DOUBLE(0.25, o.p_nak);
    set_ok("stall", "250");
    TEST_ASSERT_EQUAL_INT(250, o.stall_ms);
    set_ok("stall_after_s", "1.5");
    TEST_ASSERT_EQUAL_DOUBLE(1.5, o.stall_after_s);
    set_ok("reopen-after", "-1");
    TEST_ASSERT_EQUAL_INT(-1, o.reopen_after_ms);
    set_ok("link", "/tmp/x");
    TEST_ASSERT_EQUAL_STRING("/tmp/x", o.link);
    set_ok("replay", "/tmp/r.csv");
    TEST_ASSERT_EQUAL_STRING("/tmp/r.csv", o.replay_csv);
    set_ok("replay", "");
    TEST_ASSERT_EQUAL_STRING("", o.replay_csv);
}

static void test_set_rejects(void)
{
    char longpath[700];
    memset(longpath, 'a', sizeof longpath - 1);
    longpath[sizeof longpath - 1] = '\0';
    set_bad("model", "XYZ", "XYZ");
    set_bad("serial", "12a", "digits");
    set_bad("serial", "123456789", "1 to 8");
    set_bad("serial", "", "1 to 8");
    set_bad("firmware", "1.131", "1 to 4");
    set_bad("firmware", "a\tb", "printable");
    set_bad("constant", "yes", "flag");
    set_bad("filter", "4", "0 to 3");
    set_bad("filter", "-1", "0 to 3");
    set_bad("rate", "0", "1 to 10000");
    set_bad("rate", "fast", "fast");
    set_bad("rate", "1200x", "1 to 10000");
    set_bad("rate", "", "1 to 10000");
    set_bad("rate", NULL, "needs a value");
    set_bad("seed", "-1", "18446744073709551615");
    set_bad("seed", "18446744073709551616", "18446744073709551615");
    set_bad("amplitude", "4.01", "0 to 4");
    set_bad("noise", "nan", "0 to 1");
    set_bad("nak", "1.5", "0 to 1");
    set_bad("overload-duration", "0", "> 0");
    set_bad("stall", "-5", "0 to 86400000");
    set_bad("stall", "1e3", "integer");
    set_bad("reopen-after", "-2", "-1 to");
    set_bad("ppm", "1001", "-1000 to 1000");
    set_bad("ppm", "nan", "-1000 to 1000");
    set_bad("ftdi-latency", "256", "0 to 255");
    set_bad("ftdi-latency", "-1", "0 to 255");
    set_bad("usb-packets", "2", "flag");
    /* times: no infinities, nothing near where nanoseconds leave int64 */
    set_bad("hangup-after", "inf", "0 to 1000000");
    set_bad("hangup-after", "9.3e9", "0 to 1000000");
    set_bad("hangup_after_s", "-inf", "0 to 1000000");
    set_bad("stall-after", "1e300", "0 to 1000000");
    set_bad("stall-after", "1e999", "0 to 1000000");
    set_bad("overload-every", "infinity", "0 to 1000000");
    set_bad("link", longpath, "longer than");
    set_bad("replay", longpath, "longer than");
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_option_set(&o, "bogus", "1", err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "bogus"));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_option_set(NULL, "rate", "1", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_option_set(&o, "rate", "0", NULL, 0));
}

static void test_check_is_the_one_validation(void)
{
    lep_sim *sim = NULL;
    lep_sim_options_init(&o);
    o.hangup_after_s = INFINITY;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(&o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "hangup-after"), err);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_start_so(&o, &sim, err, sizeof err));
    TEST_ASSERT_NULL(sim);
    lep_sim_options_init(&o);
    o.stall_after_s = 9.3e9;
    o.stall_ms = 10;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_start_so(&o, &sim, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "stall-after"), err);
    lep_sim_options_init(&o);
    o.rate_hz = NAN;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(&o, err, sizeof err));
    lep_sim_options_init(&o);
    o.overload_every_s = 0.2;
    o.overload_duration_s = 0.2;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(&o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "overload-duration"), err);
    lep_sim_options_init(&o);
    o.reopen_after_ms = 0;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(&o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "needs link"), err);
    lep_sim_options_init(&o);
    o.stall_after_s = 1.0;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(&o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "needs stall"), err);
    lep_sim_options_init(&o);
    set_ok("usb-packets", NULL);
    set_ok("ftdi-latency", "16");
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(&o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "choose one"), err);
    set_ok("usb-packets", "0");
    set_ok("ppm", "-300");
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_options_check(&o, err, sizeof err), err);
    TEST_ASSERT_EQUAL_INT(16, o.ftdi_latency_ms);
    TEST_ASSERT_EQUAL_DOUBLE(-300.0, o.ppm);
    lep_sim_options_init(&o);
    memset(o.serial, '1', sizeof o.serial); /* no NUL: an FFI caller's mistake */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(&o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "NUL"), err);
    lep_sim_options_init(&o);
    o.filter = 9;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(&o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "filter 9"), err);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_options_check(NULL, err, sizeof err));
}

/* Every value lep_sim_option_get prints is read back by lep_sim_option_set. */
static void test_get_round_trips(void)
{
    size_t i;
    char buf[600], small[2];
    lep_sim_options copy;
    set_ok("amplitude", "0.123456789");
    set_ok("seed", "987654321987");
    set_ok("link", "/tmp/lnk");
    set_ok("constant", NULL);
    lep_sim_options_init(&copy);
    for (i = 0; i < lep_sim_option_count(); i++) {
        const lep_sim_option_info *in = lep_sim_option_at(i);
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_get(&o, in->name, buf, sizeof buf));
        TEST_ASSERT_EQUAL_INT_MESSAGE(
            LEP_OK, lep_sim_option_set(&copy, in->name, buf, err, sizeof err), err);
    }
    TEST_ASSERT_EQUAL_MEMORY(&o, &copy, sizeof o);
    TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER, lep_sim_option_get(&o, "model", small, sizeof small));
    TEST_ASSERT_EQUAL_STRING("", small);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_sim_option_get(&o, "nope", buf, sizeof buf));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_table_is_complete_and_consistent);
    RUN_TEST(test_defaults);
    RUN_TEST(test_payload_and_gravity);
    RUN_TEST(test_find_accepts_python_names);
    RUN_TEST(test_set_every_type);
    RUN_TEST(test_set_rejects);
    RUN_TEST(test_check_is_the_one_validation);
    RUN_TEST(test_get_round_trips);
    return UNITY_END();
}
