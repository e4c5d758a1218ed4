/* Message codec tests driven by test/vectors/messages.json: commands and
 * responses in both directions (host and sensor side), validation errors with
 * the result code a sensor answers, SI conversion, saturation, status bits and
 * the static strings. */
#include <stdio.h>
#include <string.h>

#include "hex.h"
#include "json.h"
#include "leptrino/error.h"
#include "leptrino/frame.h"
#include "leptrino/message.h"
#include "unity.h"
#include "vectors.h"

static lep_json *g_vectors;

void setUp(void)
{
}

void tearDown(void)
{
}

/* ---- helpers --------------------------------------------------------------- */

static uint8_t get_u8(const lep_json *v, const char *key)
{
    long n = lep_json_get_int(v, key, -1);
    TEST_ASSERT_TRUE_MESSAGE(n >= 0 && n <= 255, key);
    return (uint8_t)n;
}

static void copy_text(char *dst, size_t cap, const lep_json *obj, const char *key)
{
    const char *s = lep_json_get_str(obj, key);
    TEST_ASSERT_NOT_NULL_MESSAGE(s, key);
    TEST_ASSERT_LESS_THAN_size_t_MESSAGE(cap, strlen(s), key);
    memcpy(dst, s, strlen(s) + 1u);
}

/* The fields of a response vector as a lep_response (what a sensor encodes). */
static void response_of(const lep_json *v, lep_response *r)
{
    const lep_json *info = lep_json_get(v, "info");
    const lep_json *rated = lep_json_get(v, "rated");
    const lep_json *sample = lep_json_get(v, "sample");
    size_t i;
    memset(r, 0, sizeof(*r));
    r->code = get_u8(v, "code");
    r->result = get_u8(v, "result");
    r->stream = lep_json_get_bool(v, "stream", false);
    if (info != NULL) {
        copy_text(r->u.info.model, sizeof(r->u.info.model), info, "model");
        copy_text(r->u.info.serial, sizeof(r->u.info.serial), info, "serial");
        copy_text(r->u.info.firmware, sizeof(r->u.info.firmware), info, "firmware");
        copy_text(r->u.info.output_rate, sizeof(r->u.info.output_rate), info, "output_rate");
        r->u.info.has_output_rate = lep_json_get_bool(info, "has_output_rate", false);
        r->u.info.output_rate_hz = (uint32_t)lep_json_get_int(info, "output_rate_hz", 0);
    } else if (rated != NULL) {
        TEST_ASSERT_EQUAL_size_t(LEP_AXES, lep_json_len(rated));
        for (i = 0; i < LEP_AXES; i++) {
            r->u.rated.axis[i] = (float)lep_json_num(lep_json_at(rated, i));
        }
    } else if (lep_json_has(v, "filter")) {
        r->u.filter = get_u8(v, "filter");
    } else if (sample != NULL) {
        const lep_json *raw = lep_json_get(sample, "raw");
        TEST_ASSERT_EQUAL_size_t(LEP_AXES, lep_json_len(raw));
        for (i = 0; i < LEP_AXES; i++) {
            r->u.sample.raw[i] = (int16_t)lep_json_num(lep_json_at(raw, i));
        }
        r->u.sample.reserved = (uint16_t)lep_json_get_int(sample, "reserved", 0);
        r->u.sample.status = get_u8(sample, "status");
    }
}

/* ---- commands ---------------------------------------------------------------- */

static void test_command_vectors_encode_and_decode(void)
{
    const lep_json *cmds = lep_vectors_section(g_vectors, "commands");
    size_t i;
    for (i = 0; i < lep_json_len(cmds); i++) {
        const lep_json *v = lep_json_at(cmds, i);
        const char *name = lep_json_get_str(v, "name");
        uint8_t want[LEP_MAX_MESSAGE];
        uint8_t out[LEP_MAX_MESSAGE];
        uint8_t wire[LEP_MAX_FRAME];
        uint8_t wire2[LEP_MAX_FRAME];
        size_t wlen = lep_vectors_hex(lep_json_get_str(v, "message"), want, sizeof(want));
        size_t n = 0;
        size_t fn = 0;
        size_t fn2 = 0;
        uint8_t result = 0xEE;
        lep_command cmd;
        lep_command got;
        cmd.code = get_u8(v, "code");
        cmd.filter = lep_json_has(v, "filter") ? get_u8(v, "filter") : 0u;

        /* Host side: encode. */
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_command_encode(&cmd, out, sizeof(out), &n),
                                      lep_vectors_ctx(name, "encode"));
        TEST_ASSERT_EQUAL_size_t_MESSAGE(wlen, n, lep_vectors_ctx(name, "encoded length"));
        TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(want, out, wlen,
                                             lep_vectors_ctx(name, "encoded bytes"));
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_command_encode(&cmd, out, wlen, &n),
                                      lep_vectors_ctx(name, "exact capacity"));
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_E_BUFFER, lep_command_encode(&cmd, out, wlen - 1u, &n),
                                      lep_vectors_ctx(name, "capacity one short"));

        /* Straight to a frame: the same as framing the message. */
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_command_frame(&cmd, wire, sizeof(wire), &fn));
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_encode(want, wlen, wire2, sizeof(wire2), &fn2));
        TEST_ASSERT_EQUAL_size_t_MESSAGE(fn2, fn, lep_vectors_ctx(name, "frame size"));
        TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(wire2, wire, fn2,
                                             lep_vectors_ctx(name, "frame bytes"));
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_E_BUFFER, lep_command_frame(&cmd, wire, fn2 - 1u, &fn),
                                      lep_vectors_ctx(name, "frame capacity one short"));

        /* Sensor side: decode. */
        memset(&got, 0xA5, sizeof(got));
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_command_decode(want, wlen, &got, &result),
                                      lep_vectors_ctx(name, "decode"));
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(LEP_RESULT_OK, result,
                                       lep_vectors_ctx(name, "decode result"));
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(cmd.code, got.code, lep_vectors_ctx(name, "decoded code"));
        if (cmd.code == LEP_CMD_FILTER_SET) {
            TEST_ASSERT_EQUAL_UINT8_MESSAGE(cmd.filter, got.filter,
                                            lep_vectors_ctx(name, "decoded filter"));
        }
    }
}

