/* Sensor side: answers, result codes, state errors, filter power cycle. */
#include <stdbool.h>
#include <string.h>

#include "unity.h"
#include "leptrino/leptrino.h"

static lep_device dev;
static uint8_t out[LEP_MAX_FRAME];
static size_t out_len;
static lep_device_event ev;

void setUp(void)
{
    lep_product_info info;
    lep_rated rated = { { 100.0f, 100.0f, 200.0f, 1.0f, 1.0f, 1.0f } };
    memset(&info, 0, sizeof(info));
    strcpy(info.model, "CFS018CA201U");
    strcpy(info.serial, "00000042");
    strcpy(info.firmware, "1.13");
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_device_init(&dev, &info, &rated, 1));
}

void tearDown(void)
{
}

/* Feed a whole frame; it must be consumed in full and produce one event. */
static void feed(const uint8_t *frame, size_t len)
{
    size_t n = lep_device_feed(&dev, frame, len, &ev, out, sizeof(out), &out_len);
    TEST_ASSERT_EQUAL_size_t(len, n);
}

static void send_cmd(uint8_t code, uint8_t filter)
{
    lep_command cmd = { code, filter };
    uint8_t frame[LEP_MAX_FRAME];
    size_t n;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_command_frame(&cmd, frame, sizeof(frame), &n));
    feed(frame, n);
}

/* Decode the answer in out as a frame + response. */
static int answer(lep_response *r)
{
    lep_frame_decoder d;
    lep_frame_event fev;
    lep_frame_decoder_init(&d);
    TEST_ASSERT_EQUAL_size_t(out_len, lep_frame_decoder_feed(&d, out, out_len, &fev));
    TEST_ASSERT_EQUAL_INT(LEP_FRAME_MESSAGE, fev.type);
    return lep_response_decode(fev.msg, fev.len, r);
}

static void expect_result(uint8_t code, uint8_t result)
{
    lep_response r;
    TEST_ASSERT_EQUAL_INT(LEP_DEVICE_COMMAND, ev.type);
    TEST_ASSERT_EQUAL_HEX8(code, ev.code);
    TEST_ASSERT_EQUAL_HEX8(result, ev.result);
    TEST_ASSERT_EQUAL_INT(result == 0 ? LEP_OK : LEP_E_SENSOR, answer(&r));
    TEST_ASSERT_EQUAL_HEX8(code, r.code);
    TEST_ASSERT_EQUAL_HEX8(result, r.result);
}

static void test_init_validates(void)
{
    lep_product_info info;
    lep_rated bad = { { 100.0f, -1.0f, 200.0f, 1.0f, 1.0f, 1.0f } };
    lep_rated good = { { 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f } };
    memset(&info, 0, sizeof(info));
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_device_init(&dev, &info, &bad, 0));
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_device_init(&dev, &info, &good, 4));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_device_init(NULL, &info, &good, 0));
}

static void test_init_rejects_identity_that_cannot_be_answered(void)
{
    /* Fields that do not fit the product-info answer would make every 0x2A go
     * unanswered: refuse them up front. */
    lep_product_info info;
    lep_rated good = { { 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f } };
    lep_response r;
    memset(&info, 0, sizeof(info));
    memset(info.model, 'M', sizeof(info.model)); /* 17 characters, no NUL */
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_device_init(&dev, &info, &good, 0));
    memset(&info, 0, sizeof(info));
    memset(info.output_rate, '9', sizeof(info.output_rate));
    info.has_output_rate = true;
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_device_init(&dev, &info, &good, 0));
    /* The same string without the rate field is fine, and answered in the 38-byte form when set. */
    info.has_output_rate = false;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_device_init(&dev, &info, &good, 0));
    memset(&info, 0, sizeof(info));
    strcpy(info.model, "PFS080YS102U6");
    strcpy(info.output_rate, "1200");
    info.has_output_rate = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_device_init(&dev, &info, &good, 0));
    send_cmd(LEP_CMD_PRODUCT_INFO, 0);
    TEST_ASSERT_EQUAL_INT(LEP_OK, answer(&r));
    TEST_ASSERT_TRUE(r.u.info.has_output_rate);
    TEST_ASSERT_EQUAL_UINT32(1200, r.u.info.output_rate_hz);
}

