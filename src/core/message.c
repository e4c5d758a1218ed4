/* Message codec: commands and responses of spec sections 3-7, both directions. */
#include "leptrino/message.h"

#include <string.h>

#include "leptrino/error.h"
#include "leptrino/frame.h"

#define RESERVED_FF 0xFFu

/* The rated values travel as IEEE-754 binary32. */
typedef char lep_float_is_binary32[(sizeof(float) == 4u) ? 1 : -1];

/* Shifts are done on unsigned types at least as wide as the result: a 16-bit
 * int (AVR) must not see p[1] << 8 overflow into its sign bit. */
static uint16_t get_u16(const uint8_t *p)
{
    return (uint16_t)((uint16_t)p[0] | (uint16_t)((uint16_t)p[1] << 8));
}

static int16_t get_i16(const uint8_t *p)
{
    uint16_t u = get_u16(p);
    return u >= 0x8000u ? (int16_t)((int32_t)u - (int32_t)65536L) : (int16_t)u;
}

static void put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)(v >> 8);
}

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)((v >> 8) & 0xFFu);
    p[2] = (uint8_t)((v >> 16) & 0xFFu);
    p[3] = (uint8_t)(v >> 24);
}

/* A rating must be finite and strictly positive. */
static bool rating_bits_ok(uint32_t bits)
{
    bool finite = ((bits >> 23) & 0xFFu) != 0xFFu;
    bool positive = (bits & 0x80000000u) == 0u && (bits & 0x7FFFFFFFu) != 0u;
    return finite && positive;
}

static uint32_t float_bits(float f)
{
    uint32_t bits;
    memcpy(&bits, &f, sizeof(bits));
    return bits;
}

static bool known_code(uint8_t code)
{
    switch (code) {
    case LEP_CMD_PRODUCT_INFO:
    case LEP_CMD_RATED:
    case LEP_CMD_FILTER_GET:
    case LEP_CMD_SAMPLE:
    case LEP_CMD_START:
    case LEP_CMD_STOP:
    case LEP_CMD_FILTER_SET:
        return true;
    default:
        return false;
    }
}

static void put_header(uint8_t *msg, size_t len, uint8_t code, uint8_t fourth)
{
    msg[0] = (uint8_t)len;
    msg[1] = RESERVED_FF;
    msg[2] = code;
    msg[3] = fourth;
}

int lep_command_encode(const lep_command *cmd, uint8_t *msg, size_t cap, size_t *len)
{
    size_t n;
    if (cmd == NULL || msg == NULL || len == NULL) {
        return LEP_E_ARG;
    }
    *len = 0;
    if (!known_code(cmd->code)) {
        return LEP_E_UNEXPECTED;
    }
    n = cmd->code == LEP_CMD_FILTER_SET ? LEP_LEN_FILTER_SET_CMD : LEP_LEN_HEADER;
    if (cmd->code == LEP_CMD_FILTER_SET && cmd->filter > LEP_FILTER_MAX) {
        return LEP_E_VALUE;
    }
    if (cap < n) {
        return LEP_E_BUFFER;
    }
    put_header(msg, n, cmd->code, 0x00u);
    if (cmd->code == LEP_CMD_FILTER_SET) {
        msg[4] = cmd->filter;
        msg[5] = msg[6] = msg[7] = 0x00u;
    }
    *len = n;
    return LEP_OK;
}

static int command_fail(uint8_t *result, uint8_t code, int err)
{
    *result = code;
    return err;
}

int lep_command_decode(const uint8_t *msg, size_t len, lep_command *cmd, uint8_t *result)
{
    size_t want;
    if (msg == NULL || cmd == NULL || result == NULL) {
        return LEP_E_ARG;
    }
    cmd->code = len >= 3u ? msg[2] : 0u;
    cmd->filter = 0;
    *result = LEP_RESULT_OK;
    if (len < LEP_LEN_HEADER || msg[0] != len) {
        return command_fail(result, LEP_RESULT_LENGTH, LEP_E_LENGTH);
    }
    if (!known_code(cmd->code)) {
        return command_fail(result, LEP_RESULT_UNDEFINED, LEP_E_UNEXPECTED);
    }
    want = cmd->code == LEP_CMD_FILTER_SET ? LEP_LEN_FILTER_SET_CMD : LEP_LEN_HEADER;
    if (len != want) {
        return command_fail(result, LEP_RESULT_LENGTH, LEP_E_LENGTH);
    }
    if (msg[1] != RESERVED_FF || msg[3] != 0x00u) {
        return command_fail(result, LEP_RESULT_VALUE, LEP_E_RESERVED);
    }
    if (cmd->code == LEP_CMD_FILTER_SET) {
        if (msg[5] != 0u || msg[6] != 0u || msg[7] != 0u) {
            return command_fail(result, LEP_RESULT_VALUE, LEP_E_RESERVED);
        }
        if (msg[4] > LEP_FILTER_MAX) {
            return command_fail(result, LEP_RESULT_VALUE, LEP_E_VALUE);
        }
        cmd->filter = msg[4];
    }
    return LEP_OK;
}

