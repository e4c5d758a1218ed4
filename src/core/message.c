/* Message codec: commands and responses of spec sections 3-7, both directions.
 *
 * One table describes the seven command codes; every response length, and so
 * every data layout, belongs to exactly one layout (4 none, 8 filter, 20
 * sample, 28 ratings, 32/38 product info), so decoding and encoding dispatch
 * on the length once the code has allowed it. A command is built in one
 * place, framed or not (it never needs stuffing). */
#include "leptrino/message.h"

#include <stdbool.h>
#include <string.h>

#include "leptrino/error.h"
#include "leptrino/frame.h"

#define RESERVED_FF 0xFFu
/* DLE STX in front of a message, DLE ETX BCC behind it */
#define FRAME_EXTRA 5u

/* The rated values travel as IEEE-754 binary32. */
typedef char lep_float_is_binary32[(sizeof(float) == 4u) ? 1 : -1];

/* The known codes, in the order of k_response_len and of lep_command_name's list. */
enum { I_INFO, I_RATED, I_FILTER_GET, I_SAMPLE, I_START, I_STOP, I_FILTER_SET, N_CODES };
static const uint8_t k_codes[N_CODES] = { LEP_CMD_PRODUCT_INFO, LEP_CMD_RATED, LEP_CMD_FILTER_GET,
                                          LEP_CMD_SAMPLE,       LEP_CMD_START, LEP_CMD_STOP,
                                          LEP_CMD_FILTER_SET };

/* Lengths of a successful answer per code: the usual one, then the other
 * (the 38-byte product info with output rate, start's first data message). */
static const uint8_t k_response_len[N_CODES][2] = { { LEP_LEN_PRODUCT_INFO,
                                                      LEP_LEN_PRODUCT_INFO_RATE },
                                                    { LEP_LEN_RATED, LEP_LEN_RATED },
                                                    { LEP_LEN_FILTER, LEP_LEN_FILTER },
                                                    { LEP_LEN_SAMPLE, LEP_LEN_SAMPLE },
                                                    { LEP_LEN_HEADER, LEP_LEN_SAMPLE },
                                                    { LEP_LEN_HEADER, LEP_LEN_HEADER },
                                                    { LEP_LEN_HEADER, LEP_LEN_HEADER } };

/* The text fields of the product info, in wire order from byte 4; a
 * message holds the fields that start below its length (32: three, 38:
 * four), and the last entry starts beyond any message. */
static const struct text_field {
    uint8_t wire;  /* offset in the message */
    uint8_t width; /* bytes on the wire */
    uint8_t at;    /* offset of the C string in lep_product_info */
} k_text[] = { { 4, LEP_MODEL_LEN, offsetof(lep_product_info, model) },
               { 20, LEP_SERIAL_LEN, offsetof(lep_product_info, serial) },
               { 28, LEP_FIRMWARE_LEN, offsetof(lep_product_info, firmware) },
               { 32, LEP_RATE_LEN, offsetof(lep_product_info, output_rate) },
               { 0xFF, 0, 0 } }; /* the end: beyond any message */

/* Index of a code in k_codes, N_CODES when unknown. */
static unsigned code_index(uint8_t code)
{
    unsigned i = 0;
    while (i < N_CODES && k_codes[i] != code) {
        i++;
    }
    return i;
}

static size_t command_length(unsigned k)
{
    return k == I_FILTER_SET ? LEP_LEN_FILTER_SET_CMD : LEP_LEN_HEADER;
}

/* n little-endian bytes. Shifts are done on uint32_t: a 16-bit int (AVR)
 * must not see p[1] << 8 overflow into its sign bit. */
static uint32_t get_le(const uint8_t *p, unsigned n)
{
    uint32_t v = 0;
    while (n > 0u) {
        n--;
        v = (v << 8) | p[n];
    }
    return v;
}

/* Two little-endian bytes (the sample's fields). */
static uint16_t get_le16(const uint8_t *p)
{
    return (uint16_t)(p[0] | (unsigned)p[1] << 8);
}