static void test_invalid_command_vectors(void)
{
    const lep_json *bad = lep_vectors_section(g_vectors, "invalid_commands");
    size_t i;
    for (i = 0; i < lep_json_len(bad); i++) {
        const lep_json *v = lep_json_at(bad, i);
        const char *name = lep_json_get_str(v, "name");
        uint8_t msg[LEP_MAX_MESSAGE];
        size_t len = lep_vectors_hex(lep_json_get_str(v, "message"), msg, sizeof(msg));
        uint8_t result = 0xEE;
        lep_command cmd;
        memset(&cmd, 0xA5, sizeof(cmd));
        TEST_ASSERT_EQUAL_INT_MESSAGE(lep_vectors_error(lep_json_get_str(v, "error")),
                                      lep_command_decode(msg, len, &cmd, &result),
                                      lep_vectors_ctx(name, "error"));
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(get_u8(v, "result"), result,
                                       lep_vectors_ctx(name, "result to answer"));
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(get_u8(v, "code"), cmd.code,
                                       lep_vectors_ctx(name, "reported code"));
    }
}

static void test_command_encode_error_vectors(void)
{
    const lep_json *errs = lep_vectors_section(g_vectors, "command_encode_errors");
    size_t i;
    for (i = 0; i < lep_json_len(errs); i++) {
        const lep_json *v = lep_json_at(errs, i);
        uint8_t out[LEP_MAX_MESSAGE];
        uint8_t wire[LEP_MAX_FRAME];
        size_t n = 99;
        lep_command cmd;
        cmd.code = get_u8(v, "code");
        cmd.filter = lep_json_has(v, "filter") ? get_u8(v, "filter") : 0u;
        TEST_ASSERT_EQUAL_INT_MESSAGE(lep_vectors_error(lep_json_get_str(v, "error")),
                                      lep_command_encode(&cmd, out, sizeof(out), &n),
                                      lep_vectors_ctx(lep_json_get_str(v, "name"), "encode"));
        TEST_ASSERT_EQUAL_INT_MESSAGE(lep_vectors_error(lep_json_get_str(v, "error")),
                                      lep_command_frame(&cmd, wire, sizeof(wire), &n),
                                      lep_vectors_ctx(lep_json_get_str(v, "name"), "frame"));
    }
}

static void test_command_null_arguments(void)
{
    lep_command cmd = { LEP_CMD_STOP, 0 };
    uint8_t out[16];
    uint8_t result = 0;
    size_t n;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_encode(NULL, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_encode(&cmd, NULL, sizeof(out), &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_encode(&cmd, out, sizeof(out), NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_decode(NULL, 4, &cmd, &result));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_decode(out, 4, NULL, &result));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_decode(out, 4, &cmd, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_frame(&cmd, out, sizeof(out), NULL));
}

/* Every code and filter value: lep_command_frame gives exactly what framing
 * lep_command_encode's message gives (no byte of a command is stuffed), the
 * two agree on every error, and *len is 0 on each failure. */
static void test_command_frame_every_code_and_filter(void)
{
    unsigned code;
    unsigned filter;
    for (code = 0; code < 256u; code++) {
        for (filter = 0; filter < 256u; filter++) {
            lep_command cmd;
            uint8_t msg[LEP_LEN_FILTER_SET_CMD];
            uint8_t want[LEP_MAX_FRAME];
            uint8_t got[LEP_MAX_FRAME];
            size_t n = 99;
            size_t wn = 0;
            size_t gn = 99;
            size_t i;
            int rc;
            cmd.code = (uint8_t)code;
            cmd.filter = (uint8_t)filter;
            rc = lep_command_encode(&cmd, msg, sizeof(msg), &n);
            TEST_ASSERT_EQUAL_INT(rc, lep_command_frame(&cmd, got, sizeof(got), &gn));
            if (rc != LEP_OK) {
                TEST_ASSERT_EQUAL_size_t(0, n);
                TEST_ASSERT_EQUAL_size_t(0, gn);
                continue;
            }
            for (i = 0; i < n; i++) {
                TEST_ASSERT_NOT_EQUAL(LEP_DLE, msg[i]);
            }
            TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_encode(msg, n, want, sizeof(want), &wn));
            TEST_ASSERT_EQUAL_size_t(n + 5u, wn);
            TEST_ASSERT_EQUAL_size_t(wn, gn);
            TEST_ASSERT_EQUAL_HEX8_ARRAY(want, got, wn);
            /* exact capacity, one short */
            TEST_ASSERT_EQUAL_INT(LEP_OK, lep_command_frame(&cmd, got, wn, &gn));
            TEST_ASSERT_EQUAL_INT(LEP_E_BUFFER, lep_command_frame(&cmd, got, wn - 1u, &gn));
            TEST_ASSERT_EQUAL_size_t(0, gn);
        }
    }
}

