/* The recording writer, byte for byte: CSV and JSON lines, columns, time
 * bases, events in place, several sensors, refusing to overwrite. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "leptrino/error.h"
#include "leptrino/output.h"
#include "host_os.h"
#include "struct_api.h"
#include "unity.h"

#define META "{\"model\":\"M\",\"serial\":\"1\"}"

static char dir[64];
static char path[128];
static double t_mono[3] = { 100.25, 100.2508333, 100.5 };
static double t_utc[3] = { 1700000000.25, 1700000000.2508333, 1700000000.5 };
static int16_t raw[18] = {
    1, -2, 3, -4, 5, -6, 10000, 0, -10000, 32000, -32000, 7, 0, 0, 0, 0, 0, 0
};
static double zeroed[18] = { 0.5,   -2.25,  3, -4, 5, -6.125, 9999.5, 0, -10000,
                             32000, -32000, 7, 0,  0, 0,      0,      0, 1.0 / 3.0 };
static double si[18] = { 0.025, -0.1, 0.15,   -0.004, 0.005, -0.0048, 500, 0, -500,
                         32,    -32,  0.0056, 1e-7,   -1e-7, 0,       0,   0, 2.0 / 3.0 };
static uint8_t status[3] = { 0, 4, 0 };
static uint8_t flags[3] = { 0, 2, 1 };
static uint16_t seq[3] = { 7, 8, 10 };
static lep_session_batch batch;

void setUp(void)
{
    snprintf(dir, sizeof dir, "/tmp/lep-test-output-XXXXXX");
    TEST_ASSERT_NOT_NULL(lep_test_mkdtemp(dir));
    snprintf(path, sizeof path, "%s/rec.csv", dir);
    memset(&batch, 0, sizeof batch);
    batch.cap = batch.n = 3;
    batch.t_mono = t_mono;
    batch.t_utc = t_utc;
    batch.raw = raw;
    batch.zeroed = zeroed;
    batch.si = si;
    batch.status = status;
    batch.flags = flags;
    batch.seq = seq;
}

void tearDown(void)
{
    (void)unlink(path);
    (void)rmdir(dir);
}

static char *slurp(const char *p)
{
    static char buf[16384];
    FILE *f = fopen(p, "rb");
    size_t n;
    TEST_ASSERT_NOT_NULL(f);
    n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return buf;
}

static lep_output *open_with(int format, int time, unsigned columns, double t0)
{
    lep_output_options o;
    lep_output *w = NULL;
    char err[256] = "";
    lep_output_options_init(&o);
    o.format = format;
    o.time = time;
    o.columns = columns;
    o.t0_mono = t0;
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_output_open_opts(path, &o, &w, err, sizeof err), err);
    return w;
}

static void test_csv_default_columns(void)
{
    lep_output *w = open_with(LEP_OUTPUT_CSV, LEP_TIME_REL, LEP_COL_DEFAULT, 0.0);
    TEST_ASSERT_EQUAL_INT(0, lep_output_add_sensor(w, NULL, META, 100.0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_write_batch(w, 0, &batch, 0, NULL, 0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_close(w));
    TEST_ASSERT_EQUAL_STRING(
        "# leptrino-metadata: " META "\n"
        "t_s,fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm,status\n"
        "0.250000,0.025000,-0.100000,0.150000,-0.004000,0.005000,-0.004800,0\n"
        "0.250833,500.000000,0.000000,-500.000000,32.000000,-32.000000,0.005600,4\n"
        "0.500000,0.000000,-0.000000,0.000000,0.000000,0.000000,0.666667,0\n",
        slurp(path));
}

static void test_csv_all_columns_mono_time(void)
{
    lep_output *w =
        open_with(LEP_OUTPUT_CSV, LEP_TIME_MONO,
                  LEP_COL_RAW | LEP_COL_ZEROED | LEP_COL_STATUS | LEP_COL_FLAGS | LEP_COL_SEQ, 0.0);
    batch.n = 2;
    TEST_ASSERT_EQUAL_INT(0, lep_output_add_sensor(w, NULL, META, 100.0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_write_batch(w, 0, &batch, 0, NULL, 0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_close(w));
    TEST_ASSERT_EQUAL_STRING(
        "# leptrino-metadata: " META "\n"
        "t_mono_s,fx_counts,fy_counts,fz_counts,mx_counts,my_counts,mz_counts,"
        "fx_zeroed_counts,fy_zeroed_counts,fz_zeroed_counts,mx_zeroed_counts,my_zeroed_counts,"
        "mz_zeroed_counts,status,flags,seq\n"
        "100.250000,1,-2,3,-4,5,-6,0.500,-2.250,3.000,-4.000,5.000,-6.125,0,0,7\n"
        "100.250833,10000,0,-10000,32000,-32000,7,9999.500,0.000,-10000.000,32000.000,"
        "-32000.000,7.000,4,2,8\n",
        slurp(path));
}

static void test_jsonl_utc_with_events(void)
{
    lep_output *w = open_with(LEP_OUTPUT_JSONL, LEP_TIME_UTC, LEP_COL_RAW | LEP_COL_STATUS, 0.0);
    lep_session_event ev[3];
    memset(ev, 0, sizeof ev);
    ev[0].type = LEP_EV_GAP;
    ev[0].sample = 2;
    ev[0].t_mono = 100.5;
    ev[0].t_utc = 1700000000.5;
    ev[0].gap_from = 100.2508333;
    ev[0].gap_to = 100.5;
    ev[0].lost = 1;
    ev[1].type = LEP_EV_TARE;
    ev[1].sample = 2;
    ev[1].t_mono = 100.5;
    ev[1].t_utc = 1700000000.5;
    ev[1].tare[0] = 0.5;
    ev[1].tare[5] = -1.0 / 3.0;
    ev[2].type = LEP_EV_DISCONNECTED;
    ev[2].sample = 3;
    ev[2].t_mono = 101.0;
    ev[2].t_utc = 1700000001.0;
    ev[2].error = LEP_E_TIMEOUT;
    TEST_ASSERT_EQUAL_INT(0, lep_output_add_sensor(w, NULL, META, 100.0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_write_batch(w, 0, &batch, 0, ev, 3));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_close(w));
    TEST_ASSERT_EQUAL_STRING(
        "{\"metadata\":" META "}\n"
        "{\"t_utc_s\":1700000000.250000,\"fx_counts\":1,\"fy_counts\":-2,\"fz_counts\":3,"
        "\"mx_counts\":-4,\"my_counts\":5,\"mz_counts\":-6,\"status\":0}\n"
        "{\"t_utc_s\":1700000000.250833,\"fx_counts\":10000,\"fy_counts\":0,\"fz_counts\":-10000,"
        "\"mx_counts\":32000,\"my_counts\":-32000,\"mz_counts\":7,\"status\":4}\n"
        "{\"event\":\"gap\",\"from\":1700000000.250833,\"to\":1700000000.500000,\"lost\":1,"
        "\"reason\":\"gap\"}\n"
        "{\"event\":\"tare\",\"at\":1700000000.500000,\"offset_counts\":[0.500000,0.000000,"
        "0.000000,0.000000,0.000000,-0.333333]}\n"
        "{\"t_utc_s\":1700000000.500000,\"fx_counts\":0,\"fy_counts\":0,\"fz_counts\":0,"
        "\"mx_counts\":0,\"my_counts\":0,\"mz_counts\":0,\"status\":0}\n"
        "{\"event\":\"disconnected\",\"at\":1700000001.000000,\"reason\":\"no-data\"}\n",
        slurp(path));
}

static void test_csv_events_and_two_sensors_on_one_time_base(void)
{
    lep_output *w = open_with(LEP_OUTPUT_CSV, LEP_TIME_REL, LEP_COL_SENSOR | LEP_COL_STATUS, 0.0);
    lep_session_batch b2 = batch;
    lep_session_event ev[2];
    memset(ev, 0, sizeof ev);
    ev[0].type = LEP_EV_OVERLOAD_BEGIN;
    ev[0].sample = 1;
    ev[0].t_mono = 100.2508333;
    ev[0].t_utc = 1700000000.2508333;
    ev[0].axes = 0x18;
    ev[0].status = 4;
    ev[1].type = LEP_EV_RECONNECTED;
    ev[1].sample = 1;
    ev[1].t_mono = 100.6;
    ev[1].t_utc = 1700000000.6;
    ev[1].gap_from = 100.3;
    ev[1].gap_to = 100.6;
    ev[1].lost = 359;
    ev[1].error = LEP_E_DISCONNECTED;
    TEST_ASSERT_EQUAL_INT(0, lep_output_add_sensor(w, "left", META, 100.0));
    TEST_ASSERT_EQUAL_INT(1, lep_output_add_sensor(w, "right", "{}", 100.1));
    b2.n = 2;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_write_batch(w, 0, &b2, 0, &ev[0], 1));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_write_batch(w, 1, &b2, 1, &ev[1], 1));
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_output_add_sensor(w, "late", "{}", 0.0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_close(w));
    TEST_ASSERT_EQUAL_STRING(
        "# leptrino-metadata: {\"sensor\":\"left\",\"model\":\"M\",\"serial\":\"1\"}\n"
        "# leptrino-metadata: {\"sensor\":\"right\"}\n"
        "t_s,sensor,status\n"
        "0.250000,left,0\n"
        "# overload begin sensor=left at=0.250833 axes=24 status=4\n"
        "0.250833,left,4\n"
        "0.250833,right,4\n"
        "# gap sensor=right from=0.300000 to=0.600000 lost=359 reason=disconnected\n",
        slurp(path));
}

static void test_refuses_to_overwrite_and_keeps_the_file(void)
{
    lep_output_options o;
    lep_output *w = NULL;
    char err[256] = "";
    FILE *f = fopen(path, "w");
    TEST_ASSERT_NOT_NULL(f);
    fputs("someone's data\n", f);
    fclose(f);
    lep_output_options_init(&o);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_output_open_opts(path, &o, &w, err, sizeof err));
    TEST_ASSERT_NULL(w);
    TEST_ASSERT_NOT_NULL(strstr(err, "already exists"));
    TEST_ASSERT_NOT_NULL(strstr(err, path));
    TEST_ASSERT_EQUAL_STRING("someone's data\n", slurp(path));
    o.overwrite = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_open_opts(path, &o, &w, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(0, lep_output_add_sensor(w, NULL, "{}", 0.0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_close(w));
    TEST_ASSERT_EQUAL_STRING(
        "# leptrino-metadata: {}\nt_s,fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm,status\n", slurp(path));
}

static void test_bad_arguments(void)
{
    lep_output_options o;
    lep_output *w = NULL;
    char err[256] = "", missing[160];
    lep_output_options_init(&o);
    snprintf(missing, sizeof missing, "%s/no/such/file.csv", dir);
    TEST_ASSERT_EQUAL_INT(LEP_E_NOT_FOUND, lep_output_open_opts(missing, &o, &w, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, missing));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_output_open_opts(dir, &o, &w, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_output_open_fd_opts(-1, &o, &w, err, sizeof err));
    o.format = 7;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_output_open_opts(path, &o, &w, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(-1, access(path, F_OK)); /* nothing created for bad options */
    w = open_with(LEP_OUTPUT_CSV, LEP_TIME_REL, LEP_COL_DEFAULT | LEP_COL_SEQ, 0.0);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_output_add_sensor(w, "a,b", "{}", 0.0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_output_add_sensor(w, "x", "not json", 0.0));
    TEST_ASSERT_EQUAL_INT(0, lep_output_add_sensor(w, "x", "{}", 0.0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_output_write_batch(w, 1, &batch, 0, NULL, 0));
    batch.seq = NULL; /* a chosen column without its array */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_output_write_batch(w, 0, &batch, 0, NULL, 0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_close(w));
}

