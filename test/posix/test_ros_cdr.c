/* lep_ros_wrench_cdr: WrenchStamped CDR bytes from batch arrays, checked
 * byte for byte against a layout written out by hand here; stamps held
 * monotonic; raw through lep_sample_to_si; every refusal writes nothing. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "leptrino/error.h"
#include "leptrino/ros_cdr.h"
#include "struct_api.h"
#include "unity.h"

static double t_utc[3] = { 1700000000.25, 1700000000.2499999, 1700000001.0 };
static int16_t raw[18] = {
    1, -2, 3, -4, 5, -6, 10000, 0, -10000, 32000, -32000, 7, 0, 0, 0, 0, 0, 0
};
static double si[18] = { 0.5, -1.5, 2.0,    -0.25, 0.125, 1e-9, 500, 0, -500,
                         32,  -32,  0.0056, 0,     0,     0,    0,   0, -0.0 };
static lep_session_batch batch;
static lep_rated rated = { { 200.f, 200.f, 400.f, 4.f, 4.f, 4.f } };

void setUp(void)
{
    memset(&batch, 0, sizeof batch);
    batch.cap = batch.n = 3;
    batch.t_utc = t_utc;
    batch.raw = raw;
    batch.si = si;
}

void tearDown(void)
{
}

static uint32_t u32_at(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static double f64_at(const uint8_t *p)
{
    uint64_t v = (uint64_t)u32_at(p) | (uint64_t)u32_at(p + 4) << 32;
    double d;
    memcpy(&d, &v, sizeof d);
    return d;
}

static void test_sizes(void)
{
    /* 4 header + 8 stamp + 4 length + L+1 bytes, padded to 8 from offset 4, + 48 */
    TEST_ASSERT_EQUAL_UINT(4 + 16 + 48, lep_ros_wrench_size(0));  /* 13 -> 16 */
    TEST_ASSERT_EQUAL_UINT(4 + 16 + 48, lep_ros_wrench_size(3));  /* 16 */
    TEST_ASSERT_EQUAL_UINT(4 + 24 + 48, lep_ros_wrench_size(4));  /* 17 -> 24 */
    TEST_ASSERT_EQUAL_UINT(4 + 24 + 48, lep_ros_wrench_size(11)); /* 24 */
    TEST_ASSERT_EQUAL_UINT(0, lep_ros_wrench_size(LEP_ROS_FRAME_ID_MAX + 1));
}

static void test_bytes(void)
{
    static const uint8_t want_head[24] = { 0x00, 0x01, 0x00, 0x00, 0x00, 0xf1, 0x53, 0x65,
                                           0x80, 0xb2, 0xe6, 0x0e, 0x05, 0x00, 0x00, 0x00,
                                           'l',  'e',  'f',  't',  0x00, 0x00, 0x00, 0x00 };
    uint8_t w[3 * 76], r[3 * 76];
    int64_t st[3], last = 0;
    size_t size = lep_ros_wrench_size(4);
    TEST_ASSERT_EQUAL_UINT(76, size);
    memset(w, 0xee, sizeof w);
    memset(r, 0xee, sizeof r);
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_ros_wrench_cdr_batch(&batch, 0, 3, &rated, "left", &last, w, r, sizeof w, st));
    /* 1700000000 = 0x6553f100, 250000000 = 0x0ee6b280 */
    TEST_ASSERT_EQUAL_HEX8_ARRAY(want_head, w, 24);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(want_head, r, 24);
    for (size_t i = 0; i < 3; i++) {
        lep_sample s;
        double want_raw[LEP_AXES];
        memset(&s, 0, sizeof s);
        memcpy(s.raw, raw + 6 * i, sizeof s.raw);
        lep_sample_to_si(&s, &rated, want_raw);
        for (size_t k = 0; k < 6; k++) {
            double got = f64_at(w + i * size + 28 + 8 * k);
            TEST_ASSERT_EQUAL_MEMORY(&si[6 * i + k], &got, sizeof got); /* bit for bit, -0.0 too */
            got = f64_at(r + i * size + 28 + 8 * k);
            TEST_ASSERT_EQUAL_MEMORY(&want_raw[k], &got, sizeof got);
        }
    }
    /* 10000 counts are the rated value; -10000 its negative */
    TEST_ASSERT_TRUE(f64_at(r + size + 28) == 200.0);
    TEST_ASSERT_TRUE(f64_at(r + size + 28 + 16) == -400.0);
    /* the second t_utc is 1e-7 s earlier: its stamp holds the first one */
    TEST_ASSERT_EQUAL_INT64(1700000000250000000LL, st[0]);
    TEST_ASSERT_EQUAL_INT64(1700000000250000000LL, st[1]);
    TEST_ASSERT_EQUAL_INT64(1700000001000000000LL, st[2]);
    TEST_ASSERT_EQUAL_INT64(st[2], last);
    TEST_ASSERT_EQUAL_UINT32(1700000001u, u32_at(w + 2 * size + 4));
    TEST_ASSERT_EQUAL_UINT32(0u, u32_at(w + 2 * size + 8));
    TEST_ASSERT_EQUAL_UINT32(250000000u, u32_at(r + size + 8));
}