/* A missing argument is LEP_E_ARG before any check of the command (the order
 * LEP_E_ARG, _UNEXPECTED, _VALUE, _BUFFER), with *len 0 where there is one. */
static void test_command_arguments_checked_first(void)
{
    lep_command unknown = { 0x40, 0 };
    lep_command bad_filter = { LEP_CMD_FILTER_SET, 9 };
    uint8_t out[16];
    size_t n = 99;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_frame(&unknown, NULL, sizeof(out), &n));
    TEST_ASSERT_EQUAL_size_t(0, n);
    n = 99;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_frame(&bad_filter, NULL, sizeof(out), &n));
    TEST_ASSERT_EQUAL_size_t(0, n);
    n = 99;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_frame(NULL, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_size_t(0, n);
    n = 99;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_command_encode(&unknown, NULL, sizeof(out), &n));
    TEST_ASSERT_EQUAL_size_t(0, n);
    TEST_ASSERT_EQUAL_INT(LEP_E_UNEXPECTED, lep_command_encode(&unknown, out, 0, &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_command_encode(&bad_filter, out, 0, &n));
}

/* ---- responses --------------------------------------------------------------- */

static void expect_fields(const lep_response *want, const lep_response *got, const char *name)
{
    size_t i;
    TEST_ASSERT_EQUAL_HEX8_MESSAGE(want->code, got->code, lep_vectors_ctx(name, "code"));
    TEST_ASSERT_EQUAL_HEX8_MESSAGE(want->result, got->result, lep_vectors_ctx(name, "result"));
    TEST_ASSERT_EQUAL_INT_MESSAGE(want->stream, got->stream, lep_vectors_ctx(name, "stream"));
    if (want->result != LEP_RESULT_OK) {
        return;
    }
    switch (want->code) {
    case LEP_CMD_PRODUCT_INFO:
        TEST_ASSERT_EQUAL_STRING_MESSAGE(want->u.info.model, got->u.info.model,
                                         lep_vectors_ctx(name, "model"));
        TEST_ASSERT_EQUAL_STRING_MESSAGE(want->u.info.serial, got->u.info.serial,
                                         lep_vectors_ctx(name, "serial"));
        TEST_ASSERT_EQUAL_STRING_MESSAGE(want->u.info.firmware, got->u.info.firmware,
                                         lep_vectors_ctx(name, "firmware"));
        TEST_ASSERT_EQUAL_STRING_MESSAGE(want->u.info.output_rate, got->u.info.output_rate,
                                         lep_vectors_ctx(name, "output_rate"));
        TEST_ASSERT_EQUAL_INT_MESSAGE(want->u.info.has_output_rate, got->u.info.has_output_rate,
                                      lep_vectors_ctx(name, "has_output_rate"));
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(want->u.info.output_rate_hz, got->u.info.output_rate_hz,
                                         lep_vectors_ctx(name, "output_rate_hz"));
        break;
    case LEP_CMD_RATED:
        for (i = 0; i < LEP_AXES; i++) {
            /* Exact: the vectors hold float32 values. */
            TEST_ASSERT_TRUE_MESSAGE(want->u.rated.axis[i] == got->u.rated.axis[i],
                                     lep_vectors_ctx(name, "rated"));
        }
        break;
    case LEP_CMD_FILTER_GET:
        TEST_ASSERT_EQUAL_UINT8_MESSAGE(want->u.filter, got->u.filter,
                                        lep_vectors_ctx(name, "filter"));
        break;
    case LEP_CMD_SAMPLE:
    case LEP_CMD_START:
        if (want->code == LEP_CMD_SAMPLE || want->stream) {
            TEST_ASSERT_EQUAL_INT16_ARRAY_MESSAGE(want->u.sample.raw, got->u.sample.raw, LEP_AXES,
                                                  lep_vectors_ctx(name, "raw"));
            TEST_ASSERT_EQUAL_HEX16_MESSAGE(want->u.sample.reserved, got->u.sample.reserved,
                                            lep_vectors_ctx(name, "reserved"));
            TEST_ASSERT_EQUAL_HEX8_MESSAGE(want->u.sample.status, got->u.sample.status,
                                           lep_vectors_ctx(name, "status"));
        }
        break;
    default:
        break;
    }
}