static void put_le(uint8_t *p, uint32_t v, unsigned n)
{
    unsigned i;
    for (i = 0; i < n; i++) {
        p[i] = (uint8_t)(v & 0xFFu);
        v >>= 8;
    }
}

/* A rating must be finite (exponent not all ones) and strictly positive
 * (sign clear, not zero: 1 <= bits <= 0x7FFFFFFF). */
static bool rating_bits_ok(uint32_t bits)
{
    return ((bits >> 23) & 0xFFu) != 0xFFu && bits - 1u < 0x7FFFFFFFu;
}

static bool raw_ok(int16_t v)
{
    return v <= LEP_SATURATION_V113 && v >= -LEP_SATURATION_V113;
}

/* The filter field (code, then three reserved zero bytes) at msg[4..8) of a
 * filter set or a filter query's answer; the reserved bytes are checked first. */
static int get_filter(const uint8_t *msg, uint8_t *filter)
{
    if ((msg[5] | msg[6] | msg[7]) != 0u) {
        return LEP_E_RESERVED;
    }
    if (msg[4] > LEP_FILTER_MAX) {
        return LEP_E_VALUE;
    }
    *filter = msg[4];
    return LEP_OK;
}

static void put_header(uint8_t *msg, size_t len, uint8_t code, uint8_t fourth)
{
    msg[0] = (uint8_t)len;
    msg[1] = RESERVED_FF;
    msg[2] = code;
    msg[3] = fourth;
}

/* A message's own Length field agrees with its size. */
static bool length_ok(const uint8_t *msg, size_t len)
{
    return len >= LEP_LEN_HEADER && msg[0] == len;
}

/* A command never holds a DLE: its length is 4 or 8, then 0xFF, a code of
 * k_codes, 0x00 and, for a filter set, a filter code 0..3 and three 0x00
 * (the codes are checked below); so the frame is DLE STX, the message as it
 * is, DLE ETX and the BCC (never stuffed). (The casts: the codes and the
 * control byte are enumerators of different enums.) */
typedef char lep_no_command_code_is_dle
    [(LEP_CMD_PRODUCT_INFO != (int)LEP_DLE && LEP_CMD_RATED != (int)LEP_DLE &&
      LEP_CMD_FILTER_GET != (int)LEP_DLE && LEP_CMD_SAMPLE != (int)LEP_DLE &&
      LEP_CMD_START != (int)LEP_DLE && LEP_CMD_STOP != (int)LEP_DLE &&
      LEP_CMD_FILTER_SET != (int)LEP_DLE && LEP_FILTER_MAX < (int)LEP_DLE)
         ? 1
         : -1];

/* The one builder of a command: cmd as a message (extra 0) or as a frame
 * (extra FRAME_EXTRA) into out[0..cap); the errors of lep_command_frame. */
static int command_out(const lep_command *cmd, uint8_t *out, size_t cap, size_t *len,
                       unsigned extra)
{
    unsigned k;
    unsigned n = LEP_LEN_HEADER;
    unsigned filter = 0;
    if (len == NULL) {
        return LEP_E_ARG;
    }
    *len = 0;
    if (cmd == NULL || out == NULL) {
        return LEP_E_ARG;
    }
    k = code_index(cmd->code);
    if (k == N_CODES) {
        return LEP_E_UNEXPECTED;
    }
    if (k == I_FILTER_SET) {
        filter = cmd->filter;
        if (filter > LEP_FILTER_MAX) {
            return LEP_E_VALUE;
        }
        n = LEP_LEN_FILTER_SET_CMD;
    }
    if (cap < n + extra) {
        return LEP_E_BUFFER;
    }
    *len = n + extra;
    if (extra != 0u) {
        *out++ = LEP_DLE;
        *out++ = LEP_STX;
        out[n] = LEP_DLE;
        out[n + 1] = LEP_ETX;
        out[n + 2] = (uint8_t)(LEP_ETX ^ n ^ RESERVED_FF ^ cmd->code ^
                               filter); /* the XOR of the message and ETX */
    }
    put_header(out, n, cmd->code, 0x00u);
    /* the filter code and three reserved 0x00 follow the header of a filter set */
    put_le(out + 4, filter, n - LEP_LEN_HEADER);
    return LEP_OK;
}