static bool printable(uint8_t b)
{
    return b >= 0x20u && b <= 0x7Eu;
}

/* Copy an ASCII field into a C string without its padding (trailing spaces
 * and NULs). LEP_E_VALUE for anything but printable ASCII before the padding
 * (a control byte, a byte >= 0x80, a NUL followed by text). */
static int get_text(char *dst, const uint8_t *src, size_t n)
{
    size_t end = n;
    size_t i;
    while (end > 0 && (src[end - 1] == ' ' || src[end - 1] == 0u)) {
        end--;
    }
    for (i = 0; i < end; i++) {
        if (!printable(src[i])) {
            return LEP_E_VALUE;
        }
        dst[i] = (char)src[i];
    }
    dst[end] = '\0';
    return LEP_OK;
}

/* Write a C string (at most n characters, printable ASCII) into an n-byte
 * field, space padded. */
static int put_text(uint8_t *dst, const char *src, size_t n)
{
    size_t len = 0;
    while (src[len] != '\0') { /* src has room for n characters and a NUL */
        if (len == n || !printable((uint8_t)src[len])) {
            return LEP_E_VALUE;
        }
        dst[len] = (uint8_t)src[len];
        len++;
    }
    memset(dst + len, ' ', n - len);
    return LEP_OK;
}

static uint32_t parse_rate(const char *s)
{
    uint32_t v = 0;
    size_t i = 0;
    size_t digits = 0;
    while (s[i] == ' ') {
        i++;
    }
    while (s[i] >= '0' && s[i] <= '9') { /* at most 6 digits: no overflow */
        v = v * 10u + (uint32_t)(s[i] - '0');
        i++;
        digits++;
    }
    return (digits > 0u && s[i] == '\0') ? v : 0u;
}

/* The last reserved byte (msg[19], "0x00 fixed" in v1.13) is accepted with
 * any value: later firmware leaves it unspecified. |raw| > 32000 is
 * impossible on every firmware: LEP_E_VALUE. */
static int decode_sample(const uint8_t *msg, lep_sample *s)
{
    size_t i;
    for (i = 0; i < LEP_AXES; i++) {
        int16_t v = get_i16(msg + 4 + 2 * i);
        if (v > LEP_SATURATION_V113 || v < -LEP_SATURATION_V113) {
            return LEP_E_VALUE;
        }
        s->raw[i] = v;
    }
    s->reserved = get_u16(msg + 16);
    s->status = msg[18];
    return LEP_OK;
}