static void test_response_vectors_decode(void)
{
    const lep_json *rs = lep_vectors_section(g_vectors, "responses");
    size_t i;
    for (i = 0; i < lep_json_len(rs); i++) {
        const lep_json *v = lep_json_at(rs, i);
        const char *name = lep_json_get_str(v, "name");
        const char *err = lep_json_get_str(v, "error");
        uint8_t msg[LEP_MAX_MESSAGE];
        size_t len = lep_vectors_hex(lep_json_get_str(v, "message"), msg, sizeof(msg));
        lep_response want;
        lep_response got;
        response_of(v, &want);
        memset(&got, 0xA5, sizeof(got));
        TEST_ASSERT_EQUAL_INT_MESSAGE(err != NULL ? lep_vectors_error(err) : LEP_OK,
                                      lep_response_decode(msg, len, &got),
                                      lep_vectors_ctx(name, "decode"));
        expect_fields(&want, &got, name);
    }
}

static void test_response_vectors_encode(void)
{
    const lep_json *rs = lep_vectors_section(g_vectors, "responses");
    size_t i;
    for (i = 0; i < lep_json_len(rs); i++) {
        const lep_json *v = lep_json_at(rs, i);
        const char *name = lep_json_get_str(v, "name");
        uint8_t want[LEP_MAX_MESSAGE];
        uint8_t out[LEP_MAX_MESSAGE];
        uint8_t wire[LEP_MAX_FRAME];
        uint8_t wire2[LEP_MAX_FRAME];
        size_t wlen = lep_vectors_hex(lep_json_get_str(v, "message"), want, sizeof(want));
        size_t n = 0;
        size_t fn = 0;
        size_t fn2 = 0;
        lep_response r;
        response_of(v, &r);
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_response_encode(&r, out, sizeof(out), &n),
                                      lep_vectors_ctx(name, "encode"));
        TEST_ASSERT_EQUAL_size_t_MESSAGE(wlen, n, lep_vectors_ctx(name, "encoded length"));
        TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(want, out, wlen,
                                             lep_vectors_ctx(name, "encoded bytes"));
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_response_encode(&r, out, wlen, &n),
                                      lep_vectors_ctx(name, "exact capacity"));
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_E_BUFFER, lep_response_encode(&r, out, wlen - 1u, &n),
                                      lep_vectors_ctx(name, "capacity one short"));
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_response_frame(&r, wire, sizeof(wire), &fn));
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_frame_encode(want, wlen, wire2, sizeof(wire2), &fn2));
        TEST_ASSERT_EQUAL_size_t_MESSAGE(fn2, fn, lep_vectors_ctx(name, "frame size"));
        TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(wire2, wire, fn2,
                                             lep_vectors_ctx(name, "frame bytes"));
    }
}

/* Decode then encode gives the same bytes (whatever the fields' JSON form). */
static void test_response_vectors_round_trip(void)
{
    const lep_json *rs = lep_vectors_section(g_vectors, "responses");
    size_t i;
    for (i = 0; i < lep_json_len(rs); i++) {
        const lep_json *v = lep_json_at(rs, i);
        const char *name = lep_json_get_str(v, "name");
        uint8_t msg[LEP_MAX_MESSAGE];
        uint8_t out[LEP_MAX_MESSAGE];
        size_t len = lep_vectors_hex(lep_json_get_str(v, "message"), msg, sizeof(msg));
        size_t n = 0;
        lep_response r;
        (void)lep_response_decode(msg, len, &r); /* LEP_E_SENSOR still fills code and result */
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_response_encode(&r, out, sizeof(out), &n),
                                      lep_vectors_ctx(name, "re-encode"));
        TEST_ASSERT_EQUAL_size_t_MESSAGE(len, n, lep_vectors_ctx(name, "re-encoded length"));
        TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(msg, out, len,
                                             lep_vectors_ctx(name, "re-encoded bytes"));
    }
}

static void test_invalid_response_vectors(void)
{
    const lep_json *bad = lep_vectors_section(g_vectors, "invalid_responses");
    size_t i;
    for (i = 0; i < lep_json_len(bad); i++) {
        const lep_json *v = lep_json_at(bad, i);
        uint8_t msg[LEP_MAX_MESSAGE];
        size_t len = lep_vectors_hex(lep_json_get_str(v, "message"), msg, sizeof(msg));
        lep_response r;
        TEST_ASSERT_EQUAL_INT_MESSAGE(lep_vectors_error(lep_json_get_str(v, "error")),
                                      lep_response_decode(msg, len, &r),
                                      lep_vectors_ctx(lep_json_get_str(v, "name"), "decode"));
    }
}

/* Firmware variants: decoded into the fields (the last reserved byte of a
 * sample is accepted with any value), re-encoded into the canonical v1.13 bytes. */
static void test_response_variant_vectors(void)
{
    const lep_json *vs = lep_vectors_section(g_vectors, "response_variants");
    size_t i;
    for (i = 0; i < lep_json_len(vs); i++) {
        const lep_json *v = lep_json_at(vs, i);
        const char *name = lep_json_get_str(v, "name");
        uint8_t msg[LEP_MAX_MESSAGE];
        uint8_t canonical[LEP_MAX_MESSAGE];
        uint8_t out[LEP_MAX_MESSAGE];
        size_t len = lep_vectors_hex(lep_json_get_str(v, "message"), msg, sizeof(msg));
        size_t clen =
            lep_vectors_hex(lep_json_get_str(v, "canonical"), canonical, sizeof(canonical));
        size_t n = 0;
        lep_response want;
        lep_response got;
        response_of(v, &want);
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_response_decode(msg, len, &got),
                                      lep_vectors_ctx(name, "decode"));
        expect_fields(&want, &got, name);
        if (len == LEP_LEN_SAMPLE) {
            TEST_ASSERT_EQUAL_HEX8_MESSAGE((uint8_t)lep_json_get_int(v, "last_reserved", -1),
                                           msg[19], lep_vectors_ctx(name, "last reserved byte"));
        }
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_response_encode(&got, out, sizeof(out), &n),
                                      lep_vectors_ctx(name, "encode"));
        TEST_ASSERT_EQUAL_size_t_MESSAGE(clen, n, lep_vectors_ctx(name, "canonical length"));
        TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(canonical, out, clen,
                                             lep_vectors_ctx(name, "canonical bytes"));
    }
}