static void test_answers_queries(void)
{
    lep_response r;
    send_cmd(LEP_CMD_PRODUCT_INFO, 0);
    expect_result(LEP_CMD_PRODUCT_INFO, 0);
    TEST_ASSERT_EQUAL_INT(LEP_OK, answer(&r));
    TEST_ASSERT_EQUAL_STRING("CFS018CA201U", r.u.info.model);
    TEST_ASSERT_EQUAL_STRING("00000042", r.u.info.serial);
    send_cmd(LEP_CMD_RATED, 0);
    TEST_ASSERT_EQUAL_INT(LEP_OK, answer(&r));
    TEST_ASSERT_EQUAL_FLOAT(200.0f, r.u.rated.axis[LEP_FZ]);
    send_cmd(LEP_CMD_FILTER_GET, 0);
    TEST_ASSERT_EQUAL_INT(LEP_OK, answer(&r));
    TEST_ASSERT_EQUAL_UINT8(1, r.u.filter);
}

static void test_handshake_answers_current_sample(void)
{
    lep_sample s;
    lep_response r;
    memset(&s, 0, sizeof(s));
    s.raw[LEP_FX] = 16;
    s.raw[LEP_FY] = -16;
    s.raw[LEP_FZ] = 10000;
    s.raw[LEP_MX] = -10000;
    s.raw[LEP_MY] = 4112;
    s.raw[LEP_MZ] = 32000;
    s.status = 0x04;
    lep_device_set_sample(&dev, &s);
    send_cmd(LEP_CMD_SAMPLE, 0);
    {
        /* The data response of the spec's worked frames, byte for byte. */
        static const uint8_t wire[] = { 0x10, 0x02, 0x14, 0xFF, 0x30, 0x00, 0x10, 0x10, 0x00, 0xF0,
                                        0xFF, 0x10, 0x10, 0x27, 0xF0, 0xD8, 0x10, 0x10, 0x10, 0x10,
                                        0x00, 0x7D, 0x00, 0x00, 0x04, 0x00, 0x10, 0x03, 0xA1 };
        TEST_ASSERT_EQUAL_size_t(sizeof(wire), out_len);
        TEST_ASSERT_EQUAL_HEX8_ARRAY(wire, out, sizeof(wire));
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, answer(&r));
    TEST_ASSERT_EQUAL_INT16_ARRAY(s.raw, r.u.sample.raw, LEP_AXES);
}

static void test_bad_bcc_gets_nak(void)
{
    static const uint8_t bad[] = { 0x10, 0x02, 0x04, 0xFF, 0x2A, 0x00, 0x10, 0x03, 0xD3 };
    feed(bad, sizeof(bad));
    TEST_ASSERT_EQUAL_INT(LEP_DEVICE_NAK, ev.type);
    TEST_ASSERT_EQUAL_size_t(2, out_len);
    TEST_ASSERT_EQUAL_HEX8(0x10, out[0]);
    TEST_ASSERT_EQUAL_HEX8(0x15, out[1]);
}

static void test_result_codes(void)
{
    /* Length error: Length byte says 5 but 4 bytes came. */
    static const uint8_t wrong_len[] = { 0x05, 0xFF, 0x2A, 0x00 };
    static const uint8_t unknown[] = { 0x04, 0xFF, 0x99, 0x00 };
    static const uint8_t long_query[] = { 0x05, 0xFF, 0x2B, 0x00, 0x00 };
    static const uint8_t bad_reserved[] = { 0x04, 0xFE, 0x2A, 0x00 };
    uint8_t frame[LEP_MAX_FRAME];
    size_t n;
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_frame_encode(wrong_len, sizeof(wrong_len), frame, sizeof(frame), &n));
    feed(frame, n);
    expect_result(0x2A, LEP_RESULT_LENGTH);
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_frame_encode(long_query, sizeof(long_query), frame, sizeof(frame), &n));
    feed(frame, n);
    expect_result(0x2B, LEP_RESULT_LENGTH);
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_frame_encode(unknown, sizeof(unknown), frame, sizeof(frame), &n));
    feed(frame, n);
    TEST_ASSERT_EQUAL_INT(LEP_DEVICE_COMMAND, ev.type);
    TEST_ASSERT_EQUAL_HEX8(LEP_RESULT_UNDEFINED, ev.result);
    /* The host cannot decode an unknown code as a response: check the raw answer. */
    {
        static const uint8_t want[] = { 0x10, 0x02, 0x04, 0xFF, 0x99, 0x02, 0x10, 0x03, 0x63 };
        TEST_ASSERT_EQUAL_size_t(sizeof(want), out_len);
        TEST_ASSERT_EQUAL_HEX8_ARRAY(want, out, sizeof(want));
    }
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_frame_encode(bad_reserved, sizeof(bad_reserved), frame, sizeof(frame), &n));
    feed(frame, n);
    expect_result(0x2A, LEP_RESULT_VALUE);
    send_cmd(LEP_CMD_FILTER_SET, 3);
    expect_result(LEP_CMD_FILTER_SET, 0);
    {
        static const uint8_t filter4[] = { 0x08, 0xFF, 0xA6, 0x00, 0x04, 0x00, 0x00, 0x00 };
        TEST_ASSERT_EQUAL_INT(LEP_OK,
                              lep_frame_encode(filter4, sizeof(filter4), frame, sizeof(frame), &n));
        feed(frame, n);
        expect_result(LEP_CMD_FILTER_SET, LEP_RESULT_VALUE);
        TEST_ASSERT_EQUAL_UINT8(3, lep_device_filter_pending(&dev));
    }
}