static int decode_data(const uint8_t *msg, size_t len, lep_response *r)
{
    size_t i;
    switch (r->code) {
    case LEP_CMD_PRODUCT_INFO:
        if (len != LEP_LEN_PRODUCT_INFO && len != LEP_LEN_PRODUCT_INFO_RATE) {
            return LEP_E_LENGTH;
        }
        r->u.info.has_output_rate = len == LEP_LEN_PRODUCT_INFO_RATE;
        if (get_text(r->u.info.model, msg + 4, LEP_MODEL_LEN) != LEP_OK ||
            get_text(r->u.info.serial, msg + 20, LEP_SERIAL_LEN) != LEP_OK ||
            get_text(r->u.info.firmware, msg + 28, LEP_FIRMWARE_LEN) != LEP_OK ||
            (r->u.info.has_output_rate &&
             get_text(r->u.info.output_rate, msg + 32, LEP_RATE_LEN) != LEP_OK)) {
            memset(&r->u.info, 0, sizeof(r->u.info));
            return LEP_E_VALUE;
        }
        r->u.info.output_rate_hz = parse_rate(r->u.info.output_rate);
        return LEP_OK;
    case LEP_CMD_RATED:
        if (len != LEP_LEN_RATED) {
            return LEP_E_LENGTH;
        }
        for (i = 0; i < LEP_AXES; i++) {
            uint32_t bits = get_u32(msg + 4 + 4 * i);
            if (!rating_bits_ok(bits)) {
                return LEP_E_VALUE;
            }
            memcpy(&r->u.rated.axis[i], &bits, sizeof(bits));
        }
        return LEP_OK;
    case LEP_CMD_FILTER_GET:
        if (len != LEP_LEN_FILTER) {
            return LEP_E_LENGTH;
        }
        if (msg[5] != 0u || msg[6] != 0u || msg[7] != 0u) {
            return LEP_E_RESERVED;
        }
        if (msg[4] > LEP_FILTER_MAX) {
            return LEP_E_VALUE;
        }
        r->u.filter = msg[4];
        return LEP_OK;
    case LEP_CMD_SAMPLE:
        return len == LEP_LEN_SAMPLE ? decode_sample(msg, &r->u.sample) : LEP_E_LENGTH;
    case LEP_CMD_START:
        if (len == LEP_LEN_SAMPLE) {
            r->stream = true;
            return decode_sample(msg, &r->u.sample);
        }
        return len == LEP_LEN_HEADER ? LEP_OK : LEP_E_LENGTH;
    default: /* stop, filter set: acknowledgement only */
        return len == LEP_LEN_HEADER ? LEP_OK : LEP_E_LENGTH;
    }
}

int lep_response_decode(const uint8_t *msg, size_t len, lep_response *r)
{
    if (msg == NULL || r == NULL) {
        return LEP_E_ARG;
    }
    memset(r, 0, sizeof(*r));
    if (len < LEP_LEN_HEADER || msg[0] != len) {
        return LEP_E_LENGTH;
    }
    if (msg[1] != RESERVED_FF) {
        return LEP_E_RESERVED;
    }
    r->code = msg[2];
    r->result = msg[3];
    if (!known_code(r->code)) {
        return LEP_E_UNEXPECTED;
    }
    if (r->result != LEP_RESULT_OK) {
        return len == LEP_LEN_HEADER ? LEP_E_SENSOR : LEP_E_LENGTH;
    }
    return decode_data(msg, len, r);
}

static int encode_sample(uint8_t *msg, const lep_sample *s)
{
    size_t i;
    for (i = 0; i < LEP_AXES; i++) {
        if (s->raw[i] > LEP_SATURATION_V113 || s->raw[i] < -LEP_SATURATION_V113) {
            return LEP_E_VALUE;
        }
        put_u16(msg + 4 + 2 * i, (uint16_t)s->raw[i]);
    }
    put_u16(msg + 16, s->reserved);
    msg[18] = s->status;
    msg[19] = 0x00u;
    return LEP_OK;
}

/* Length of the encoded response r, or 0 when r cannot be encoded. */
static size_t response_length(const lep_response *r)
{
    if (r->result != LEP_RESULT_OK) {
        return LEP_LEN_HEADER; /* any code: a sensor answers unknown commands with 0x02 */
    }
    if (!known_code(r->code)) {
        return 0;
    }
    switch (r->code) {
    case LEP_CMD_PRODUCT_INFO:
        return r->u.info.has_output_rate ? LEP_LEN_PRODUCT_INFO_RATE : LEP_LEN_PRODUCT_INFO;
    case LEP_CMD_RATED: return LEP_LEN_RATED;
    case LEP_CMD_FILTER_GET: return LEP_LEN_FILTER;
    case LEP_CMD_SAMPLE: return LEP_LEN_SAMPLE;
    case LEP_CMD_START: return r->stream ? LEP_LEN_SAMPLE : LEP_LEN_HEADER;
    default: return LEP_LEN_HEADER;
    }
}

static int encode_info(uint8_t *msg, const lep_product_info *info)
{
    int rc = put_text(msg + 4, info->model, LEP_MODEL_LEN);
    if (rc == LEP_OK) {
        rc = put_text(msg + 20, info->serial, LEP_SERIAL_LEN);
    }
    if (rc == LEP_OK) {
        rc = put_text(msg + 28, info->firmware, LEP_FIRMWARE_LEN);
    }
    if (rc == LEP_OK && info->has_output_rate) {
        rc = put_text(msg + 32, info->output_rate, LEP_RATE_LEN);
    }
    return rc;
}