/* The encoder refuses what the decoder would reject, so a device never sends it. */
static void test_encoder_refuses_what_decoding_rejects(void)
{
    lep_response r;
    uint8_t out[LEP_MAX_MESSAGE];
    size_t n = 99;
    memset(&r, 0, sizeof(r));
    r.code = LEP_CMD_SAMPLE;
    r.u.sample.raw[LEP_MY] = 32001;
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_response_encode(&r, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_size_t(0, n);
    r.u.sample.raw[LEP_MY] = -32001;
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_response_encode(&r, out, sizeof(out), &n));
    r.u.sample.raw[LEP_MY] = -32000;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_response_encode(&r, out, sizeof(out), &n));
    memset(&r, 0, sizeof(r));
    r.code = LEP_CMD_PRODUCT_INFO;
    strcpy(r.u.info.model, "PFS\033[2J");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_response_encode(&r, out, sizeof(out), &n));
    strcpy(r.u.info.model, "PFS055");
    r.u.info.firmware[0] = (char)0xB3;
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_response_encode(&r, out, sizeof(out), &n));
    strcpy(r.u.info.firmware, "1.13");
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_response_encode(&r, out, sizeof(out), &n));
}

/* The float helper agrees with the double one to float precision. */
static void test_sample_to_si_float(void)
{
    lep_sample s;
    lep_rated rated = { { 500.0f, 500.0f, 1000.0f, 40.0f, 40.0f, 30.0f } };
    double d[LEP_AXES];
    float f[LEP_AXES] = { 0 };
    size_t i;
    memset(&s, 0, sizeof(s));
    s.raw[0] = 10000;
    s.raw[1] = -10000;
    s.raw[2] = 1;
    s.raw[3] = 32000;
    s.raw[4] = -32000;
    s.raw[5] = 4112;
    lep_sample_to_si(&s, &rated, d);
    lep_sample_to_si_f(&s, &rated, f);
    for (i = 0; i < LEP_AXES; i++) {
        TEST_ASSERT_FLOAT_WITHIN((float)(1e-6 * (d[i] < 0 ? -d[i] : d[i]) + 1e-9), (float)d[i],
                                 f[i]);
    }
    TEST_ASSERT_EQUAL_FLOAT(500.0f, f[0]);
    d[0] = 7.0;
    lep_sample_to_si(NULL, &rated, d);
    lep_sample_to_si(&s, NULL, d);
    lep_sample_to_si(&s, &rated, NULL);
    TEST_ASSERT_EQUAL_DOUBLE(7.0, d[0]);
    f[0] = 7.0f;
    lep_sample_to_si_f(NULL, &rated, f);
    lep_sample_to_si_f(&s, NULL, f);
    lep_sample_to_si_f(&s, &rated, NULL);
    TEST_ASSERT_EQUAL_FLOAT(7.0f, f[0]);
}

/* Every non-zero result code is the sensor's error, kept apart from library errors. */
static void test_sensor_result_codes(void)
{
    uint8_t result;
    for (result = 1; result <= 4; result++) {
        uint8_t msg[4] = { 0x04, 0xFF, LEP_CMD_RATED, 0 };
        lep_response r;
        msg[3] = result;
        TEST_ASSERT_EQUAL_INT(LEP_E_SENSOR, lep_response_decode(msg, sizeof(msg), &r));
        TEST_ASSERT_EQUAL_HEX8(LEP_CMD_RATED, r.code);
        TEST_ASSERT_EQUAL_HEX8(result, r.result);
    }
}

static void test_response_encode_errors(void)
{
    static const uint32_t bad_bits[] = { 0x7FC00000u, 0x7F800000u, 0xFF800000u,
                                         0x00000000u, 0x80000000u, 0xC1200000u /* -10.0 */ };
    uint8_t out[LEP_MAX_MESSAGE];
    size_t n;
    size_t i;
    lep_response r;
    memset(&r, 0, sizeof(r));
    r.code = LEP_CMD_RATED;
    for (i = 0; i < sizeof(bad_bits) / sizeof(bad_bits[0]); i++) {
        size_t axis;
        for (axis = 0; axis < LEP_AXES; axis++) {
            r.u.rated.axis[axis] = 100.0f;
        }
        memcpy(&r.u.rated.axis[i % LEP_AXES], &bad_bits[i], sizeof(float));
        TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_response_encode(&r, out, sizeof(out), &n));
    }
    memset(&r, 0, sizeof(r));
    r.code = LEP_CMD_FILTER_GET;
    r.u.filter = 4;
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_response_encode(&r, out, sizeof(out), &n));
    r.code = 0x40;
    r.u.filter = 0;
    TEST_ASSERT_EQUAL_INT(LEP_E_UNEXPECTED, lep_response_encode(&r, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_UNEXPECTED, lep_response_frame(&r, out, sizeof(out), &n));
    r.code = LEP_CMD_STOP;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_response_encode(NULL, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_response_encode(&r, NULL, sizeof(out), &n));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_response_encode(&r, out, sizeof(out), NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_response_decode(NULL, 4, &r));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_response_decode(out, 4, NULL));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_response_frame(&r, out, sizeof(out), NULL));
}

