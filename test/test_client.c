/* Host client against the scripted in-memory sensor (test/support/script_io). */
#include <string.h>

#include "script_io.h"
#include "unity.h"

/* An error or result text as this build has it ("" with LEP_CONFIG_NO_ERROR_STRINGS). */
#define TEXT(s) (LEP_HAVE_ERROR_STRINGS ? (s) : "")

static script_io sio;
static lep_client client;
static lep_client_rx rx;

void setUp(void)
{
    script_io_client(&sio, &client);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_rx(&client, &rx));
}

/* A stream left running by an earlier program: the device streams before any command. */
static void leave_stream_running(void)
{
    static const uint8_t start[] = { 0x10, 0x02, 0x04, 0xFF, 0x32, 0x00, 0x10, 0x03, 0xCA };
    lep_device_event ev;
    uint8_t out[LEP_MAX_FRAME];
    size_t n;
    (void)lep_device_feed(&sio.dev, start, sizeof(start), &ev, out, sizeof(out), &n);
    TEST_ASSERT_TRUE(lep_device_streaming(&sio.dev));
}

/* The decoded message of the last outcome of c (asserted to exist). */
static lep_response last_response(const lep_client *c)
{
    lep_response r;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_response(c, &r));
    return r;
}

void tearDown(void)
{
}

static lep_client_stats stats(void)
{
    lep_client_stats st;
    lep_client_get_stats(&client, &st);
    return st;
}

static void force_reply(const uint8_t *msg, size_t len)
{
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_frame_encode(msg, len, sio.forced, sizeof(sio.forced), &sio.forced_len));
}

static void test_init_rejects_incomplete_io(void)
{
    lep_io io = script_io_table(&sio);
    lep_client c;
    io.now_ms = NULL;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_init(&c, &io));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_init(NULL, &io));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_set_timeout(&client, 0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_set_retries(&client, 256));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_set_retries(&client, -1));
    TEST_ASSERT_EQUAL_size_t(sizeof(lep_client), lep_client_sizeof());
    TEST_ASSERT_EQUAL_size_t(sizeof(lep_client_rx), lep_client_rx_sizeof());
}

/* lep_client_init zeroes the whole context and does not call
 * lep_frame_decoder_init: a zeroed decoder must be exactly an initialised one. */
static void test_init_zeroes_like_decoder_init(void)
{
    lep_frame_decoder zero;
    lep_frame_decoder d;
    lep_io io = script_io_table(&sio);
    lep_client c;
    memset(&zero, 0, sizeof(zero));
    memset(&d, 0xA5, sizeof(d));
    lep_frame_decoder_init(&d);
    TEST_ASSERT_EQUAL_MEMORY(&zero, &d, sizeof(d));
    memset(&c, 0xA5, sizeof(c));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(&c, &io));
    TEST_ASSERT_EQUAL_MEMORY(&zero, &c.dec, sizeof(c.dec));
}

static void test_product_info_and_rated(void)
{
    lep_product_info info;
    lep_rated rated;
    uint8_t filter = 9;
    static const uint8_t cmd[] = { 0x10, 0x02, 0x04, 0xFF, 0x2A, 0x00, 0x10, 0x03, 0xD2 };
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &info));
    TEST_ASSERT_EQUAL_UINT8_ARRAY(cmd, sio.out, sizeof(cmd));
    TEST_ASSERT_EQUAL_STRING("PFS055YA501U6", info.model);
    TEST_ASSERT_EQUAL_STRING("12345678", info.serial);
    TEST_ASSERT_EQUAL_STRING("1.13", info.firmware);
    TEST_ASSERT_FALSE(info.has_output_rate);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_FLOAT(500.0f, rated.axis[LEP_FX]);
    TEST_ASSERT_EQUAL_FLOAT(8.0f, rated.axis[LEP_MZ]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_get(&client, &filter));
    TEST_ASSERT_EQUAL_UINT8(0, filter);
    TEST_ASSERT_EQUAL_UINT32(3, stats().messages);
    TEST_ASSERT_EQUAL_UINT32(0, stats().unexpected);
}

static void test_transact_gives_the_whole_response(void)
{
    lep_command cmd = { LEP_CMD_RATED, 0 };
    lep_response r;
    memset(&r, 0xA5, sizeof(r));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_transact(&client, &cmd, &r));
    TEST_ASSERT_EQUAL_HEX8(LEP_CMD_RATED, r.code);
    TEST_ASSERT_EQUAL_HEX8(LEP_RESULT_OK, r.result);
    TEST_ASSERT_FALSE(r.stream);
    TEST_ASSERT_EQUAL_FLOAT(500.0f, r.u.rated.axis[LEP_FX]);
    TEST_ASSERT_EQUAL_FLOAT(8.0f, r.u.rated.axis[LEP_MZ]);
}

static void test_handshake_sample(void)
{
    lep_sample want;
    lep_sample got;
    memset(&want, 0, sizeof(want));
    want.raw[LEP_FX] = -10000;
    want.raw[LEP_MZ] = 4112;
    want.status = LEP_STATUS_OVERLOAD;
    lep_device_set_sample(&sio.dev, &want);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sample(&client, &got));
    TEST_ASSERT_EQUAL_INT16_ARRAY(want.raw, got.raw, LEP_AXES);
    TEST_ASSERT_EQUAL_HEX8(LEP_STATUS_OVERLOAD, got.status);
}

static void test_filter_set_needs_power_cycle(void)
{
    uint8_t f = 9;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_set(&client, 2));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_get(&client, &f));
    TEST_ASSERT_EQUAL_UINT8(0, f);
    lep_device_power_cycle(&sio.dev);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_filter_get(&client, &f));
    TEST_ASSERT_EQUAL_UINT8(2, f);
}

static void test_filter_set_rejects_bad_code_without_writing(void)
{
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_client_filter_set(&client, 4));
    TEST_ASSERT_EQUAL_UINT(0, sio.writes);
}

static void test_nak_then_success(void)
{
    lep_rated rated;
    sio.naks_left = 2;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_UINT(3, sio.writes);
    TEST_ASSERT_EQUAL_UINT32(2, stats().naks);
    TEST_ASSERT_EQUAL_UINT32(2, stats().retries);
    /* Every retransmission is the same frame. */
    TEST_ASSERT_EQUAL_MEMORY(sio.out, sio.out + 9, 9);
    TEST_ASSERT_EQUAL_MEMORY(sio.out, sio.out + 18, 9);
}

static void test_nak_past_the_limit(void)
{
    lep_rated rated;
    sio.naks_left = 100;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_retries(&client, 3));
    TEST_ASSERT_EQUAL_INT(LEP_E_NAK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_UINT(4, sio.writes);
    TEST_ASSERT_EQUAL_UINT32(3, stats().retries);
    TEST_ASSERT_FALSE(lep_client_busy(&client));
}

static void test_no_retries_when_disabled(void)
{
    lep_rated rated;
    sio.naks_left = 1;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_retries(&client, 0));
    TEST_ASSERT_EQUAL_INT(LEP_E_NAK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_UINT(1, sio.writes);
}

static void test_timeout(void)
{
    lep_product_info info;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_timeout(&client, 250));
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_product_info(&client, &info));
    /* The documented bound: (retries + 1) x timeout, every attempt the same frame. */
    TEST_ASSERT_EQUAL_UINT32(4u * 250u, sio.now);
    TEST_ASSERT_EQUAL_UINT(4, sio.writes);
    TEST_ASSERT_EQUAL_MEMORY(sio.out, sio.out + 27, 9);
    TEST_ASSERT_EQUAL_UINT32(1, stats().timeouts);
    TEST_ASSERT_EQUAL_UINT32(3, stats().resent_after_timeout);
    TEST_ASSERT_EQUAL_UINT32(0, stats().retries);
    TEST_ASSERT_FALSE(lep_client_busy(&client));
}

static void test_wrong_response_type_is_skipped(void)
{
    static const uint8_t filter_answer[] = { 0x08, 0xFF, 0xB6, 0x00, 0x01, 0x00, 0x00, 0x00 };
    lep_rated rated;
    /* The sensor first sends an answer of another type, then the right one. */
    script_push_msg(&sio, filter_answer, sizeof(filter_answer));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_FLOAT(500.0f, rated.axis[LEP_FY]);
    TEST_ASSERT_EQUAL_UINT32(1, stats().unexpected);
}

static void test_only_wrong_type_is_resent(void)
{
    static const uint8_t filter_answer[] = { 0x08, 0xFF, 0xB6, 0x00, 0x01, 0x00, 0x00, 0x00 };
    lep_rated rated;
    force_reply(filter_answer, sizeof(filter_answer));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_UINT32(1, stats().unexpected);
    TEST_ASSERT_EQUAL_UINT32(1, stats().resent_after_timeout);
    TEST_ASSERT_EQUAL_UINT32(LEP_CLIENT_DEFAULT_TIMEOUT_MS, sio.now);
}

static void test_sensor_error_codes(void)
{
    uint8_t code;
    for (code = 1; code <= 4; code++) {
        uint8_t msg[4] = { 0x04, 0xFF, 0x2B, 0 };
        lep_rated rated;
        msg[3] = code;
        force_reply(msg, sizeof(msg));
        TEST_ASSERT_EQUAL_INT(LEP_E_SENSOR, lep_client_rated(&client, &rated));
        TEST_ASSERT_EQUAL_UINT8(code, lep_client_last_result(&client));
    }
    TEST_ASSERT_EQUAL_STRING(TEXT("state error"), lep_result_str(lep_client_last_result(&client)));
}