static void test_last_carries_over(void)
{
    uint8_t w[76];
    int64_t st, last = 1700000000300000000LL; /* a later stamp from the previous batch */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_ros_wrench_cdr_batch(&batch, 1, 1, NULL, "left", &last, w,
                                                           NULL, sizeof w, &st));
    TEST_ASSERT_EQUAL_INT64(1700000000300000000LL, st);
    TEST_ASSERT_EQUAL_UINT32(300000000u, u32_at(w + 8));
}

static void test_empty_frame_id(void)
{
    uint8_t w[68];
    int64_t last = 0;
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_ros_wrench_cdr_batch(&batch, 2, 1, NULL, "", &last, w, NULL, sizeof w, NULL));
    TEST_ASSERT_EQUAL_UINT32(1u, u32_at(w + 12)); /* the NUL alone */
    TEST_ASSERT_EQUAL_HEX8(0, w[16]);
    TEST_ASSERT_EQUAL_HEX8(0, w[19]);
    TEST_ASSERT_EQUAL_UINT32(1700000001u, u32_at(w + 4));
    TEST_ASSERT_TRUE(f64_at(w + 20) == si[12]); /* the doubles from offset 20 */
    TEST_ASSERT_TRUE(signbit(f64_at(w + 20 + 40)));
}

static void test_refusals_write_nothing(void)
{
    uint8_t w[3 * 76], r[3 * 76];
    int64_t last = 5, st[3] = { 9, 9, 9 };
    double bad_t[3] = { 1.0, NAN, 2.0 };
    double far_t[3] = { 1.0, 4294967296.0, 2.0 };
    char longid[LEP_ROS_FRAME_ID_MAX + 2];
    memset(longid, 'x', sizeof longid - 1);
    longid[sizeof longid - 1] = 0;
    memset(w, 0xee, sizeof w);
    memset(r, 0xee, sizeof r);
    TEST_ASSERT_EQUAL_INT(
        LEP_E_ARG, lep_ros_wrench_cdr_batch(NULL, 0, 1, &rated, "a", &last, w, r, sizeof w, st));
    TEST_ASSERT_EQUAL_INT(
        LEP_E_ARG, lep_ros_wrench_cdr_batch(&batch, 2, 2, &rated, "a", &last, w, r, sizeof w, st));
    TEST_ASSERT_EQUAL_INT(
        LEP_E_ARG, lep_ros_wrench_cdr_batch(&batch, 4, 0, &rated, "a", &last, w, r, sizeof w, st));
    TEST_ASSERT_EQUAL_INT(
        LEP_E_ARG, lep_ros_wrench_cdr_batch(&batch, 0, 1, NULL, "a", &last, w, r, sizeof w, st));
    TEST_ASSERT_EQUAL_INT(
        LEP_E_ARG, lep_ros_wrench_cdr_batch(&batch, 0, 1, &rated, NULL, &last, w, r, sizeof w, st));
    TEST_ASSERT_EQUAL_INT(
        LEP_E_ARG, lep_ros_wrench_cdr_batch(&batch, 0, 1, &rated, "a", NULL, w, r, sizeof w, st));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_ros_wrench_cdr_batch(&batch, 0, 1, &rated, longid, &last,
                                                              w, r, sizeof w, st));
    TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER, lep_ros_wrench_cdr_batch(&batch, 0, 3, &rated, "left",
                                                                 &last, w, r, 3 * 76 - 1, st));
    batch.si = NULL;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_ros_wrench_cdr_batch(&batch, 0, 1, &rated, "a", &last, w,
                                                              NULL, sizeof w, st));
    batch.si = si;
    batch.raw = NULL;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_ros_wrench_cdr_batch(&batch, 0, 1, &rated, "a", &last,
                                                              NULL, r, sizeof w, st));
    batch.raw = raw;
    batch.t_utc = bad_t;
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_ros_wrench_cdr_batch(&batch, 0, 3, &rated, "a", &last, w,
                                                                r, sizeof w, st));
    batch.t_utc = far_t; /* 2^32 s: past int32 seconds */
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_ros_wrench_cdr_batch(&batch, 0, 3, &rated, "a", &last, w,
                                                                r, sizeof w, st));
    for (size_t i = 0; i < sizeof w; i++) {
        TEST_ASSERT_EQUAL_HEX8(0xee, w[i]);
        TEST_ASSERT_EQUAL_HEX8(0xee, r[i]);
    }
    TEST_ASSERT_EQUAL_INT64(5, last);
    TEST_ASSERT_EQUAL_INT64(9, st[0]);
    batch.t_utc = t_utc;
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_ros_wrench_cdr_batch(&batch, 3, 0, &rated, "a", &last, w, r, 0, st));
    TEST_ASSERT_EQUAL_INT64(5, last);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sizes);
    RUN_TEST(test_bytes);
    RUN_TEST(test_last_carries_over);
    RUN_TEST(test_empty_frame_id);
    RUN_TEST(test_refusals_write_nothing);
    return UNITY_END();
}