/* Text fields: trailing spaces and NULs are removed on decode, spaces added on encode. */
static void test_product_info_padding(void)
{
    uint8_t msg[LEP_LEN_PRODUCT_INFO];
    uint8_t out[LEP_LEN_PRODUCT_INFO];
    lep_response r;
    size_t n;
    memset(msg, 0, sizeof(msg));
    msg[0] = LEP_LEN_PRODUCT_INFO;
    msg[1] = 0xFF;
    msg[2] = LEP_CMD_PRODUCT_INFO;
    memcpy(msg + 4, "AB  ", 4); /* then NULs up to 16 bytes */
    memcpy(msg + 20, "1234    ", 8);
    memcpy(msg + 28, "1.0 ", 4);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_response_decode(msg, sizeof(msg), &r));
    TEST_ASSERT_EQUAL_STRING("AB", r.u.info.model);
    TEST_ASSERT_EQUAL_STRING("1234", r.u.info.serial);
    TEST_ASSERT_EQUAL_STRING("1.0", r.u.info.firmware);
    TEST_ASSERT_FALSE(r.u.info.has_output_rate);
    TEST_ASSERT_EQUAL_STRING("", r.u.info.output_rate);
    TEST_ASSERT_EQUAL_UINT32(0u, r.u.info.output_rate_hz);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_response_encode(&r, out, sizeof(out), &n));
    TEST_ASSERT_EQUAL_size_t(LEP_LEN_PRODUCT_INFO, n);
    TEST_ASSERT_EQUAL_MEMORY("AB              ", out + 4, 16);
    TEST_ASSERT_EQUAL_MEMORY("1234    1.0 ", out + 20, 12);
}

/* ---- samples ------------------------------------------------------------------ */

static void test_si_vectors(void)
{
    const lep_json *si = lep_vectors_section(g_vectors, "si");
    size_t i;
    for (i = 0; i < lep_json_len(si); i++) {
        const lep_json *v = lep_json_at(si, i);
        const char *name = lep_json_get_str(v, "name");
        const lep_json *rated = lep_json_get(v, "rated");
        const lep_json *raw = lep_json_get(v, "raw");
        const lep_json *want = lep_json_get(v, "si");
        lep_sample s;
        lep_rated rt;
        double got[LEP_AXES];
        size_t a;
        memset(&s, 0, sizeof(s));
        for (a = 0; a < LEP_AXES; a++) {
            rt.axis[a] = (float)lep_json_num(lep_json_at(rated, a));
            s.raw[a] = (int16_t)lep_json_num(lep_json_at(raw, a));
        }
        lep_sample_to_si(&s, &rt, got);
        for (a = 0; a < LEP_AXES; a++) {
            double w = lep_json_num(lep_json_at(want, a));
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-12 * ((w < 0 ? -w : w) + 1.0), w, got[a],
                                              lep_vectors_ctx(name, "si"));
        }
    }
}

static void test_si_of_the_spec_sample(void)
{
    /* Spec data response: (16, -16, 10000, -10000, 4112, 32000) with PFS055YA501U6 ratings. */
    const lep_sample s = { { 16, -16, 10000, -10000, 4112, 32000 }, 0, LEP_STATUS_OVERLOAD };
    const lep_rated rt = { { 500.0f, 500.0f, 500.0f, 10.0f, 10.0f, 8.0f } };
    double si[LEP_AXES];
    lep_sample_to_si(&s, &rt, si);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.8, si[LEP_FX]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, -0.8, si[LEP_FY]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 500.0, si[LEP_FZ]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, -10.0, si[LEP_MX]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 4.112, si[LEP_MY]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 25.6, si[LEP_MZ]);
}

static void test_saturation_vectors(void)
{
    const lep_json *sat = lep_vectors_section(g_vectors, "saturation");
    size_t i;
    for (i = 0; i < lep_json_len(sat); i++) {
        const lep_json *v = lep_json_at(sat, i);
        const lep_json *raw = lep_json_get(v, "raw");
        lep_sample s;
        size_t a;
        memset(&s, 0, sizeof(s));
        for (a = 0; a < LEP_AXES; a++) {
            s.raw[a] = (int16_t)lep_json_num(lep_json_at(raw, a));
        }
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(
            get_u8(v, "mask"), lep_sample_saturated(&s, (int16_t)lep_json_get_int(v, "limit", 0)),
            lep_vectors_ctx(lep_json_get_str(v, "name"), "mask"));
    }
    TEST_ASSERT_EQUAL_INT(32000, LEP_SATURATION_V113);
    TEST_ASSERT_EQUAL_INT(15000, LEP_SATURATION_LATER);
    TEST_ASSERT_EQUAL_INT(10000, LEP_RAW_FULL_SCALE);
    TEST_ASSERT_EQUAL_HEX8(0u, lep_sample_saturated(NULL, LEP_SATURATION_V113));
}