static void test_invalid_answer_is_counted_not_taken(void)
{
    /* Rated values with a NaN for Fx: framed correctly, invalid as a message. */
    uint8_t msg[28] = { 0x1C, 0xFF, 0x2B, 0x00, 0x00, 0x00, 0xC0, 0x7F };
    lep_rated rated;
    force_reply(msg, sizeof(msg));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_FLOAT(500.0f, rated.axis[LEP_FX]);
    TEST_ASSERT_EQUAL_UINT32(1, stats().invalid);
    TEST_ASSERT_EQUAL_UINT32(1, stats().resent_after_timeout);
}

static void test_corrupt_answer_is_counted(void)
{
    static const uint8_t bad[] = { 0x10, 0x02, 0x04, 0xFF, 0x2A, 0x00, 0x10, 0x03, 0xD3 };
    lep_product_info info;
    memcpy(sio.forced, bad, sizeof(bad));
    sio.forced_len = sizeof(bad);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &info));
    TEST_ASSERT_EQUAL_UINT32(1, stats().resent_after_timeout);
    TEST_ASSERT_EQUAL_UINT32(1, stats().bcc_errors);
    TEST_ASSERT_EQUAL_UINT32(sizeof(bad), stats().bytes_discarded);
}

static void test_stale_stream_does_not_answer_queries(void)
{
    lep_rated rated;
    /* A stream left running by an earlier program. */
    leave_stream_running();
    TEST_ASSERT_TRUE(lep_device_streaming(&sio.dev));
    script_push_data(&sio);
    script_push_data(&sio);
    sio.inflight = 3;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_FLOAT(10.0f, rated.axis[LEP_MX]);
    TEST_ASSERT_EQUAL_UINT32(5, stats().unexpected);
}

static void test_sync_recovers_stale_stream(void)
{
    lep_product_info info;
    static const uint8_t start[] = { 0x10, 0x02, 0x04, 0xFF, 0x32, 0x00, 0x10, 0x03, 0xCA };
    leave_stream_running();
    script_push_data(&sio);
    /* Half a frame on the line when the program starts. */
    script_push(&sio, start + 3, 4);
    sio.inflight = 4;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 20, &info));
    TEST_ASSERT_FALSE(lep_device_streaming(&sio.dev));
    TEST_ASSERT_FALSE(lep_client_streaming(&client));
    TEST_ASSERT_EQUAL_STRING("PFS055YA501U6", info.model);
    TEST_ASSERT_EQUAL_size_t(0, script_pending(&sio));
}

static void test_sync_on_a_silent_line_times_out(void)
{
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_sync(&client, 20, NULL));
}

static void test_sync_gives_up_on_endless_noise(void)
{
    /* A device that answers nothing but streams forever: the line never goes quiet. */
    leave_stream_running();
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_E_NO_SYNC, lep_client_sync(&client, 20, NULL));
    /* The stop's (retries + 1) attempts, then at most 20 timeouts + the quiet time of draining. */
    TEST_ASSERT_TRUE(sio.now <= LEP_CLIENT_DEFAULT_TIMEOUT_MS * (4u + 20u) + 20u + 2u);
}

static void test_late_answer_is_skipped_by_the_next_query(void)
{
    static const uint8_t rated_answer[28] = { 0x1C, 0xFF, 0x2B, 0x00, 0x00, 0x00, 0x80,
                                              0x3F, 0x00, 0x00, 0x80, 0x3F, 0x00, 0x00,
                                              0x80, 0x3F, 0x00, 0x00, 0x80, 0x3F, 0x00,
                                              0x00, 0x80, 0x3F, 0x00, 0x00, 0x80, 0x3F };
    lep_rated rated;
    lep_product_info info;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_rated(&client, &rated));
    sio.silent = false;
    script_push_msg(&sio, rated_answer, sizeof(rated_answer)); /* the answer, too late */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &info));
    TEST_ASSERT_EQUAL_STRING("12345678", info.serial);
    TEST_ASSERT_EQUAL_UINT32(1, stats().unexpected);
    TEST_ASSERT_EQUAL_UINT32(1, stats().timeouts);
}

static void test_timeout_applies_to_each_attempt(void)
{
    /* A NAK just before the deadline restarts the wait for the retransmission. */
    static const uint8_t nak[2] = { LEP_DLE, LEP_NAK };
    lep_command cmd = { LEP_CMD_RATED, 0 };
    size_t used;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_retries(&client, 1));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &cmd));
    sio.now += LEP_CLIENT_DEFAULT_TIMEOUT_MS - 1u;
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, nak, sizeof(nak), &used));
    TEST_ASSERT_EQUAL_UINT(2, sio.writes);
    sio.now += LEP_CLIENT_DEFAULT_TIMEOUT_MS - 1u;
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
    sio.now += 1u;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_step(&client, NULL, 0, &used));
}

static void test_stream_start_next_stop(void)
{
    lep_sample s;
    unsigned i;
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_next_sample(&client, &s, 10));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_TRUE(lep_client_streaming(&client));
    for (i = 0; i < 50; i++) {
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, 100));
        TEST_ASSERT_EQUAL_UINT16(i, s.reserved);
    }
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_sample(&client, &s));
    sio.inflight = 7; /* data already on the line when the stop is answered */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    TEST_ASSERT_FALSE(lep_client_streaming(&client));
    TEST_ASSERT_FALSE(lep_device_streaming(&sio.dev));
    TEST_ASSERT_EQUAL_UINT32(0, stats().unexpected);
    TEST_ASSERT_EQUAL_UINT32(50, stats().samples);
}

static void test_start_while_streaming_is_a_state_error(void)
{
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_EQUAL_INT(LEP_E_SENSOR, lep_client_start(&client));
    TEST_ASSERT_EQUAL_UINT8(LEP_RESULT_STATE, lep_client_last_result(&client));
    TEST_ASSERT_TRUE(lep_client_streaming(&client));
    TEST_ASSERT_EQUAL_UINT32(0, stats().recoveries);
}

static void test_start_refused_by_a_stale_stream_recovers_once(void)
{
    static const uint8_t stop_cmd[] = { 0x10, 0x02, 0x04, 0xFF, 0x33, 0x00, 0x10, 0x03, 0xCB };
    static const uint8_t start_cmd[] = { 0x10, 0x02, 0x04, 0xFF, 0x32, 0x00, 0x10, 0x03, 0xCA };
    /* A stream left running by an earlier program. */
    leave_stream_running();
    script_push_data(&sio);
    sio.inflight = 2;
    /* The sensor refuses (0x04: already streaming): stop, drain, start. */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_TRUE(lep_client_streaming(&client));
    TEST_ASSERT_TRUE(lep_device_streaming(&sio.dev));
    TEST_ASSERT_EQUAL_UINT32(1, stats().recoveries);
    TEST_ASSERT_EQUAL_UINT8(LEP_RESULT_OK, lep_client_last_result(&client));
    TEST_ASSERT_EQUAL_size_t(27, sio.out_len);
    TEST_ASSERT_EQUAL_MEMORY(start_cmd, sio.out, 9);
    TEST_ASSERT_EQUAL_MEMORY(stop_cmd, sio.out + 9, 9);
    TEST_ASSERT_EQUAL_MEMORY(start_cmd, sio.out + 18, 9);
}

static void test_start_refused_twice_is_a_sensor_error(void)
{
    static const uint8_t refused[] = { 0x04, 0xFF, 0x32, 0x04 };
    lep_command start = { LEP_CMD_START, 0 };
    uint8_t frame[16];
    size_t n;
    size_t used;
    int rc = LEP_STEP_NONE;
    unsigned i;
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_frame_encode(refused, sizeof(refused), frame, sizeof(frame), &n));
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &start));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, frame, n, &used));
    TEST_ASSERT_EQUAL_UINT(2, sio.writes); /* the stop */
    TEST_ASSERT_TRUE(lep_client_busy(&client));
    sio.now += LEP_CLIENT_DEFAULT_TIMEOUT_MS * 4u; /* the stop is never answered: drain anyway */
    for (i = 0; i < 4 && sio.writes < 6; i++) {
        TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
        sio.now += LEP_CLIENT_DEFAULT_TIMEOUT_MS;
    }
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
    sio.now += LEP_CLIENT_DEFAULT_QUIET_MS;
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
    TEST_ASSERT_EQUAL_UINT8(LEP_CMD_START, sio.out[sio.out_len - 5]); /* started again */
    rc = lep_client_step(&client, frame, n, &used);
    TEST_ASSERT_EQUAL_INT(LEP_E_SENSOR, rc);
    TEST_ASSERT_EQUAL_UINT8(LEP_RESULT_STATE, lep_client_last_result(&client));
    TEST_ASSERT_FALSE(lep_client_streaming(&client));
    TEST_ASSERT_FALSE(lep_client_busy(&client));
    TEST_ASSERT_EQUAL_UINT32(0, stats().recoveries);
}

static void test_next_samples_batches_buffered_data(void)
{
    lep_sample s[16];
    size_t n = 0;
    unsigned i;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    for (i = 0; i < 10; i++) {
        script_push_data(&sio);
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_samples(&client, s, 16, &n, 100));
    TEST_ASSERT_EQUAL_size_t(10, n);
    for (i = 0; i < 10; i++) {
        TEST_ASSERT_EQUAL_UINT16(i, s[i].reserved);
    }
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_next_samples(&client, s, 16, &n, 30));
    TEST_ASSERT_EQUAL_size_t(0, n);
}

