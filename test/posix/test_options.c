/* Options by name (leptrino/options.h), through the public header alone, as
 * a caller from another language sees them: the one table, the handle's
 * setters and getters of each type, the text rule, and errors that name the
 * option and leave the handle unchanged. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "leptrino/leptrino.h"
#include "leptrino/options.h"
#include "leptrino/session.h"
#include "unity.h"

static lep_options *o;
static char err[256];

void setUp(void)
{
    o = lep_options_new();
    TEST_ASSERT_NOT_NULL(o);
    err[0] = '\0';
}

void tearDown(void)
{
    lep_options_free(o);
}

static void text_of(const char *name, char *buf, size_t cap)
{
    size_t len = 99;
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_options_get(o, name, buf, cap, &len), name);
    TEST_ASSERT_EQUAL_size_t(strlen(buf), len);
}

/* Every row: a unique name, a known type and scope, a default that the
 * handle holds and reads back as text, help without a trailing period. */
static void test_every_row_is_described_and_holds_its_default(void)
{
    size_t i, j, n = lep_option_count();
    char buf[600];
    TEST_ASSERT_TRUE(n >= 48); /* 22 of the session, 28 of the virtual sensor */
    for (i = 0; i < n; i++) {
        const char *name = lep_option_name(i);
        const char *help = lep_option_help(i);
        const char *def = lep_option_default(i);
        int type = lep_option_type(i), scope = lep_option_scope(i);
        TEST_ASSERT_NOT_NULL(name);
        TEST_ASSERT_EQUAL_INT_MESSAGE((int)i, lep_option_index(name), name);
        for (j = 0; j < i; j++)
            TEST_ASSERT_NOT_EQUAL(0, strcmp(name, lep_option_name(j)));
        TEST_ASSERT_TRUE_MESSAGE(type >= LEP_OPT_FLAG && type <= LEP_OPT_NUMBERS, name);
        TEST_ASSERT_TRUE_MESSAGE(scope >= LEP_SCOPE_SESSION && scope <= LEP_SCOPE_SIM, name);
        TEST_ASSERT_EQUAL_INT_MESSAGE(strncmp(name, "sim-", 4) == 0, scope == LEP_SCOPE_SIM, name);
        TEST_ASSERT_TRUE_MESSAGE(help[0] != '\0', name);
        /* no closing period (an ellipsis that leads to the next row is fine) */
        TEST_ASSERT_TRUE_MESSAGE(
            help[strlen(help) - 1] != '.' ||
                (strlen(help) > 3 && strcmp(help + strlen(help) - 3, "...") == 0),
            name);
        text_of(name, buf, sizeof buf);
        if (def[0] != '\0')
            TEST_ASSERT_EQUAL_STRING_MESSAGE(def, buf, name);
        else if (type == LEP_OPT_FLAG)
            TEST_ASSERT_EQUAL_STRING_MESSAGE("0", buf, name);
        else
            TEST_ASSERT_EQUAL_STRING_MESSAGE("", buf, name);
        if (type == LEP_OPT_NUMBERS)
            TEST_ASSERT_TRUE_MESSAGE(lep_option_numbers(i) > 1, name);
    }
    TEST_ASSERT_NULL(lep_option_name(n));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_option_type(n));
    TEST_ASSERT_EQUAL_STRING("", lep_option_help(n));
}

static void test_names_take_underscores_and_the_sim_prefix(void)
{
    int64_t v = 0;
    TEST_ASSERT_EQUAL_INT(lep_option_index("data-timeout"), lep_option_index("data_timeout"));
    TEST_ASSERT_EQUAL_INT(lep_option_index("sim-overload-every"),
                          lep_option_index("sim_overload_every"));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_option_index("rate")); /* the sim's: sim-rate */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_option_index("rate_hz"));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_option_index(NULL));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_int(o, "data_timeout", 750, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get_int(o, "data-timeout", &v));
    TEST_ASSERT_EQUAL_INT64(750, v);
}