static void test_status_bits(void)
{
    static const uint8_t msg[] = { 0x14, 0xFF, 0x30, 0x00, 0, 0, 0, 0, 0,    0,
                                   0,    0,    0,    0,    0, 0, 0, 0, 0x07, 0 };
    lep_response r;
    TEST_ASSERT_EQUAL_HEX8(0x01, LEP_STATUS_CALIBRATION);
    TEST_ASSERT_EQUAL_HEX8(0x02, LEP_STATUS_SENSOR_FAULT);
    TEST_ASSERT_EQUAL_HEX8(0x04, LEP_STATUS_OVERLOAD);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_response_decode(msg, sizeof(msg), &r));
    TEST_ASSERT_BITS_HIGH(LEP_STATUS_CALIBRATION | LEP_STATUS_SENSOR_FAULT | LEP_STATUS_OVERLOAD,
                          r.u.sample.status);
    TEST_ASSERT_FALSE(r.stream);
}

/* A sample message's whole lep_response, byte for byte (every byte not
 * decoded stays 0), for the handshake answer and stream data; and a count
 * beyond +/-32000 on each axis in turn: LEP_E_VALUE, with code, stream and
 * the counts before the bad one set. Speed builds decode these messages on
 * their own path (test_message_small runs the size builds' one). */
static void test_sample_decode_whole_response(void)
{
    static const uint8_t codes[2] = { LEP_CMD_SAMPLE, LEP_CMD_START };
    static const int16_t raw[LEP_AXES] = { -32000, 32000, -1, 0, 256, -257 };
    static const int32_t bad[2] = { 32001, -32001 };
    size_t c;
    for (c = 0; c < 2; c++) {
        uint8_t msg[LEP_LEN_SAMPLE] = { LEP_LEN_SAMPLE, 0xFF, codes[c], 0x00 };
        lep_response want;
        lep_response got;
        size_t a;
        size_t b;
        size_t i;
        for (i = 0; i < LEP_AXES; i++) {
            msg[4 + 2 * i] = (uint8_t)((uint16_t)raw[i] & 0xFFu);
            msg[5 + 2 * i] = (uint8_t)((uint16_t)raw[i] >> 8);
        }
        msg[16] = 0x34;
        msg[17] = 0x12;
        msg[18] = LEP_STATUS_OVERLOAD;
        msg[19] = 0x5A; /* the last reserved byte: any value, not kept */
        memset(&want, 0, sizeof(want));
        want.code = codes[c];
        want.stream = codes[c] == LEP_CMD_START;
        memcpy(want.u.sample.raw, raw, sizeof(raw));
        want.u.sample.reserved = 0x1234;
        want.u.sample.status = LEP_STATUS_OVERLOAD;
        memset(&got, 0xA5, sizeof(got));
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_response_decode(msg, sizeof(msg), &got));
        TEST_ASSERT_EQUAL_HEX8_ARRAY(&want, &got, sizeof(want));
        for (a = 0; a < LEP_AXES; a++) {
            for (b = 0; b < 2; b++) {
                uint8_t m[LEP_LEN_SAMPLE];
                memcpy(m, msg, sizeof(m));
                m[4 + 2 * a] = (uint8_t)((uint32_t)bad[b] & 0xFFu);
                m[5 + 2 * a] = (uint8_t)(((uint32_t)bad[b] >> 8) & 0xFFu);
                memset(&want.u, 0, sizeof(want.u));
                memcpy(want.u.sample.raw, raw, a * sizeof(raw[0]));
                memset(&got, 0xA5, sizeof(got));
                TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_response_decode(m, sizeof(m), &got));
                TEST_ASSERT_EQUAL_HEX8_ARRAY(&want, &got, sizeof(want));
            }
        }
    }
}

/* ---- static strings ------------------------------------------------------------ */

static void expect_distinct(const char *const *s, size_t n, const char *what)
{
    size_t i;
    size_t j;
    for (i = 0; i < n; i++) {
        TEST_ASSERT_NOT_NULL_MESSAGE(s[i], what);
        TEST_ASSERT_GREATER_THAN_size_t_MESSAGE(0u, strlen(s[i]), what);
        for (j = 0; j < i; j++) {
            TEST_ASSERT_TRUE_MESSAGE(strcmp(s[i], s[j]) != 0, s[i]);
        }
    }
}