static void test_next_sample_timeout_when_stream_stalls(void)
{
    lep_sample s;
    uint32_t t0;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    t0 = sio.now;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_next_sample(&client, &s, 40));
    TEST_ASSERT_EQUAL_UINT32(t0 + 40, sio.now);
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_next_sample(&client, &s, 0));
    TEST_ASSERT_EQUAL_UINT32(2, stats().timeouts);
}

static void test_byte_by_byte_reads(void)
{
    lep_product_info info;
    lep_sample s;
    sio.max_chunk = 1;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &info));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, 100));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, 100));
    TEST_ASSERT_EQUAL_UINT16(1, s.reserved);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
}

static void test_io_errors_propagate(void)
{
    lep_product_info info;
    lep_sample s;
    sio.read_error = LEP_E_DISCONNECTED;
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, lep_client_product_info(&client, &info));
    TEST_ASSERT_FALSE(lep_client_busy(&client));
    sio.read_error = 0;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.read_error = LEP_E_DISCONNECTED;
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, lep_client_next_sample(&client, &s, 100));
    sio.write_error = LEP_E_IO;
    TEST_ASSERT_EQUAL_INT(LEP_E_IO, lep_client_stop(&client));
}

/* A stop that never went out leaves the stream on: its samples are still
 * delivered (the pending command is a stop, but no stop waits). */
static void test_samples_after_a_failed_stop(void)
{
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.write_error = LEP_E_IO;
    TEST_ASSERT_EQUAL_INT(LEP_E_IO, lep_client_stop(&client));
    sio.write_error = 0;
    TEST_ASSERT_TRUE(lep_client_streaming(&client));
    TEST_ASSERT_FALSE(lep_client_busy(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, 100));
    TEST_ASSERT_EQUAL_UINT32(1, stats().samples);
    TEST_ASSERT_EQUAL_UINT32(0, stats().unexpected);
}

static void test_step_api_without_read(void)
{
    /* An MCU super-loop: the client never reads; bytes are fed as they come. */
    lep_command cmd = { LEP_CMD_RATED, 0 };
    lep_io io = script_io_table(&sio);
    lep_client c;
    size_t used;
    size_t i;
    int rc = LEP_STEP_NONE;
    io.read = NULL;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(&c, &io));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_rated(&c, &(lep_rated){ { 0 } }));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&c, &cmd));
    TEST_ASSERT_TRUE(lep_client_busy(&c));
    for (i = sio.in_pos; i < sio.in_len; i++) {
        rc = lep_client_step(&c, &sio.in[i], 1, &used);
        TEST_ASSERT_EQUAL_size_t(1, used);
        if (rc != LEP_STEP_NONE) {
            break;
        }
    }
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, rc);
    TEST_ASSERT_EQUAL_size_t(sio.in_len - 1, i);
    TEST_ASSERT_EQUAL_FLOAT(40.0f / 4.0f, last_response(&c).u.rated.axis[LEP_MY]);
    TEST_ASSERT_FALSE(lep_client_busy(&c));
}

static void test_step_api_deadline(void)
{
    lep_command cmd = { LEP_CMD_STOP, 0 };
    size_t used;
    unsigned i;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &cmd));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
    for (i = 1; i <= LEP_CLIENT_DEFAULT_RETRIES; i++) {
        sio.now += LEP_CLIENT_DEFAULT_TIMEOUT_MS;
        TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
        TEST_ASSERT_EQUAL_UINT(1u + i, sio.writes); /* resent */
    }
    sio.now += LEP_CLIENT_DEFAULT_TIMEOUT_MS;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_step(&client, NULL, 0, &used));
    TEST_ASSERT_FALSE(lep_client_busy(&client));
}

static void test_step_api_stops_at_each_sample(void)
{
    uint8_t wire[3 * 29];
    size_t len = 0;
    size_t used;
    size_t pos = 0;
    unsigned got = 0;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    len = script_take_data(&sio, 3, wire, sizeof(wire));
    while (pos < len) {
        int rc = lep_client_step(&client, wire + pos, len - pos, &used);
        pos += used;
        if (rc == LEP_STEP_SAMPLE) {
            TEST_ASSERT_EQUAL_UINT16(got, last_response(&client).u.sample.reserved);
            got++;
        }
    }
    TEST_ASSERT_EQUAL_UINT(3, got);
}

/* ---- lep_client_step_byte ---- */

/* A streaming client on the script's table (the start's answer stepped in by hand). */
static void start_streaming(lep_client *c)
{
    static const uint8_t ack[] = { 0x10, 0x02, 0x04, 0xFF, 0x32, 0x00, 0x10, 0x03, 0xCA };
    lep_io io = script_io_table(&sio);
    lep_command start = { LEP_CMD_START, 0 };
    size_t used;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(c, &io));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(c, &start));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, lep_client_step(c, ack, sizeof(ack), &used));
    TEST_ASSERT_TRUE(lep_client_streaming(c));
}

/* Data frames with stuffed bytes, and between them a frame with a bad BCC,
 * noise, a NAK, an empty frame, a restart and a sample whose BCC is 0x10. */
static size_t mixed_stream(uint8_t *wire, size_t cap)
{
    static const uint8_t junk[] = { 0x55, 0x10, 0x10, 0x10, 0x15, 0x10, 0x02, 0x10, 0x03,
                                    0x03, 0x10, 0x41, 0x10, 0x02, 0x04, 0x10, 0x02 };
    size_t n = 0;
    unsigned i;
    for (i = 0; i < 48u; i++) {
        lep_sample smp;
        size_t k = 0;
        memset(&smp, 0, sizeof(smp));
        smp.raw[LEP_FX] = (int16_t)(0x1010 + (int)i);
        smp.raw[LEP_FZ] = (int16_t)(i * 37u);
        smp.reserved = (uint16_t)(i * 0x0101u);
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_device_stream_frame(&smp, wire + n, cap - n, &k));
        if (i == 5u) {
            wire[n + k - 1u] = (uint8_t)(wire[n + k - 1u] ^ 0x5Au); /* a bad BCC */
        }
        n += k;
        if (i % 16u == 9u) {
            TEST_ASSERT_TRUE(n + sizeof(junk) <= cap);
            memcpy(wire + n, junk, sizeof(junk));
            n += sizeof(junk);
        }
    }
    return n;
}

typedef struct outcomes {
    int rc[128];
    uint16_t reserved[128]; /* the sample's reserved field, for LEP_STEP_SAMPLE */
    size_t n;
} outcomes;

static void note(outcomes *o, lep_client *c, int rc)
{
    lep_sample s;
    TEST_ASSERT_TRUE(o->n < 128u);
    o->rc[o->n] = rc;
    o->reserved[o->n] = 0;
    if (rc == LEP_STEP_SAMPLE) {
        lep_response r;
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_get_sample(c, &s));
        o->reserved[o->n] = s.reserved;
        /* get_sample gives what decoding the message gives, field by field */
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_response(c, &r));
        TEST_ASSERT_TRUE(r.stream);
        TEST_ASSERT_EQUAL_INT16_ARRAY(r.u.sample.raw, s.raw, LEP_AXES);
        TEST_ASSERT_EQUAL_UINT16(r.u.sample.reserved, s.reserved);
        TEST_ASSERT_EQUAL_UINT8(r.u.sample.status, s.status);
    }
    o->n++;
}

static void test_step_byte_gives_what_step_gives_at_every_chunking(void)
{
    static const size_t chunks[] = { 1, 2, 3, 7, 25, 64, 4096 };
    uint8_t wire[2048];
    size_t len = mixed_stream(wire, sizeof(wire));
    outcomes ref;
    lep_client_stats want;
    lep_client c;
    size_t i;
    memset(&ref, 0, sizeof(ref));
    start_streaming(&client);
    for (i = 0; i < len; i++) {
        lep_sample s;
        int rc = lep_client_step_byte(&client, wire[i], &s);
        if (rc != LEP_STEP_NONE) {
            note(&ref, &client, rc);
        }
        if (rc == LEP_STEP_SAMPLE) { /* out is what lep_client_get_sample gives */
            TEST_ASSERT_EQUAL_UINT16(ref.reserved[ref.n - 1u], s.reserved);
            TEST_ASSERT_EQUAL_INT16((int16_t)(0x1010 + (int)s.reserved % 256), s.raw[LEP_FX]);
        }
    }
    lep_client_get_stats(&client, &want);
    TEST_ASSERT_EQUAL_UINT32(47, want.samples); /* 48 less the bad BCC */
    TEST_ASSERT_EQUAL_UINT32(1, want.bcc_errors);
    TEST_ASSERT_TRUE(want.invalid >= 1u);
    TEST_ASSERT_EQUAL_UINT32(6, want.frame_errors); /* two restarts in each junk */
    TEST_ASSERT_EQUAL_size_t(47, ref.n);
    for (i = 0; i < sizeof(chunks) / sizeof(chunks[0]); i++) {
        const size_t chunk = chunks[i];
        outcomes got;
        lep_client_stats st;
        size_t pos = 0;
        memset(&got, 0, sizeof(got));
        start_streaming(&c);
        while (pos < len) {
            size_t used = 0;
            size_t n = len - pos < chunk ? len - pos : chunk;
            int rc = lep_client_step(&c, wire + pos, n, &used);
            TEST_ASSERT_TRUE(used >= 1u && used <= n);
            pos += used;
            if (rc != LEP_STEP_NONE) {
                note(&got, &c, rc);
            }
        }
        lep_client_get_stats(&c, &st);
        TEST_ASSERT_EQUAL_size_t(ref.n, got.n);
        TEST_ASSERT_EQUAL_INT_ARRAY(ref.rc, got.rc, ref.n);
        TEST_ASSERT_EQUAL_UINT16_ARRAY(ref.reserved, got.reserved, ref.n);
        TEST_ASSERT_EQUAL_MEMORY(&want, &st, sizeof(st));
    }
}