int lep_response_encode(const lep_response *r, uint8_t *msg, size_t cap, size_t *len)
{
    size_t n;
    size_t i;
    int rc = LEP_OK;
    if (r == NULL || msg == NULL || len == NULL) {
        return LEP_E_ARG;
    }
    *len = 0;
    n = response_length(r);
    if (n == 0) {
        return LEP_E_UNEXPECTED;
    }
    if (cap < n) {
        return LEP_E_BUFFER;
    }
    put_header(msg, n, r->code, r->result);
    if (n > LEP_LEN_HEADER) {
        switch (r->code) {
        case LEP_CMD_PRODUCT_INFO:
            rc = encode_info(msg, &r->u.info);
            break;
        case LEP_CMD_RATED:
            for (i = 0; i < LEP_AXES && rc == LEP_OK; i++) {
                uint32_t bits = float_bits(r->u.rated.axis[i]);
                rc = rating_bits_ok(bits) ? LEP_OK : LEP_E_VALUE;
                put_u32(msg + 4 + 4 * i, bits);
            }
            break;
        case LEP_CMD_FILTER_GET:
            rc = r->u.filter <= LEP_FILTER_MAX ? LEP_OK : LEP_E_VALUE;
            msg[4] = r->u.filter;
            msg[5] = msg[6] = msg[7] = 0x00u;
            break;
        default: /* the handshake sample or a stream data message */
            rc = encode_sample(msg, &r->u.sample);
            break;
        }
    }
    if (rc == LEP_OK) {
        *len = n;
    }
    return rc;
}

int lep_command_frame(const lep_command *cmd, uint8_t *out, size_t cap, size_t *len)
{
    uint8_t msg[LEP_LEN_FILTER_SET_CMD];
    size_t n;
    int rc;
    if (len == NULL) {
        return LEP_E_ARG;
    }
    *len = 0;
    rc = lep_command_encode(cmd, msg, sizeof(msg), &n);
    return rc == LEP_OK ? lep_frame_encode(msg, n, out, cap, len) : rc;
}

int lep_response_frame(const lep_response *r, uint8_t *out, size_t cap, size_t *len)
{
    uint8_t msg[LEP_LEN_PRODUCT_INFO_RATE];
    size_t n;
    int rc;
    if (len == NULL) {
        return LEP_E_ARG;
    }
    *len = 0;
    rc = lep_response_encode(r, msg, sizeof(msg), &n);
    return rc == LEP_OK ? lep_frame_encode(msg, n, out, cap, len) : rc;
}

void lep_sample_to_si(const lep_sample *s, const lep_rated *rated, double si[LEP_AXES])
{
    size_t i;
    if (s == NULL || rated == NULL || si == NULL) {
        return;
    }
    for (i = 0; i < LEP_AXES; i++) {
        si[i] = (double)s->raw[i] * (double)rated->axis[i] / (double)LEP_RAW_FULL_SCALE;
    }
}

void lep_sample_to_si_f(const lep_sample *s, const lep_rated *rated, float si[LEP_AXES])
{
    size_t i;
    if (s == NULL || rated == NULL || si == NULL) {
        return;
    }
    for (i = 0; i < LEP_AXES; i++) {
        si[i] = (float)s->raw[i] * rated->axis[i] / (float)LEP_RAW_FULL_SCALE;
    }
}

uint8_t lep_sample_saturated(const lep_sample *s, int16_t limit)
{
    uint8_t mask = 0;
    size_t i;
    if (s == NULL) {
        return 0;
    }
    for (i = 0; i < LEP_AXES; i++) {
        int32_t v = s->raw[i];
        if ((v < 0 ? -v : v) >= (int32_t)limit) {
            mask = (uint8_t)(mask | (1u << i));
        }
    }
    return mask;
}

const char *lep_filter_label(uint8_t code)
{
    switch (code) {
    case 0: return "off";
    case 1: return "10 Hz";
    case 2: return "100 Hz";
    case 3: return "200 Hz";
    default: return "invalid";
    }
}

const char *lep_command_name(uint8_t code)
{
    switch (code) {
    case LEP_CMD_PRODUCT_INFO: return "product info";
    case LEP_CMD_RATED: return "rated values";
    case LEP_CMD_FILTER_GET: return "filter query";
    case LEP_CMD_SAMPLE: return "handshake sample";
    case LEP_CMD_START: return "start continuous output";
    case LEP_CMD_STOP: return "stop continuous output";
    case LEP_CMD_FILTER_SET: return "set filter";
    default: return "unknown";
    }
}