#if LEP_HAVE_ERROR_STRINGS /* (test_config checks the texts are "" without) */
static void test_strerror_every_code(void)
{
    static const int codes[] = {
        LEP_OK,        LEP_E_ARG,         LEP_E_BUFFER,     LEP_E_TOO_LONG,   LEP_E_BCC,
        LEP_E_ESCAPE,  LEP_E_LENGTH,      LEP_E_RESERVED,   LEP_E_UNEXPECTED, LEP_E_VALUE,
        LEP_E_SENSOR,  LEP_E_NAK,         LEP_E_TIMEOUT,    LEP_E_IO,         LEP_E_DISCONNECTED,
        LEP_E_BUSY,    LEP_E_NOT_FOUND,   LEP_E_PERMISSION, LEP_E_NOT_TTY,    LEP_E_STATE,
        LEP_E_NO_SYNC, LEP_E_UNSUPPORTED, LEP_E_END,        LEP_E_STALLED,    LEP_E_LOST
    };
    const char *s[sizeof(codes) / sizeof(codes[0]) + 1];
    size_t i;
    for (i = 0; i < sizeof(codes) / sizeof(codes[0]); i++) {
        s[i] = lep_strerror(codes[i]);
    }
    s[i] = lep_strerror(-9999); /* the unknown text differs from every known one */
    expect_distinct(s, i + 1u, "lep_strerror");
    /* the ends of the packed list, and both sides of it */
    TEST_ASSERT_EQUAL_STRING("success", lep_strerror(LEP_OK));
    TEST_ASSERT_EQUAL_STRING("invalid argument", lep_strerror(LEP_E_ARG));
    TEST_ASSERT_EQUAL_STRING("no stream data within the watchdog time",
                             lep_strerror(LEP_E_STALLED));
    TEST_ASSERT_EQUAL_STRING("unknown error", lep_strerror(1));
    TEST_ASSERT_EQUAL_STRING("stream lost", lep_strerror(LEP_E_LOST));
    TEST_ASSERT_EQUAL_STRING("unknown error", lep_strerror(LEP_E_LOST - 1));
}

static void test_result_str(void)
{
    const char *s[6];
    uint8_t i;
    for (i = 0; i <= 5; i++) {
        s[i] = lep_result_str(i); /* 5 is not a result code of the spec */
    }
    expect_distinct(s, 6, "lep_result_str");
    TEST_ASSERT_EQUAL_STRING("success", lep_result_str(LEP_RESULT_OK));
    TEST_ASSERT_EQUAL_STRING("length error", lep_result_str(LEP_RESULT_LENGTH));
    TEST_ASSERT_EQUAL_STRING("state error", lep_result_str(LEP_RESULT_STATE));
    TEST_ASSERT_EQUAL_STRING("unknown result code", lep_result_str(5));
    TEST_ASSERT_EQUAL_STRING(lep_result_str(5), lep_result_str(0xFF));
}
#endif

static void test_filter_labels(void)
{
    const char *s[5];
    uint8_t i;
    for (i = 0; i <= 4; i++) {
        s[i] = lep_filter_label(i);
    }
    expect_distinct(s, 5, "lep_filter_label");
    TEST_ASSERT_EQUAL_STRING("off", lep_filter_label(0));
    TEST_ASSERT_EQUAL_STRING("10 Hz", lep_filter_label(1));
    TEST_ASSERT_EQUAL_STRING("100 Hz", lep_filter_label(2));
    TEST_ASSERT_EQUAL_STRING("200 Hz", lep_filter_label(3));
    TEST_ASSERT_EQUAL_STRING(lep_filter_label(4), lep_filter_label(0xFF));
}

static void test_command_names(void)
{
    const char *s[8];
    s[0] = lep_command_name(LEP_CMD_PRODUCT_INFO);
    s[1] = lep_command_name(LEP_CMD_RATED);
    s[2] = lep_command_name(LEP_CMD_FILTER_GET);
    s[3] = lep_command_name(LEP_CMD_SAMPLE);
    s[4] = lep_command_name(LEP_CMD_START);
    s[5] = lep_command_name(LEP_CMD_STOP);
    s[6] = lep_command_name(LEP_CMD_FILTER_SET);
    s[7] = lep_command_name(0x40);
    expect_distinct(s, 8, "lep_command_name");
}

int main(void)
{
    int failures;
    g_vectors = lep_vectors_load("messages.json");
    UNITY_BEGIN();
    RUN_TEST(test_command_vectors_encode_and_decode);
    RUN_TEST(test_invalid_command_vectors);
    RUN_TEST(test_command_encode_error_vectors);
    RUN_TEST(test_command_null_arguments);
    RUN_TEST(test_command_frame_every_code_and_filter);
    RUN_TEST(test_command_arguments_checked_first);
    RUN_TEST(test_response_vectors_decode);
    RUN_TEST(test_response_vectors_encode);
    RUN_TEST(test_response_vectors_round_trip);
    RUN_TEST(test_invalid_response_vectors);
    RUN_TEST(test_response_variant_vectors);
    RUN_TEST(test_encoder_refuses_what_decoding_rejects);
    RUN_TEST(test_sample_to_si_float);
    RUN_TEST(test_sensor_result_codes);
    RUN_TEST(test_response_encode_errors);
    RUN_TEST(test_product_info_padding);
    RUN_TEST(test_si_vectors);
    RUN_TEST(test_si_of_the_spec_sample);
    RUN_TEST(test_saturation_vectors);
    RUN_TEST(test_status_bits);
    RUN_TEST(test_sample_decode_whole_response);
#if LEP_HAVE_ERROR_STRINGS
    RUN_TEST(test_strerror_every_code);
    RUN_TEST(test_result_str);
#endif
    RUN_TEST(test_filter_labels);
    RUN_TEST(test_command_names);
    failures = UNITY_END();
    lep_json_free(g_vectors);
    return failures;
}