static void test_step_byte_message_lasts_until_the_next_step(void)
{
    uint8_t wire[64];
    lep_sample s;
    lep_response r;
    size_t len;
    size_t i = 0;
    int rc = LEP_STEP_NONE;
    start_streaming(&client);
    sio.endless_stream = false;
    sio.in_len = sio.in_pos = 0;
    script_push_data(&sio);
    script_push_data(&sio);
    len = script_pending(&sio);
    memcpy(wire, sio.in, len);
    for (; i < len && rc == LEP_STEP_NONE; i++) {
        rc = lep_client_step_byte(&client, wire[i], NULL); /* out may be NULL */
    }
    TEST_ASSERT_EQUAL_INT(LEP_STEP_SAMPLE, rc);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_get_sample(&client, &s));
    TEST_ASSERT_EQUAL_UINT16(0, s.reserved);
    /* The next byte ends it (on the inline path too). */
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step_byte(&client, wire[i++], &s));
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_get_sample(&client, &s));
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_response(&client, &r));
    for (rc = LEP_STEP_NONE; i < len && rc == LEP_STEP_NONE; i++) {
        rc = lep_client_step_byte(&client, wire[i], &s);
    }
    TEST_ASSERT_EQUAL_INT(LEP_STEP_SAMPLE, rc);
    TEST_ASSERT_EQUAL_UINT16(1, s.reserved);
    /* Settings leave it alone. */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_watchdog(&client, 50));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_get_sample(&client, &s));
    TEST_ASSERT_EQUAL_UINT16(1, s.reserved);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_watchdog(&client, 0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_response(&client, &r));
    TEST_ASSERT_TRUE(r.stream);
    /* A transaction without a place for its answer. */
    {
        lep_command stop = { LEP_CMD_STOP, 0 };
        sio.silent = false;
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_rx(&client, &rx));
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_transact(&client, &stop, NULL));
        TEST_ASSERT_FALSE(lep_client_streaming(&client));
    }
}

static void test_step_byte_reads_the_clock_every_32_bytes(void)
{
    lep_command cmd = { LEP_CMD_RATED, 0 };
    static const uint8_t open[] = { 0x10, 0x02 };
    uint32_t t0;
    unsigned i;
    int rc = LEP_STEP_NONE;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_timeout(&client, 1000));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &cmd));
    sio.tick = 1; /* every clock read moves the clock 1 ms: it counts them */
    t0 = sio.now;
    for (i = 0; i < sizeof(open); i++) {
        TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step_byte(&client, open[i], NULL));
    }
    for (i = 0; i < 96u; i++) { /* the body of a frame that never ends */
        TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step_byte(&client, 0x41, NULL));
    }
    TEST_ASSERT_TRUE(sio.now - t0 >= 98u / 32u); /* at least every 32 steps */
    TEST_ASSERT_TRUE(sio.now - t0 <= 98u / 32u + 1u);
    /* The timeout passes mid-frame: the resend comes within 32 bytes. */
    sio.tick = 0;
    sio.now += 1000;
    for (i = 0; i < 32u && sio.writes < 2u; i++) {
        rc = lep_client_step_byte(&client, 0x42, NULL);
    }
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, rc);
    TEST_ASSERT_EQUAL_UINT(2, sio.writes);
    TEST_ASSERT_EQUAL_UINT32(1, stats().resent_after_timeout);
}

static void test_two_clients_are_independent(void)
{
    script_io other;
    lep_client c2;
    lep_client_stats st2;
    lep_io io;
    lep_product_info info;
    lep_rated rated;
    script_io_init(&other);
    io = script_io_table(&other);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(&c2, &io));
    other.naks_left = 1;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&c2, &info));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&c2, &rated));
    TEST_ASSERT_TRUE(lep_client_streaming(&client));
    TEST_ASSERT_FALSE(lep_client_streaming(&c2));
    TEST_ASSERT_EQUAL_UINT32(0, stats().naks);
    lep_client_get_stats(&c2, &st2);
    TEST_ASSERT_EQUAL_UINT32(1, st2.naks);
    TEST_ASSERT_EQUAL_UINT32(1, st2.retries);
}

/* ---- clock wrap-around: now_ms wraps at 2^32 in the middle of a wait ---- */

static void test_transaction_timeout_across_clock_wrap(void)
{
    lep_product_info info;
    sio.now = 0xFFFFFFFFu - 30u;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_product_info(&client, &info));
    TEST_ASSERT_EQUAL_UINT32(0xFFFFFFFFu - 30u + 4u * LEP_CLIENT_DEFAULT_TIMEOUT_MS, sio.now);
}

static void test_nak_retry_and_answer_across_clock_wrap(void)
{
    lep_rated rated;
    sio.now = 0xFFFFFFFFu;
    sio.naks_left = 2;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_UINT32(2, stats().retries);
    TEST_ASSERT_EQUAL_UINT32(0, stats().timeouts);
}

static void test_next_sample_timeout_across_clock_wrap(void)
{
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    sio.now = 0xFFFFFFFFu - 10u;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_next_sample(&client, &s, 40));
    TEST_ASSERT_EQUAL_UINT32(29u, sio.now); /* exactly 40 ms later, past the wrap */
}

static void test_step_api_deadline_across_clock_wrap(void)
{
    lep_command cmd = { LEP_CMD_STOP, 0 };
    size_t used;
    sio.silent = true;
    sio.now = 0xFFFFFFFFu - 5u;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_retries(&client, 0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &cmd));
    sio.now += LEP_CLIENT_DEFAULT_TIMEOUT_MS - 1u; /* wrapped, 1 ms before the deadline */
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
    sio.now += 1u;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_step(&client, NULL, 0, &used));
}

static void test_sync_across_clock_wrap(void)
{
    lep_product_info info;
    sio.now = 0xFFFFFFFFu - 3u;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 20, &info));
    TEST_ASSERT_EQUAL_STRING("PFS055YA501U6", info.model);
}

/* ---- next_sample timeouts ---- */

static void test_next_sample_negative_timeout_waits_forever(void)
{
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.stall_reads = 5; /* five empty reads (5 s of virtual time) before data flows again */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, -1));
    TEST_ASSERT_EQUAL_INT(-1, sio.last_timeout);
    TEST_ASSERT_TRUE(sio.now >= 5000u);
    TEST_ASSERT_EQUAL_UINT32(0, stats().timeouts);
}

static void test_next_sample_times_out_on_endless_noise(void)
{
    /* Bytes keep coming but never form a frame (e.g. a wrong baud rate). */
    lep_sample s;
    uint32_t t0;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    sio.noise = true;
    t0 = sio.now;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_next_sample(&client, &s, 50));
    TEST_ASSERT_TRUE(sio.now - t0 >= 50u);
    TEST_ASSERT_TRUE(sio.now - t0 <= 52u);
    TEST_ASSERT_EQUAL_UINT32(1, stats().timeouts);
}

static void test_next_sample_zero_timeout_reads_once_on_endless_noise(void)
{
    lep_sample s;
    unsigned reads;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    sio.noise = true;
    reads = sio.reads;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_next_sample(&client, &s, 0));
    TEST_ASSERT_TRUE(sio.reads - reads <= 2u);
}

static void test_next_samples_returns_on_endless_noise(void)
{
    lep_sample s[4];
    size_t n = 9;
    unsigned reads;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    script_push_data(&sio);
    sio.noise = true;
    reads = sio.reads;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_samples(&client, s, 4, &n, 100));
    TEST_ASSERT_EQUAL_size_t(1, n);
    TEST_ASSERT_TRUE(sio.reads - reads <= 8u);
}

static void test_transaction_times_out_on_endless_noise(void)
{
    lep_rated rated;
    uint32_t t0 = sio.now;
    sio.silent = true;
    sio.noise = true;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_rated(&client, &rated));
    TEST_ASSERT_TRUE(sio.now - t0 >= 4u * LEP_CLIENT_DEFAULT_TIMEOUT_MS);
    TEST_ASSERT_TRUE(sio.now - t0 <= 4u * (LEP_CLIENT_DEFAULT_TIMEOUT_MS + 2u));
    TEST_ASSERT_EQUAL_UINT32(3, stats().resent_after_timeout);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)sio.total_read, stats().bytes_discarded);
}

/* ---- counters ---- */

static void test_samples_skipped_by_a_query_are_not_counted_as_delivered(void)
{
    lep_rated rated;
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    script_push_data(&sio);
    script_push_data(&sio);
    script_push_data(&sio);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_UINT32(0, stats().samples);
    TEST_ASSERT_EQUAL_UINT32(3, stats().unexpected);
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_next_sample(&client, &s, 0));
    script_push_data(&sio);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, 0));
    TEST_ASSERT_EQUAL_UINT16(3, s.reserved);
    TEST_ASSERT_EQUAL_UINT32(1, stats().samples);
}