int lep_command_frame(const lep_command *cmd, uint8_t *out, size_t cap, size_t *len)
{
    return command_out(cmd, out, cap, len, FRAME_EXTRA);
}

/* The same bytes as lep_command_frame's without DLE STX in front and DLE ETX
 * BCC behind (no byte of a command is stuffed). */
int lep_command_encode(const lep_command *cmd, uint8_t *msg, size_t cap, size_t *len)
{
    return command_out(cmd, msg, cap, len, 0u);
}

int lep_command_decode(const uint8_t *msg, size_t len, lep_command *cmd, uint8_t *result)
{
    unsigned k;
    int rc = LEP_OK;
    if (msg == NULL || cmd == NULL || result == NULL) {
        return LEP_E_ARG;
    }
    cmd->code = len >= 3u ? msg[2] : 0u;
    cmd->filter = 0;
    if (!length_ok(msg, len)) {
        rc = LEP_E_LENGTH;
    } else if ((k = code_index(cmd->code)) == N_CODES) {
        rc = LEP_E_UNEXPECTED;
    } else if (len != command_length(k)) {
        rc = LEP_E_LENGTH;
    } else if (msg[1] != RESERVED_FF || msg[3] != 0x00u) {
        rc = LEP_E_RESERVED;
    } else if (len == LEP_LEN_FILTER_SET_CMD) {
        rc = get_filter(msg, &cmd->filter);
    }
    /* the answer's result: a length error, an undefined command, or a bad value */
    *result = rc == LEP_OK             ? LEP_RESULT_OK
              : rc == LEP_E_LENGTH     ? LEP_RESULT_LENGTH
              : rc == LEP_E_UNEXPECTED ? LEP_RESULT_UNDEFINED
                                       : LEP_RESULT_VALUE;
    return rc;
}

static bool printable(uint8_t b)
{
    return b >= 0x20u && b <= 0x7Eu;
}

/* Copy an ASCII field into a zeroed C string without its padding (trailing spaces
 * and NULs). False for anything but printable ASCII before the padding
 * (a control byte, a byte >= 0x80, a NUL followed by text). */
static bool get_text(char *dst, const uint8_t *src, size_t n)
{
    bool pad = true;
    while (n > 0u) {
        uint8_t b = src[--n];
        if (pad && (b | 0x20u) == 0x20u) {
            continue; /* a trailing space or NUL */
        }
        pad = false;
        if (!printable(b)) {
            return false;
        }
        dst[n] = (char)b;
    }
    return true; /* the padding stays '\0': lep_response_decode zeroed r */
}

/* Write a C string (at most n characters, printable ASCII) into an n-byte
 * field, space padded. */
static bool put_text(uint8_t *dst, const char *src, size_t n)
{
    size_t len = 0;
    while (src[len] != '\0') { /* src has room for n characters and a NUL */
        if (len == n || !printable((uint8_t)src[len])) {
            return false;
        }
        dst[len] = (uint8_t)src[len];
        len++;
    }
    memset(dst + len, ' ', n - len);
    return true;
}

/* Leading spaces, then digits to the end; 0 for anything else (no digits
 * leave v at 0, so they need no test of their own). */
static uint32_t parse_rate(const char *s)
{
    uint32_t v = 0;
    while (*s == ' ') {
        s++;
    }
    while (*s >= '0' && *s <= '9') { /* at most 6 digits: no overflow */
        v = v * 10u + (uint32_t)(*s - '0');
        s++;
    }
    return *s == '\0' ? v : 0u;
}

/* The product info's text fields of a len-byte message (32: three, 38: four). */
static int decode_info(const uint8_t *msg, size_t len, lep_product_info *info)
{
    const struct text_field *t;
    for (t = k_text; t->wire < len; t++) {
        if (!get_text((char *)info + t->at, msg + t->wire, t->width)) {
            memset(info, 0, sizeof(*info));
            return LEP_E_VALUE;
        }
    }
    info->has_output_rate = len == LEP_LEN_PRODUCT_INFO_RATE;
    info->output_rate_hz = parse_rate(info->output_rate);
    return LEP_OK;
}