static void test_state_errors_and_idempotent_stop(void)
{
    send_cmd(LEP_CMD_STOP, 0);
    expect_result(LEP_CMD_STOP, 0);
    send_cmd(LEP_CMD_START, 0);
    expect_result(LEP_CMD_START, 0);
    TEST_ASSERT_TRUE(lep_device_streaming(&dev));
    send_cmd(LEP_CMD_START, 0);
    expect_result(LEP_CMD_START, LEP_RESULT_STATE);
    send_cmd(LEP_CMD_FILTER_SET, 2);
    expect_result(LEP_CMD_FILTER_SET, LEP_RESULT_STATE);
    TEST_ASSERT_EQUAL_UINT8(1, lep_device_filter_pending(&dev));
    send_cmd(LEP_CMD_RATED, 0);
    expect_result(LEP_CMD_RATED, 0); /* queries are answered while streaming */
    send_cmd(LEP_CMD_STOP, 0);
    expect_result(LEP_CMD_STOP, 0);
    TEST_ASSERT_FALSE(lep_device_streaming(&dev));
}

static void test_filter_applies_at_power_cycle(void)
{
    send_cmd(LEP_CMD_FILTER_SET, 0);
    TEST_ASSERT_EQUAL_UINT8(1, lep_device_filter(&dev));
    TEST_ASSERT_EQUAL_UINT8(0, lep_device_filter_pending(&dev));
    send_cmd(LEP_CMD_START, 0);
    lep_device_power_cycle(&dev);
    TEST_ASSERT_EQUAL_UINT8(0, lep_device_filter(&dev));
    TEST_ASSERT_FALSE(lep_device_streaming(&dev));
}

static void test_stream_frame(void)
{
    lep_sample s;
    lep_response r;
    memset(&s, 0, sizeof(s));
    s.raw[LEP_FZ] = -1;
    s.reserved = 0x1234;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_device_stream_frame(&s, out, sizeof(out), &out_len));
    TEST_ASSERT_EQUAL_INT(LEP_OK, answer(&r));
    TEST_ASSERT_TRUE(r.stream);
    TEST_ASSERT_EQUAL_HEX8(LEP_CMD_START, r.code);
    TEST_ASSERT_EQUAL_INT16(-1, r.u.sample.raw[LEP_FZ]);
    TEST_ASSERT_EQUAL_HEX16(0x1234, r.u.sample.reserved);
    TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER, lep_device_stream_frame(&s, out, 10, &out_len));
}

static void test_unanswerable_frames(void)
{
    static const uint8_t escape[] = { 0x10, 0x02, 0x04, 0xFF, 0x10, 0x07 };
    static const uint8_t tiny[] = { 0x10, 0x02, 0x04, 0xFF, 0x10, 0x03, 0xF8 };
    feed(escape, sizeof(escape));
    TEST_ASSERT_EQUAL_INT(LEP_DEVICE_REJECTED, ev.type);
    TEST_ASSERT_EQUAL_size_t(0, out_len);
    feed(tiny, sizeof(tiny));
    TEST_ASSERT_EQUAL_INT(LEP_DEVICE_REJECTED, ev.type);
    TEST_ASSERT_EQUAL_size_t(0, out_len);
    /* Too small an output buffer drops the answer instead of overflowing. */
    {
        static const uint8_t info[] = { 0x10, 0x02, 0x04, 0xFF, 0x2A, 0x00, 0x10, 0x03, 0xD2 };
        size_t n = lep_device_feed(&dev, info, sizeof(info), &ev, out, 8, &out_len);
        TEST_ASSERT_EQUAL_size_t(sizeof(info), n);
        TEST_ASSERT_EQUAL_INT(LEP_DEVICE_COMMAND, ev.type);
        TEST_ASSERT_EQUAL_size_t(0, out_len);
    }
}