static void test_sync_accounts_for_every_stale_byte(void)
{
    /* A stale stream: two data frames in flight before the stop answer, one
     * more right after it, and the reads split that last frame. */
    static const uint8_t stop_answer[] = { 0x10, 0x02, 0x04, 0xFF, 0x33, 0x00, 0x10, 0x03, 0xCB };
    lep_product_info info;
    lep_sample smp;
    size_t n;
    lep_client_stats st;
    leave_stream_running();
    memset(&smp, 0, sizeof(smp));
    memcpy(sio.forced, stop_answer, sizeof(stop_answer));
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_device_stream_frame(&smp, sio.forced + sizeof(stop_answer),
                                                  sizeof(sio.forced) - sizeof(stop_answer), &n));
    TEST_ASSERT_EQUAL_size_t(25, n);
    sio.forced_len = sizeof(stop_answer) + n;
    sio.inflight = 2;
    sio.max_chunk = 20; /* 25 + 25 + 9 = 59: the third read ends 1 byte into the last frame */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 20, &info));
    st = stats();
    TEST_ASSERT_EQUAL_UINT32(0, st.bytes_discarded);
    TEST_ASSERT_EQUAL_UINT32(0, st.bcc_errors + st.frame_errors + st.invalid);
    TEST_ASSERT_EQUAL_UINT32(3, st.unexpected); /* a stream this client did not start */
    TEST_ASSERT_EQUAL_UINT32(5, st.messages);   /* 3 data, stop answer, product info */
}

static void test_read_claiming_more_than_asked_is_an_io_error(void)
{
    lep_product_info info;
    sio.overclaim = 1000;
    TEST_ASSERT_EQUAL_INT(LEP_E_IO, lep_client_product_info(&client, &info));
    TEST_ASSERT_FALSE(lep_client_busy(&client));
}

static void test_stop_with_data_in_flight_in_small_reads(void)
{
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, 100));
    sio.max_chunk = 7;
    sio.inflight = 5;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    TEST_ASSERT_FALSE(lep_client_streaming(&client));
    TEST_ASSERT_EQUAL_UINT32(0, stats().unexpected);
    TEST_ASSERT_EQUAL_UINT32(0, stats().bytes_discarded);
    TEST_ASSERT_EQUAL_UINT32(1, stats().samples);
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_next_sample(&client, &s, 0));
}

/* ---- step API fed from an ISR-filled ring buffer, no read at all ---- */

#define RING_SIZE 32u

typedef struct ring {
    uint8_t buf[RING_SIZE];
    uint32_t head; /* written by the "ISR" */
    uint32_t tail; /* advanced by the main loop */
} ring;

/* The "ISR": move up to max bytes the sensor sent into the ring. */
static void isr_receive(ring *r, size_t max)
{
    while (max-- > 0 && script_pending(&sio) > 0 && r->head - r->tail < RING_SIZE) {
        r->buf[r->head % RING_SIZE] = sio.in[sio.in_pos++];
        r->head++;
    }
}

/* The super-loop: feed the ring's contiguous spans to the client until an outcome. */
static int loop_once(lep_client *c, ring *r)
{
    while (r->head != r->tail) {
        size_t at = r->tail % RING_SIZE;
        size_t span = r->head - r->tail;
        size_t used = 0;
        int rc;
        if (span > RING_SIZE - at) {
            span = RING_SIZE - at;
        }
        rc = lep_client_step(c, r->buf + at, span, &used);
        TEST_ASSERT_TRUE(used >= 1 && used <= span);
        r->tail += (uint32_t)used;
        if (rc != LEP_STEP_NONE) {
            return rc;
        }
    }
    return lep_client_step(c, NULL, 0, &(size_t){ 0 });
}

static int run_until_outcome(lep_client *c, ring *r)
{
    unsigned spins;
    for (spins = 0; spins < 10000u; spins++) {
        int rc;
        isr_receive(r, 11); /* odd-sized bursts: frames straddle the ring's end */
        rc = loop_once(c, r);
        if (rc != LEP_STEP_NONE) {
            return rc;
        }
        sio.now += 1;
    }
    return LEP_STEP_NONE;
}

static void test_step_api_from_a_ring_buffer(void)
{
    lep_io io = script_io_table(&sio);
    lep_client c;
    ring r;
    lep_command start = { LEP_CMD_START, 0 };
    lep_command stop = { LEP_CMD_STOP, 0 };
    lep_command rated = { LEP_CMD_RATED, 0 };
    lep_client_stats st;
    unsigned i;
    memset(&r, 0, sizeof(r));
    io.read = NULL;
    sio.endless_stream = false;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(&c, &io));

    sio.naks_left = 1;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&c, &rated));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, run_until_outcome(&c, &r));
    TEST_ASSERT_EQUAL_FLOAT(500.0f, last_response(&c).u.rated.axis[LEP_FZ]);

    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&c, &start));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, run_until_outcome(&c, &r));
    TEST_ASSERT_TRUE(lep_client_streaming(&c));
    for (i = 0; i < 20; i++) {
        script_push_data(&sio);
    }
    for (i = 0; i < 20; i++) {
        TEST_ASSERT_EQUAL_INT(LEP_STEP_SAMPLE, run_until_outcome(&c, &r));
        TEST_ASSERT_EQUAL_UINT16(i, last_response(&c).u.sample.reserved);
    }
    sio.inflight = 3;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&c, &stop));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, run_until_outcome(&c, &r));
    TEST_ASSERT_FALSE(lep_client_streaming(&c));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, run_until_outcome(&c, &r));
    TEST_ASSERT_EQUAL_UINT32(0, sio.reads);

    lep_client_get_stats(&c, &st);
    TEST_ASSERT_EQUAL_UINT32(1, st.naks);
    TEST_ASSERT_EQUAL_UINT32(1, st.retries);
    TEST_ASSERT_EQUAL_UINT32(20, st.samples);
    TEST_ASSERT_EQUAL_UINT32(0, st.unexpected);
    TEST_ASSERT_EQUAL_UINT32(0, st.bytes_discarded);
    TEST_ASSERT_EQUAL_UINT32(3 + 20 + 3, st.messages);
}

/* ---- resending (issue: survive a real line) ---- */

static void test_lost_answer_is_resent(void)
{
    lep_rated rated;
    sio.lose_answers = 2;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_UINT(3, sio.writes);
    TEST_ASSERT_EQUAL_UINT32(2, stats().resent_after_timeout);
    TEST_ASSERT_EQUAL_UINT32(0, stats().timeouts);
    TEST_ASSERT_EQUAL_UINT32(2u * LEP_CLIENT_DEFAULT_TIMEOUT_MS, sio.now);
}

static void test_lost_command_is_resent(void)
{
    lep_product_info info;
    sio.lose_commands = 1;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &info));
    TEST_ASSERT_EQUAL_UINT32(1, stats().resent_after_timeout);
    TEST_ASSERT_EQUAL_STRING("12345678", info.serial);
}

static void test_naks_and_timeouts_share_one_budget(void)
{
    lep_rated rated;
    sio.naks_left = 2;
    sio.lose_answers = 5;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_UINT(4, sio.writes);
    TEST_ASSERT_EQUAL_UINT32(2, stats().retries);
    TEST_ASSERT_EQUAL_UINT32(1, stats().resent_after_timeout);
    TEST_ASSERT_EQUAL_UINT32(1, stats().timeouts);
}

static void test_resent_start_answered_state_error_counts_as_started(void)
{
    sio.lose_answers = 1; /* the start is executed, its answer lost; no data yet */
    sio.endless_stream = false;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_TRUE(lep_client_streaming(&client));
    TEST_ASSERT_TRUE(lep_device_streaming(&sio.dev));
    TEST_ASSERT_EQUAL_UINT(2, sio.writes);
    TEST_ASSERT_EQUAL_UINT32(1, stats().resent_confirmed);
    TEST_ASSERT_EQUAL_UINT32(0, stats().recoveries);
    TEST_ASSERT_EQUAL_UINT8(LEP_RESULT_STATE, lep_client_last_result(&client));
}

static void test_resent_start_with_data_flowing_counts_as_started(void)
{
    lep_command start = { LEP_CMD_START, 0 };
    lep_response r;
    lep_sample smp;
    uint8_t wire[64];
    size_t len;
    size_t used;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &start));
    sio.now += LEP_CLIENT_DEFAULT_TIMEOUT_MS;
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
    TEST_ASSERT_EQUAL_UINT(2, sio.writes); /* resent */
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_response(&client, &r));
    /* The first copy was executed after all: its data arrives. */
    script_push_data(&sio);
    len = script_pending(&sio);
    memcpy(wire, sio.in + sio.in_pos, len);
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, lep_client_step(&client, wire, len, &used));
    TEST_ASSERT_EQUAL_size_t(len, used);
    TEST_ASSERT_TRUE(lep_client_streaming(&client));
    TEST_ASSERT_EQUAL_UINT32(1, stats().resent_confirmed);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_response(&client, &r));
    TEST_ASSERT_TRUE(r.stream);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_get_sample(&client, &smp));
    TEST_ASSERT_EQUAL_UINT16(0, smp.reserved);
}

static void test_data_before_the_first_start_answer_is_not_taken_as_started(void)
{
    lep_command start = { LEP_CMD_START, 0 };
    uint8_t wire[64];
    size_t len;
    size_t used;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &start));
    script_push_data(&sio);
    len = script_pending(&sio);
    memcpy(wire, sio.in + sio.in_pos, len);
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, wire, len, &used));
    TEST_ASSERT_FALSE(lep_client_streaming(&client));
    TEST_ASSERT_TRUE(lep_client_busy(&client));
    TEST_ASSERT_EQUAL_UINT32(1, stats().unexpected);
}