/* The last reserved byte (msg[19], "0x00 fixed" in v1.13) is accepted with
 * any value: later firmware leaves it unspecified. |raw| > 32000 is
 * impossible on every firmware: LEP_E_VALUE, with the counts before the
 * first bad one kept. */
static int decode_sample(const uint8_t *msg, lep_sample *s)
{
    size_t i;
    for (i = 0; i < LEP_AXES; i++) {
        uint16_t u = get_le16(msg + 4 + 2 * i);
        int16_t v = u >= 0x8000u ? (int16_t)((int32_t)u - (int32_t)65536L) : (int16_t)u;
        if (!raw_ok(v)) {
            return LEP_E_VALUE;
        }
        s->raw[i] = v;
    }
    s->reserved = get_le16(msg + 16);
    s->status = msg[18];
    return LEP_OK;
}

int lep_response_decode(const uint8_t *msg, size_t len, lep_response *r)
{
    unsigned k;
    size_t i;
    if (msg == NULL || r == NULL) {
        return LEP_E_ARG;
    }
    memset(r, 0, sizeof(*r));
    if (!length_ok(msg, len)) {
        return LEP_E_LENGTH;
    }
    if (msg[1] != RESERVED_FF) {
        return LEP_E_RESERVED;
    }
    r->code = msg[2];
    r->result = msg[3];
    k = code_index(r->code);
    if (k == N_CODES) {
        return LEP_E_UNEXPECTED;
    }
    if (r->result != LEP_RESULT_OK) {
        return len == LEP_LEN_HEADER ? LEP_E_SENSOR : LEP_E_LENGTH;
    }
    if (len != k_response_len[k][0] && len != k_response_len[k][1]) {
        return LEP_E_LENGTH;
    }
    switch (len) {
    case LEP_LEN_HEADER: /* acknowledgement only */
        return LEP_OK;
    case LEP_LEN_FILTER:
        return get_filter(msg, &r->u.filter);
    case LEP_LEN_SAMPLE: /* the handshake sample, or start's data message */
        r->stream = k == I_START;
        return decode_sample(msg, &r->u.sample);
    case LEP_LEN_RATED:
        for (i = 0; i < LEP_AXES; i++) {
            uint32_t bits = get_le(msg + 4 + 4 * i, 4);
            float f;
            if (!rating_bits_ok(bits)) {
                return LEP_E_VALUE;
            }
            memcpy(&f, &bits, sizeof(f));
            r->u.rated.axis[i] = f;
        }
        return LEP_OK;
    default: /* 32 or 38 */
        return decode_info(msg, len, &r->u.info);
    }
}

static int encode_sample(uint8_t *msg, const lep_sample *s)
{
    size_t i;
    for (i = 0; i < LEP_AXES; i++) {
        if (!raw_ok(s->raw[i])) {
            return LEP_E_VALUE;
        }
        put_le(msg + 4 + 2 * i, (uint16_t)s->raw[i], 2);
    }
    put_le(msg + 16, s->reserved, 2);
    msg[18] = s->status;
    return LEP_OK;
}

/* Each value is checked by the rule that decoding applies (rating_bits_ok,
 * raw_ok, printable, LEP_FILTER_MAX), so what decoding would reject,
 * encoding refuses (LEP_E_VALUE); the sensor side needs no decoder. */