/* Every entry point with a NULL argument: a clear "nothing" instead of a crash. */
static void test_null_arguments(void)
{
    lep_product_info info;
    lep_rated rated = { { 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f } };
    lep_sample s;
    size_t n = 7;
    static const uint8_t byte = 0x10;
    memset(&info, 0, sizeof(info));
    memset(&s, 0, sizeof(s));
    TEST_ASSERT_EQUAL_size_t(sizeof(lep_device),
                             lep_device_sizeof()); /* what a binding allocates */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_device_init(NULL, &info, &rated, 0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_device_init(&dev, NULL, &rated, 0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_device_init(&dev, &info, NULL, 0));
    lep_device_set_sample(NULL, &s);
    lep_device_set_sample(&dev, NULL);
    TEST_ASSERT_FALSE(lep_device_streaming(NULL));
    TEST_ASSERT_EQUAL_UINT8(0, lep_device_filter(NULL));
    TEST_ASSERT_EQUAL_UINT8(0, lep_device_filter_pending(NULL));
    lep_device_power_cycle(NULL);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_device_stream_frame(NULL, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_size_t(0, lep_device_feed(NULL, &byte, 1, &ev, out, sizeof(out), &out_len));
    TEST_ASSERT_EQUAL_size_t(0, lep_device_feed(&dev, &byte, 1, NULL, out, sizeof(out), &out_len));
    TEST_ASSERT_EQUAL_size_t(0, lep_device_feed(&dev, &byte, 1, &ev, NULL, sizeof(out), &out_len));
    TEST_ASSERT_EQUAL_size_t(0, lep_device_feed(&dev, &byte, 1, &ev, out, sizeof(out), NULL));
    TEST_ASSERT_EQUAL_size_t(0, lep_device_feed(&dev, NULL, 1, &ev, out, sizeof(out), &out_len));
    TEST_ASSERT_EQUAL_INT(LEP_DEVICE_NONE, ev.type);
    TEST_ASSERT_EQUAL_size_t(0, lep_device_feed(&dev, NULL, 0, &ev, out, sizeof(out), &out_len));
    TEST_ASSERT_EQUAL_UINT8(1, lep_device_filter(&dev)); /* untouched */
}

/* A NAK that does not fit the caller's buffer is dropped, never overrun. */
static void test_nak_with_a_tiny_buffer(void)
{
    static const uint8_t bad[] = { 0x10, 0x02, 0x04, 0xFF, 0x2A, 0x00, 0x10, 0x03, 0xD3 };
    uint8_t tiny[1] = { 0xEE };
    size_t n = 99;
    size_t used = lep_device_feed(&dev, bad, sizeof(bad), &ev, tiny, sizeof(tiny), &n);
    TEST_ASSERT_EQUAL_size_t(sizeof(bad), used);
    TEST_ASSERT_EQUAL_INT(LEP_DEVICE_NAK, ev.type);
    TEST_ASSERT_EQUAL_size_t(0, n);
    TEST_ASSERT_EQUAL_HEX8(0xEE, tiny[0]);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_validates);
    RUN_TEST(test_init_rejects_identity_that_cannot_be_answered);
    RUN_TEST(test_answers_queries);
    RUN_TEST(test_handshake_answers_current_sample);
    RUN_TEST(test_bad_bcc_gets_nak);
    RUN_TEST(test_result_codes);
    RUN_TEST(test_state_errors_and_idempotent_stop);
    RUN_TEST(test_filter_applies_at_power_cycle);
    RUN_TEST(test_stream_frame);
    RUN_TEST(test_unanswerable_frames);
    RUN_TEST(test_null_arguments);
    RUN_TEST(test_nak_with_a_tiny_buffer);
    return UNITY_END();
}