static void test_resent_stop_answered_state_error_counts_as_stopped(void)
{
    static const uint8_t refused[] = { 0x04, 0xFF, 0x33, 0x04 };
    lep_command stop = { LEP_CMD_STOP, 0 };
    uint8_t frame[16];
    size_t n;
    size_t used;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_frame_encode(refused, sizeof(refused), frame, sizeof(frame), &n));
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &stop));
    /* First copy refused: a sensor error (the client cannot know it was stopped). */
    TEST_ASSERT_EQUAL_INT(LEP_E_SENSOR, lep_client_step(&client, frame, n, &used));
    TEST_ASSERT_TRUE(lep_client_streaming(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &stop));
    sio.now += LEP_CLIENT_DEFAULT_TIMEOUT_MS;
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, lep_client_step(&client, frame, n, &used));
    TEST_ASSERT_FALSE(lep_client_streaming(&client));
    TEST_ASSERT_EQUAL_UINT32(1, stats().resent_confirmed);
}

/* ---- step API: recovery and watchdog ---- */

/* Feed everything the script has queued, one byte per step; advance the clock
 * 1 ms per call with nothing to feed. Returns the first outcome. */
static int pump(lep_client *c, unsigned max_ms)
{
    unsigned spins;
    for (spins = 0; spins < 100000u; spins++) {
        size_t used;
        int rc;
        if (script_pending(&sio) > 0) {
            rc = lep_client_step(c, &sio.in[sio.in_pos], 1, &used);
            sio.in_pos += used;
        } else {
            if (max_ms == 0) {
                return LEP_STEP_NONE;
            }
            max_ms--;
            sio.now += 1;
            rc = lep_client_step(c, NULL, 0, &used);
        }
        if (rc != LEP_STEP_NONE) {
            return rc;
        }
    }
    return LEP_STEP_NONE;
}

/* A recovery's stop refused with 0x04, even a resent copy: the recovery goes
 * on to its drain (a refusal is an answer like any other), and nothing is
 * taken as a confirmed resend. */
static void test_recovery_stop_refused_after_a_resend_goes_on(void)
{
    static const uint8_t refused[] = { 0x04, 0xFF, 0x33, 0x04 };
    uint8_t frame[16];
    size_t n;
    size_t used;
    lep_response r;
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_frame_encode(refused, sizeof(refused), frame, sizeof(frame), &n));
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_recover(&client, 10));
    sio.now += LEP_CLIENT_DEFAULT_TIMEOUT_MS;
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used)); /* resent */
    TEST_ASSERT_EQUAL_UINT(2, sio.writes);
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, frame, n, &used));
    TEST_ASSERT_EQUAL_size_t(n, used);
    TEST_ASSERT_TRUE(lep_client_busy(&client)); /* draining */
    TEST_ASSERT_EQUAL_HEX8(LEP_RESULT_STATE, lep_client_last_result(&client));
    TEST_ASSERT_EQUAL_UINT32(0, stats().resent_confirmed);
    TEST_ASSERT_EQUAL_UINT32(1, stats().resent_after_timeout);
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_response(&client, &r));
    sio.silent = false;
    sio.now += 10u;
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used)); /* identify */
    TEST_ASSERT_EQUAL_UINT(3, sio.writes);
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, pump(&client, 0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_response(&client, &r));
    TEST_ASSERT_EQUAL_HEX8(LEP_CMD_PRODUCT_INFO, r.code);
    TEST_ASSERT_EQUAL_UINT32(0, stats().resent_confirmed);
    TEST_ASSERT_EQUAL_UINT32(0, stats().timeouts);
}

static void test_step_recovery_stops_drains_and_identifies(void)
{
    static const uint8_t start_cmd[] = { 0x10, 0x02, 0x04, 0xFF, 0x32, 0x00, 0x10, 0x03, 0xCA };
    lep_io io = script_io_table(&sio);
    lep_client c;
    lep_response r;
    io.read = NULL;
    sio.endless_stream = false;
    leave_stream_running();
    script_push_data(&sio);
    script_push(&sio, start_cmd, 4); /* half a frame */
    sio.inflight = 3;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(&c, &io));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_recover(&c, 10));
    TEST_ASSERT_TRUE(lep_client_busy(&c));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, pump(&c, 1000));
    TEST_ASSERT_FALSE(lep_client_busy(&c));
    TEST_ASSERT_FALSE(lep_client_streaming(&c));
    TEST_ASSERT_FALSE(lep_device_streaming(&sio.dev));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_response(&c, &r));
    TEST_ASSERT_EQUAL_HEX8(LEP_CMD_PRODUCT_INFO, r.code);
    TEST_ASSERT_EQUAL_STRING("PFS055YA501U6", r.u.info.model);
    TEST_ASSERT_EQUAL_UINT(0, sio.reads);
    TEST_ASSERT_EQUAL_UINT(2, sio.writes); /* stop, identify */
}

static void test_step_recovery_waits_for_a_quiet_line(void)
{
    lep_io io = script_io_table(&sio);
    lep_client c;
    uint32_t t0;
    unsigned i;
    io.read = NULL;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(&c, &io));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_recover(&c, 20));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, pump(&c, 0)); /* the stop's answer */
    t0 = sio.now;
    /* Noise every 10 ms for 100 ms: the drain keeps waiting. */
    for (i = 0; i < 10; i++) {
        static const uint8_t junk[3] = { 0x55, 0x55, 0x55 };
        script_push(&sio, junk, sizeof(junk));
        TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, pump(&c, 10));
    }
    TEST_ASSERT_EQUAL_UINT(1, sio.writes);
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, pump(&c, 100));
    TEST_ASSERT_TRUE(sio.now - t0 >= 90u + 20u); /* 20 ms after the last noise */
    TEST_ASSERT_EQUAL_UINT(2, sio.writes);
}

static void test_step_recovery_gives_up_on_endless_noise(void)
{
    lep_io io = script_io_table(&sio);
    lep_client c;
    size_t used;
    unsigned i;
    int rc = LEP_STEP_NONE;
    static const uint8_t junk[1] = { 0x55 };
    io.read = NULL;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(&c, &io));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_recover(&c, 0));
    for (i = 0; i < 100000u && rc == LEP_STEP_NONE; i++) {
        sio.now += 1;
        rc = lep_client_step(&c, junk, 1, &used);
    }
    TEST_ASSERT_EQUAL_INT(LEP_E_NO_SYNC, rc);
    /* The stop's 4 attempts, then 20 timeouts + the quiet time. */
    TEST_ASSERT_TRUE(sio.now <= 4u * LEP_CLIENT_DEFAULT_TIMEOUT_MS +
                                    20u * LEP_CLIENT_DEFAULT_TIMEOUT_MS +
                                    LEP_CLIENT_DEFAULT_QUIET_MS + 1u);
    TEST_ASSERT_FALSE(lep_client_busy(&c));
}

static void test_step_start_recovered_byte_by_byte(void)
{
    /* A start refused (a stale stream runs), recovered by stop, drain, start,
     * every byte stepped alone: the clock is looked at on each one meanwhile. */
    lep_io io = script_io_table(&sio);
    lep_command start = { LEP_CMD_START, 0 };
    lep_client c;
    lep_client_stats st;
    io.read = NULL;
    sio.endless_stream = false;
    leave_stream_running();
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(&c, &io));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&c, &start));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, pump(&c, 1000));
    TEST_ASSERT_TRUE(lep_client_streaming(&c));
    TEST_ASSERT_EQUAL_UINT(3, sio.writes); /* start, stop, start */
    lep_client_get_stats(&c, &st);
    TEST_ASSERT_EQUAL_UINT32(1, st.recoveries);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_response(&c, &(lep_response){ 0 }));
}

static void test_recover_write_error(void)
{
    sio.write_error = LEP_E_DISCONNECTED;
    TEST_ASSERT_EQUAL_INT(LEP_E_DISCONNECTED, lep_client_recover(&client, 0));
    TEST_ASSERT_FALSE(lep_client_busy(&client));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_recover(NULL, 0));
}

static void test_watchdog_reports_a_stalled_stream(void)
{
    lep_io io = script_io_table(&sio);
    lep_client c;
    lep_command start = { LEP_CMD_START, 0 };
    unsigned i;
    io.read = NULL;
    sio.endless_stream = false;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(&c, &io));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_watchdog(&c, 50));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&c, &start));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, pump(&c, 0));
    /* Samples every 10 ms keep it quiet. */
    for (i = 0; i < 20; i++) {
        script_push_data(&sio);
        TEST_ASSERT_EQUAL_INT(LEP_STEP_SAMPLE, pump(&c, 0));
        TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, pump(&c, 10));
    }
    /* Then nothing: LEP_E_STALLED once per 50 ms of silence. */
    TEST_ASSERT_EQUAL_INT(LEP_E_STALLED, pump(&c, 100));
    TEST_ASSERT_EQUAL_INT(LEP_E_STALLED, pump(&c, 100));
    TEST_ASSERT_TRUE(lep_client_streaming(&c));
    script_push_data(&sio);
    TEST_ASSERT_EQUAL_INT(LEP_STEP_SAMPLE, pump(&c, 0));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, pump(&c, 45));
    {
        lep_client_stats st;
        lep_client_get_stats(&c, &st);
        TEST_ASSERT_EQUAL_UINT32(2, st.stalls);
        TEST_ASSERT_EQUAL_UINT32(21, st.samples);
    }
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_watchdog(&c, 0));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, pump(&c, 1000));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_set_watchdog(NULL, 5));
}