static int encode_data(uint8_t *msg, size_t n, const lep_response *r)
{
    const struct text_field *t;
    size_t i;
    switch (n) {
    case LEP_LEN_HEADER:
        return LEP_OK;
    case LEP_LEN_FILTER:
        msg[4] = r->u.filter;
        return r->u.filter <= LEP_FILTER_MAX ? LEP_OK : LEP_E_VALUE;
    case LEP_LEN_SAMPLE: /* the handshake sample or a stream data message */
        return encode_sample(msg, &r->u.sample);
    case LEP_LEN_RATED:
        for (i = 0; i < LEP_AXES; i++) {
            union {
                float f;
                uint32_t bits;
            } v;
            uint32_t bits;
            v.f = r->u.rated.axis[i];
            bits = v.bits;
            if (!rating_bits_ok(bits)) {
                return LEP_E_VALUE;
            }
            put_le(msg + 4 + 4 * i, bits, 4);
        }
        return LEP_OK;
    default: /* 32 or 38 */
        for (t = k_text; t->wire < n; t++) {
            if (!put_text(msg + t->wire, (const char *)&r->u.info + t->at, t->width)) {
                return LEP_E_VALUE;
            }
        }
        return LEP_OK;
    }
}

int lep_response_encode(const lep_response *r, uint8_t *msg, size_t cap, size_t *len)
{
    unsigned k;
    size_t n;
    int rc;
    if (r == NULL || msg == NULL || len == NULL) {
        return LEP_E_ARG;
    }
    *len = 0;
    k = code_index(r->code);
    if (r->result != LEP_RESULT_OK) {
        n = LEP_LEN_HEADER; /* any code: a sensor answers unknown commands with 0x02 */
    } else if (k == N_CODES) {
        return LEP_E_UNEXPECTED;
    } else {
        bool other =
            k == I_INFO ? r->u.info.has_output_rate != 0u : (k == I_START && r->stream != 0u);
        n = k_response_len[k][other ? 1 : 0];
    }
    if (cap < n) {
        return LEP_E_BUFFER;
    }
    put_header(msg, n, r->code, r->result);
    memset(msg + LEP_LEN_HEADER, 0, n - LEP_LEN_HEADER); /* the reserved bytes */
    rc = encode_data(msg, n, r);
    if (rc == LEP_OK) {
        *len = n;
    }
    return rc;
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
    const int16_t *raw;
    const float *axis;
    if (s == NULL || rated == NULL || si == NULL) {
        return;
    }
    for (raw = s->raw, axis = rated->axis; raw < s->raw + LEP_AXES; raw++, axis++) {
        *si++ = (double)*raw * (double)*axis / (double)LEP_RAW_FULL_SCALE;
    }
}

void lep_sample_to_si_f(const lep_sample *s, const lep_rated *rated, float si[LEP_AXES])
{
    const int16_t *raw;
    const float *axis;
    if (s == NULL || rated == NULL || si == NULL) {
        return;
    }
    for (raw = s->raw, axis = rated->axis; raw < s->raw + LEP_AXES; raw++, axis++) {
        *si++ = (float)*raw * *axis / (float)LEP_RAW_FULL_SCALE;
    }
}

uint8_t lep_sample_saturated(const lep_sample *s, int16_t limit)
{
    unsigned mask = 0;
    unsigned i;
    if (s == NULL) {
        return 0;
    }
    for (i = 0; i < LEP_AXES; i++) {
        int32_t v = s->raw[i];
        if ((v < 0 ? -v : v) >= (int32_t)limit) {
            mask |= 1u << i;
        }
    }
    return (uint8_t)mask;
}

/* Entry i of a list of NUL-separated texts. */
static const char *text_at(const char *list, unsigned i)
{
    while (i > 0u) {
        if (*list++ == '\0') {
            i--;
        }
    }
    return list;
}

const char *lep_filter_label(uint8_t code)
{
    return text_at("off\0"
                   "10 Hz\0"
                   "100 Hz\0"
                   "200 Hz\0"
                   "invalid",
                   code > LEP_FILTER_MAX ? LEP_FILTER_MAX + 1u : code);
}

const char *lep_command_name(uint8_t code)
{
    /* in the order of k_codes, then the text for an unknown code */
    return text_at("product info\0"
                   "rated values\0"
                   "filter query\0"
                   "handshake sample\0"
                   "start continuous output\0"
                   "stop continuous output\0"
                   "set filter\0"
                   "unknown",
                   code_index(code));
}