static void test_each_type_sets_and_reads_back(void)
{
    double d = 0, many[9];
    int64_t i = 0;
    size_t n = 0;
    char buf[64];
    const double r[9] = { 0, -1, 0, 1, 0, 0, 0, 0, 1 };
    /* FLAG */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_int(o, "reconnect", 1, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get_int(o, "reconnect", &i));
    TEST_ASSERT_EQUAL_INT64(1, i);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "sim-constant", NULL, err, sizeof err));
    text_of("sim-constant", buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("1", buf);
    /* INT, also as a double holding an integer, and as text */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_double(o, "decimate", 4.0, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get_double(o, "decimate", &d));
    TEST_ASSERT_EQUAL_DOUBLE(4.0, d);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "tare-samples", "250", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get_int(o, "tare-samples", &i));
    TEST_ASSERT_EQUAL_INT64(250, i);
    /* DOUBLE: exact round trip, text and number */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_double(o, "lowpass", 0.1, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get_double(o, "lowpass", &d));
    TEST_ASSERT_TRUE(d == 0.1);
    text_of("lowpass", buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("0.1", buf);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get_doubles(o, "lowpass", many, 9, &n));
    TEST_ASSERT_EQUAL_size_t(1, n);
    /* STRING and CHOICE */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "port", "/dev/ttyACM3", err, sizeof err));
    text_of("port", buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("/dev/ttyACM3", buf);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "sim-model", "CFS018CA201U", err, sizeof err));
    text_of("sim-model", buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("CFS018CA201U", buf);
    TEST_ASSERT_EQUAL_STRING("CFS018CA201U",
                             lep_option_choice((size_t)lep_option_index("sim-model"), 0));
    TEST_ASSERT_NULL(lep_option_choice((size_t)lep_option_index("sim-model"), 99));
    TEST_ASSERT_NULL(lep_option_choice((size_t)lep_option_index("port"), 0));
    /* NUMBERS */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set_doubles(o, "rotation", r, 9, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get_doubles(o, "rotation", many, 9, &n));
    TEST_ASSERT_EQUAL_size_t(9, n);
    TEST_ASSERT_EQUAL_MEMORY(r, many, sizeof(double) * 9);
    text_of("rotation", buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("0,-1,0,1,0,0,0,0,1", buf);
    /* a count that asks: cap 0 */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get_doubles(o, "payload", NULL, 0, &n));
    TEST_ASSERT_EQUAL_size_t(4, n);
}

static void test_limit_takes_the_axis_syntax(void)
{
    double l[6];
    size_t n;
    const double want[6] = { 0, 0, 50, 0, 0, 2 };
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "limit", "fz=50,mz=2", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get_doubles(o, "limit", l, 6, &n));
    TEST_ASSERT_EQUAL_MEMORY(want, l, sizeof(double) * 6);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_set(o, "limit", "fz=50,fz=60", err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "limit 'fz=50,fz=60'"));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get_doubles(o, "limit", l, 6, &n));
    TEST_ASSERT_EQUAL_MEMORY(want, l, sizeof(double) * 6); /* unchanged */
}

/* A refused value: LEP_E_ARG, one line naming the option, nothing changed. */
static void refused(int rc, const char *name, const char *needle)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_E_ARG, rc, name);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, needle), err);
    TEST_ASSERT_NULL_MESSAGE(strchr(err, '\n'), err);
}