static void test_watchdog_in_blocking_next_sample(void)
{
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_watchdog(&client, 30));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, 100));
    sio.endless_stream = false;
    TEST_ASSERT_EQUAL_INT(LEP_E_STALLED, lep_client_next_sample(&client, &s, 1000));
    TEST_ASSERT_TRUE(sio.now <= 1u + 30u + 2u);
    TEST_ASSERT_EQUAL_UINT32(1, stats().stalls);
    TEST_ASSERT_EQUAL_STRING(TEXT("no stream data within the watchdog time"),
                             lep_strerror(LEP_E_STALLED));
}

static void test_watchdog_checked_every_32_single_bytes(void)
{
    lep_command start = { LEP_CMD_START, 0 };
    static const uint8_t junk[1] = { 0x55 };
    size_t used;
    unsigned i;
    int rc = LEP_STEP_NONE;
    sio.endless_stream = false;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_watchdog(&client, 10));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &start));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_RESPONSE, pump(&client, 0));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
    sio.now += 100;
    for (i = 0; i < 40 && rc == LEP_STEP_NONE; i++) {
        rc = lep_client_step(&client, junk, 1, &used);
    }
    TEST_ASSERT_EQUAL_INT(LEP_E_STALLED, rc);
    TEST_ASSERT_TRUE(i <= 32u);
}

/* Found by fuzz_client: a watchdog stall while a blocking query waits used
 * to end the query with LEP_E_STALLED and leave the transaction pending. */
static void test_watchdog_stall_does_not_end_a_blocking_query(void)
{
    lep_rated rated;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_watchdog(&client, 4));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    sio.lose_answers = 1; /* the query waits one timeout: the watchdog expires meanwhile */
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_FALSE(lep_client_busy(&client));
    TEST_ASSERT_TRUE(stats().stalls >= 1u);
    TEST_ASSERT_EQUAL_FLOAT(500.0f, rated.axis[LEP_FX]);
}

/* ---- firmware variants and impossible values through the client ---- */

static void test_reserved_byte_variants_are_counted_and_delivered(void)
{
    uint8_t msg[20] = {
        0x14, 0xFF, 0x32, 0x00, 1, 0, 2, 0, 3, 0, 4, 0, 5, 0, 6, 0, 9, 0, 0x00, 0xA5
    };
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    script_push_msg(&sio, msg, sizeof(msg));
    msg[19] = 0;
    script_push_msg(&sio, msg, sizeof(msg));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, 10));
    TEST_ASSERT_EQUAL_INT16(6, s.raw[LEP_MZ]);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, 10));
    TEST_ASSERT_EQUAL_UINT32(1, stats().reserved_nonzero);
    TEST_ASSERT_EQUAL_UINT32(2, stats().samples);
}

static void test_impossible_samples_are_invalid_never_delivered(void)
{
    uint8_t msg[20] = {
        0x14, 0xFF, 0x32, 0x00, 0, 0, 0x01, 0x7D, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0
    };
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    script_push_msg(&sio, msg, sizeof(msg)); /* Fy = 32001 */
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_next_sample(&client, &s, 10));
    TEST_ASSERT_EQUAL_UINT32(1, stats().invalid);
    TEST_ASSERT_EQUAL_UINT32(0, stats().samples);
}

static void test_handshake_reserved_variant_is_counted(void)
{
    uint8_t msg[20] = {
        0x14, 0xFF, 0x30, 0x00, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 7, 0, 0, 0, 0x04, 0x01
    };
    lep_sample s;
    force_reply(msg, sizeof(msg));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sample(&client, &s));
    TEST_ASSERT_EQUAL_INT16(7, s.raw[LEP_MZ]);
    TEST_ASSERT_EQUAL_UINT32(1, stats().reserved_nonzero);
}

/* ---- read buffer ---- */

static void test_blocking_calls_without_a_read_buffer_read_one_byte_at_a_time(void)
{
    lep_sample s[4];
    size_t n;
    lep_product_info info;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_rx(&client, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_product_info(&client, &info));
    TEST_ASSERT_EQUAL_STRING("PFS055YA501U6", info.model);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_samples(&client, s, 4, &n, 100));
    TEST_ASSERT_EQUAL_UINT16(0, s[0].reserved);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_stop(&client));
    TEST_ASSERT_TRUE(sio.reads >= sio.total_read); /* never more than one byte per read */
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_set_rx(NULL, &rx));
}

static void test_response_accessors(void)
{
    lep_response r;
    lep_sample s;
    lep_rated rated;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_response(NULL, &r));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_response(&client, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_get_sample(&client, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_get_sample(NULL, &s));
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_response(&client, &r));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_response(&client, &r));
    TEST_ASSERT_EQUAL_HEX8(LEP_CMD_RATED, r.code);
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_get_sample(&client, &s)); /* not a sample */
}

/* ---- arguments and rare paths ---- */

static void test_null_arguments(void)
{
    lep_io io = script_io_table(&sio);
    lep_client_stats st;
    lep_product_info info;
    lep_rated rated;
    lep_sample smp;
    lep_command cmd = { LEP_CMD_RATED, 0 };
    uint8_t code;
    size_t used;
    size_t n = 5;
    io.write = NULL;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_init(&client, &io));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_init(&client, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_set_timeout(NULL, 10));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_set_retries(NULL, 1));
    lep_client_get_stats(NULL, &st);
    lep_client_get_stats(&client, NULL);
    TEST_ASSERT_EQUAL_UINT8(0, lep_client_last_result(NULL));
    TEST_ASSERT_FALSE(lep_client_streaming(NULL));
    TEST_ASSERT_FALSE(lep_client_busy(NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_send(NULL, &cmd));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_send(&client, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_step(NULL, NULL, 0, &used));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_step(&client, NULL, 0, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_step(&client, NULL, 1, &used));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_step_byte(NULL, 0x41, &smp));
    { /* a single byte is checked the same way */
        const uint8_t one = 0x41;
        TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_step(NULL, &one, 1, &used));
        TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_step(&client, &one, 1, NULL));
    }
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_transact(NULL, &cmd, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_transact(&client, NULL, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_product_info(&client, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_rated(&client, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_filter_get(&client, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_sample(NULL, &smp));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_sample(&client, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_sync(NULL, 10, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_next_sample(NULL, &smp, 0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_next_sample(&client, NULL, 0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_next_samples(&client, &smp, 1, NULL, 0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_next_samples(&client, NULL, 1, &n, 0));
    TEST_ASSERT_EQUAL_size_t(0, n);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_next_samples(&client, &smp, 0, &n, 0));
    TEST_ASSERT_EQUAL_INT(0, sio.writes);
    (void)info;
    (void)rated;
    (void)code;
}

static void test_send_of_an_unknown_command_writes_nothing(void)
{
    lep_command cmd = { 0x40, 0 };
    TEST_ASSERT_EQUAL_INT(LEP_E_UNEXPECTED, lep_client_send(&client, &cmd));
    TEST_ASSERT_FALSE(lep_client_busy(&client));
    TEST_ASSERT_EQUAL_UINT(0, sio.writes);
}

static void test_empty_frame_is_invalid(void)
{
    static const uint8_t empty[] = { 0x10, 0x02, 0x10, 0x03, 0x03 };
    lep_rated rated;
    script_push(&sio, empty, sizeof(empty));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_rated(&client, &rated));
    TEST_ASSERT_EQUAL_UINT32(1, stats().invalid);
}

static void test_nak_without_a_transaction_is_ignored(void)
{
    static const uint8_t nak[2] = { LEP_DLE, LEP_NAK };
    size_t used;
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, nak, sizeof(nak), &used));
    TEST_ASSERT_EQUAL_UINT32(1, stats().naks);
    TEST_ASSERT_EQUAL_UINT(0, sio.writes);
}

static void test_get_sample_needs_a_sample(void)
{
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_get_sample(&client, &s)); /* nothing yet */
    sio.lose_answers = 1;
    sio.endless_stream = false;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client)); /* confirmed by a 0x04 answer */
    TEST_ASSERT_EQUAL_INT(LEP_E_STATE, lep_client_get_sample(&client, &s));
}

static void test_sync_clamps_the_quiet_time_and_reports_write_errors(void)
{
    lep_product_info info;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 100000, &info));
    TEST_ASSERT_EQUAL_UINT32(0xFFFFu, sio.now); /* quiet for 65535 ms at most */
    sio.write_error = LEP_E_IO;
    TEST_ASSERT_EQUAL_INT(LEP_E_IO, lep_client_sync(&client, 10, &info));
}

static void test_messages_and_naks_during_a_start_recovery_drain(void)
{
    static const uint8_t refused[] = { 0x04, 0xFF, 0x32, 0x04 };
    static const uint8_t stop_ack[] = { 0x04, 0xFF, 0x33, 0x00 };
    static const uint8_t nak[2] = { LEP_DLE, LEP_NAK };
    lep_command start = { LEP_CMD_START, 0 };
    uint8_t frame[16];
    size_t n;
    size_t used;
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &start));
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_frame_encode(refused, sizeof(refused), frame, sizeof(frame), &n));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, frame, n, &used)); /* stop sent */
    TEST_ASSERT_EQUAL_INT(LEP_OK,
                          lep_frame_encode(stop_ack, sizeof(stop_ack), frame, sizeof(frame), &n));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, frame, n, &used)); /* draining */
    /* A late duplicate answer and a NAK while draining: neither ends nor resends anything. */
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, frame, n, &used));
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, nak, sizeof(nak), &used));
    TEST_ASSERT_EQUAL_UINT(2, sio.writes);
    TEST_ASSERT_EQUAL_UINT32(1, stats().unexpected);
    sio.now += LEP_CLIENT_DEFAULT_QUIET_MS;
    TEST_ASSERT_EQUAL_INT(LEP_STEP_NONE, lep_client_step(&client, NULL, 0, &used));
    TEST_ASSERT_EQUAL_UINT(3, sio.writes); /* started again */
}