static void test_write_error_is_reported(void)
{
    int fds[2];
    lep_output *w = NULL;
    char err[64];
    int i, rc = LEP_OK;
    TEST_ASSERT_EQUAL_INT(0, pipe(fds));
    close(fds[0]); /* nobody reads: EPIPE (SIGPIPE ignored below) */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_open_fd_opts(fds[1], NULL, &w, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(0, lep_output_add_sensor(w, NULL, "{}", 0.0));
    for (i = 0; i < 3000 && rc == LEP_OK; i++)
        rc = lep_output_write_batch(w, 0, &batch, 0, NULL, 0);
    if (rc == LEP_OK)
        rc = lep_output_flush(w);
    TEST_ASSERT_EQUAL_INT(LEP_E_IO, rc);
    TEST_ASSERT_EQUAL_INT(EPIPE, lep_output_errno(w));
    TEST_ASSERT_EQUAL_INT(LEP_E_IO, lep_output_close(w));
    close(fds[1]);
}

int main(void)
{
    signal(SIGPIPE, SIG_IGN);
    UNITY_BEGIN();
    RUN_TEST(test_csv_default_columns);
    RUN_TEST(test_csv_all_columns_mono_time);
    RUN_TEST(test_jsonl_utc_with_events);
    RUN_TEST(test_csv_events_and_two_sensors_on_one_time_base);
    RUN_TEST(test_refuses_to_overwrite_and_keeps_the_file);
    RUN_TEST(test_bad_arguments);
    RUN_TEST(test_write_error_is_reported);
    return UNITY_END();
}