static void test_errors_name_the_option_and_change_nothing(void)
{
    lep_options *copy = lep_options_copy(o);
    const double three[3] = { 1, 2, 3 };
    const double bad[4] = { 1, NAN, 0, 0 };
    char a[600], b[600];
    size_t i;
    refused(lep_options_set(o, "lowpas", "3", err, sizeof err), "lowpas",
            "unknown option 'lowpas'");
    refused(lep_options_set_double(o, "sim-amplitude", 5.0, err, sizeof err), "sim-amplitude",
            "sim-amplitude '5': expected a number from 0 to 4");
    refused(lep_options_set_int(o, "timeout", 0, err, sizeof err), "timeout",
            "timeout '0': expected an integer from 1 to");
    refused(lep_options_set_double(o, "decimate", 2.5, err, sizeof err), "decimate",
            "decimate 2.5: expected an integer");
    refused(lep_options_set_int(o, "sim", 2, err, sizeof err), "sim", "sim 2: a flag is 0 or 1");
    refused(lep_options_set_int(o, "port", 3, err, sizeof err), "port", "port: not an integer");
    refused(lep_options_set_doubles(o, "payload", three, 3, err, sizeof err), "payload",
            "payload: expected 4 numbers (M,CX,CY,CZ), got 3");
    refused(lep_options_set_doubles(o, "payload", bad, 4, err, sizeof err), "payload",
            "payload: value 2 is nan");
    refused(lep_options_set(o, "sim-model", "PFS999", err, sizeof err), "sim-model",
            "sim-model 'PFS999': unknown");
    refused(lep_options_set(o, "gravity", "0,0", err, sizeof err), "gravity", "gravity '0,0'");
    refused(lep_options_set(o, NULL, "1", err, sizeof err), "(null)", "no option name");
    for (i = 0; i < lep_option_count(); i++) {
        const char *name = lep_option_name(i);
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get(o, name, a, sizeof a, NULL));
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_get(copy, name, b, sizeof b, NULL));
        TEST_ASSERT_EQUAL_STRING_MESSAGE(b, a, name);
    }
    lep_options_free(copy);
}

static void test_text_results_say_the_room_they_need(void)
{
    char small[4];
    size_t len = 0;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "port", "/dev/ttyUSB0", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER, lep_options_get(o, "port", NULL, 0, &len));
    TEST_ASSERT_EQUAL_size_t(12, len);
    TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER, lep_options_get(o, "port", small, sizeof small, &len));
    TEST_ASSERT_EQUAL_STRING("", small);
    TEST_ASSERT_EQUAL_size_t(12, len);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_get(o, "nope", small, sizeof small, &len));
    TEST_ASSERT_EQUAL_size_t(0, len);
}

static void test_getters_refuse_the_wrong_type(void)
{
    int64_t i;
    double d;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_get_int(o, "lowpass", &i));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_get_double(o, "port", &d));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_get_double(o, "rotation", &d));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_get_int(NULL, "decimate", &i));
    /* sim-seed holds 64 bits: beyond int64 it reads as text only */
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_options_set(o, "sim-seed", "18446744073709551615", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_get_int(o, "sim-seed", &i));
}

static void test_check_sees_how_options_combine(void)
{
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_check(o, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "sim-overload-every", "1", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_options_set(o, "sim-overload-duration", "2", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_check(o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "overload-duration"), err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "sim-overload-every", "0", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "reconnect-min", "500", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_options_set(o, "reconnect-max", "100", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_check(o, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "reconnect"), err);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_options_check(NULL, err, sizeof err));
}

static void test_open_refuses_a_handle_without_a_port(void)
{
    lep_session *s = (lep_session *)&s;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_open(o, &s, err, sizeof err));
    TEST_ASSERT_NULL(s);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "no port given"), err);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_session_open(NULL, &s, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "lep_options_new"), err);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_row_is_described_and_holds_its_default);
    RUN_TEST(test_names_take_underscores_and_the_sim_prefix);
    RUN_TEST(test_each_type_sets_and_reads_back);
    RUN_TEST(test_limit_takes_the_axis_syntax);
    RUN_TEST(test_errors_name_the_option_and_change_nothing);
    RUN_TEST(test_text_results_say_the_room_they_need);
    RUN_TEST(test_getters_refuse_the_wrong_type);
    RUN_TEST(test_check_sees_how_options_combine);
    RUN_TEST(test_open_refuses_a_handle_without_a_port);
    return UNITY_END();
}