static void test_blocking_sync_drain_limit_after_a_clock_jump(void)
{
    /* A stale stream that never stops, and the clock jumps forward mid-drain. */
    leave_stream_running();
    sio.silent = true;
    sio.max_chunk = 1;
    TEST_ASSERT_EQUAL_INT(LEP_E_NO_SYNC, lep_client_sync(&client, 30, NULL));
}

static void test_next_sample_takes_a_step_api_answer_in_stride(void)
{
    lep_command rated = { LEP_CMD_RATED, 0 };
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_send(&client, &rated)); /* answered at once */
    script_push_data(&sio);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_next_sample(&client, &s, 50));
    TEST_ASSERT_FALSE(lep_client_busy(&client));
}

static void test_blocking_waits_bounded_by_the_watchdog(void)
{
    lep_sample s;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_watchdog(&client, 40));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    sio.endless_stream = false;
    /* Forever, and a longer timeout than the watchdog: both end at the stall. */
    TEST_ASSERT_EQUAL_INT(LEP_E_STALLED, lep_client_next_sample(&client, &s, -1));
    TEST_ASSERT_EQUAL_INT(40, sio.last_timeout);
    TEST_ASSERT_EQUAL_INT(LEP_E_STALLED, lep_client_next_sample(&client, &s, 500));
    /* A shorter timeout than the watchdog: the timeout. */
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_next_sample(&client, &s, 10));
    TEST_ASSERT_EQUAL_INT(10, sio.last_timeout);
}

/* A clock that moves between any two readings (a loaded machine): every
 * deadline may already be over when the blocking calls compute their waits. */
static void test_blocking_calls_with_a_clock_that_never_stands_still(void)
{
    lep_product_info info;
    lep_rated rated;
    lep_sample s;
    unsigned i;
    leave_stream_running();
    sio.tick = 7;
    sio.max_chunk = 3;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_timeout(&client, 200));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 5, &info));
    TEST_ASSERT_EQUAL_STRING("12345678", info.serial);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_set_watchdog(&client, 9));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_start(&client));
    for (i = 0; i < 5; i++) {
        int rc = lep_client_next_sample(&client, &s, 100);
        TEST_ASSERT_TRUE(rc == LEP_OK || rc == LEP_E_STALLED);
    }
    sio.endless_stream = false;
    TEST_ASSERT_EQUAL_INT(LEP_E_STALLED, lep_client_next_sample(&client, &s, 1000));
    sio.silent = true;
    TEST_ASSERT_EQUAL_INT(LEP_E_TIMEOUT, lep_client_rated(&client, &rated));
    sio.silent = false;
    sio.noise = true;
    TEST_ASSERT_EQUAL_INT(LEP_E_NO_SYNC, lep_client_sync(&client, 30, &info));
}

static void test_blocking_calls_need_a_read_function(void)
{
    lep_io io = script_io_table(&sio);
    lep_client c;
    lep_sample s;
    io.read = NULL;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_init(&c, &io));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_next_sample(&c, &s, 0));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_client_sync(&c, 0, NULL));
}

static void test_sync_default_quiet_time(void)
{
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, 0, NULL));
    TEST_ASSERT_EQUAL_UINT32(LEP_CLIENT_DEFAULT_QUIET_MS, sio.now);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_client_sync(&client, -5, NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_rejects_incomplete_io);
    RUN_TEST(test_init_zeroes_like_decoder_init);
    RUN_TEST(test_product_info_and_rated);
    RUN_TEST(test_transact_gives_the_whole_response);
    RUN_TEST(test_handshake_sample);
    RUN_TEST(test_filter_set_needs_power_cycle);
    RUN_TEST(test_filter_set_rejects_bad_code_without_writing);
    RUN_TEST(test_nak_then_success);
    RUN_TEST(test_nak_past_the_limit);
    RUN_TEST(test_no_retries_when_disabled);
    RUN_TEST(test_timeout);
    RUN_TEST(test_wrong_response_type_is_skipped);
    RUN_TEST(test_only_wrong_type_is_resent);
    RUN_TEST(test_sensor_error_codes);
    RUN_TEST(test_invalid_answer_is_counted_not_taken);
    RUN_TEST(test_corrupt_answer_is_counted);
    RUN_TEST(test_stale_stream_does_not_answer_queries);
    RUN_TEST(test_sync_recovers_stale_stream);
    RUN_TEST(test_sync_on_a_silent_line_times_out);
    RUN_TEST(test_sync_gives_up_on_endless_noise);
    RUN_TEST(test_late_answer_is_skipped_by_the_next_query);
    RUN_TEST(test_timeout_applies_to_each_attempt);
    RUN_TEST(test_stream_start_next_stop);
    RUN_TEST(test_start_while_streaming_is_a_state_error);
    RUN_TEST(test_start_refused_by_a_stale_stream_recovers_once);
    RUN_TEST(test_start_refused_twice_is_a_sensor_error);
    RUN_TEST(test_next_samples_batches_buffered_data);
    RUN_TEST(test_next_sample_timeout_when_stream_stalls);
    RUN_TEST(test_byte_by_byte_reads);
    RUN_TEST(test_io_errors_propagate);
    RUN_TEST(test_samples_after_a_failed_stop);
    RUN_TEST(test_step_api_without_read);
    RUN_TEST(test_step_api_deadline);
    RUN_TEST(test_step_api_stops_at_each_sample);
    RUN_TEST(test_step_byte_gives_what_step_gives_at_every_chunking);
    RUN_TEST(test_step_byte_message_lasts_until_the_next_step);
    RUN_TEST(test_step_byte_reads_the_clock_every_32_bytes);
    RUN_TEST(test_two_clients_are_independent);
    RUN_TEST(test_transaction_timeout_across_clock_wrap);
    RUN_TEST(test_nak_retry_and_answer_across_clock_wrap);
    RUN_TEST(test_next_sample_timeout_across_clock_wrap);
    RUN_TEST(test_step_api_deadline_across_clock_wrap);
    RUN_TEST(test_sync_across_clock_wrap);
    RUN_TEST(test_next_sample_negative_timeout_waits_forever);
    RUN_TEST(test_next_sample_times_out_on_endless_noise);
    RUN_TEST(test_next_sample_zero_timeout_reads_once_on_endless_noise);
    RUN_TEST(test_next_samples_returns_on_endless_noise);
    RUN_TEST(test_transaction_times_out_on_endless_noise);
    RUN_TEST(test_samples_skipped_by_a_query_are_not_counted_as_delivered);
    RUN_TEST(test_sync_accounts_for_every_stale_byte);
    RUN_TEST(test_read_claiming_more_than_asked_is_an_io_error);
    RUN_TEST(test_stop_with_data_in_flight_in_small_reads);
    RUN_TEST(test_step_api_from_a_ring_buffer);
    RUN_TEST(test_lost_answer_is_resent);
    RUN_TEST(test_lost_command_is_resent);
    RUN_TEST(test_naks_and_timeouts_share_one_budget);
    RUN_TEST(test_resent_start_answered_state_error_counts_as_started);
    RUN_TEST(test_resent_start_with_data_flowing_counts_as_started);
    RUN_TEST(test_data_before_the_first_start_answer_is_not_taken_as_started);
    RUN_TEST(test_resent_stop_answered_state_error_counts_as_stopped);
    RUN_TEST(test_recovery_stop_refused_after_a_resend_goes_on);
    RUN_TEST(test_step_recovery_stops_drains_and_identifies);
    RUN_TEST(test_step_recovery_waits_for_a_quiet_line);
    RUN_TEST(test_step_recovery_gives_up_on_endless_noise);
    RUN_TEST(test_step_start_recovered_byte_by_byte);
    RUN_TEST(test_recover_write_error);
    RUN_TEST(test_watchdog_reports_a_stalled_stream);
    RUN_TEST(test_watchdog_in_blocking_next_sample);
    RUN_TEST(test_watchdog_checked_every_32_single_bytes);
    RUN_TEST(test_watchdog_stall_does_not_end_a_blocking_query);
    RUN_TEST(test_reserved_byte_variants_are_counted_and_delivered);
    RUN_TEST(test_impossible_samples_are_invalid_never_delivered);
    RUN_TEST(test_handshake_reserved_variant_is_counted);
    RUN_TEST(test_blocking_calls_without_a_read_buffer_read_one_byte_at_a_time);
    RUN_TEST(test_response_accessors);
    RUN_TEST(test_null_arguments);
    RUN_TEST(test_send_of_an_unknown_command_writes_nothing);
    RUN_TEST(test_empty_frame_is_invalid);
    RUN_TEST(test_nak_without_a_transaction_is_ignored);
    RUN_TEST(test_get_sample_needs_a_sample);
    RUN_TEST(test_sync_clamps_the_quiet_time_and_reports_write_errors);
    RUN_TEST(test_messages_and_naks_during_a_start_recovery_drain);
    RUN_TEST(test_blocking_sync_drain_limit_after_a_clock_jump);
    RUN_TEST(test_next_sample_takes_a_step_api_answer_in_stride);
    RUN_TEST(test_blocking_waits_bounded_by_the_watchdog);
    RUN_TEST(test_blocking_calls_with_a_clock_that_never_stands_still);
    RUN_TEST(test_blocking_calls_need_a_read_function);
    RUN_TEST(test_sync_default_quiet_time);
    return UNITY_END();
}
