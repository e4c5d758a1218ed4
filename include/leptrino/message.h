/* Message codec (spec 3-7): typed commands and responses, both directions.
 *
 * Works on unstuffed messages (Length .. end of Data); see frame.h for the
 * wire framing. Host side: lep_command_encode, lep_response_decode. Sensor
 * side: lep_command_decode, lep_response_encode. Pure functions.
 * NULL arguments as leptrino.h says. */
#ifndef LEPTRINO_MESSAGE_H
#define LEPTRINO_MESSAGE_H

#include <stddef.h>
#include <stdint.h>

#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Command codes (spec 4); a response carries the code it answers. */
enum lep_command_code {
    LEP_CMD_PRODUCT_INFO = 0x2A,
    LEP_CMD_RATED = 0x2B,
    LEP_CMD_FILTER_GET = 0xB6,
    LEP_CMD_SAMPLE = 0x30,
    LEP_CMD_START = 0x32,
    LEP_CMD_STOP = 0x33,
    LEP_CMD_FILTER_SET = 0xA6
};

enum lep_axis { LEP_FX = 0, LEP_FY, LEP_FZ, LEP_MX, LEP_MY, LEP_MZ, LEP_AXES };

/* Message lengths fixed by the spec, in bytes (Length .. end of Data). */
enum lep_message_length {
    LEP_LEN_HEADER = 4,             /* a message with no data (commands, acknowledgements) */
    LEP_LEN_FILTER_SET_CMD = 8,     /* the filter-set command (0xA6) */
    LEP_LEN_PRODUCT_INFO = 32,      /* product information, v1.13 form */
    LEP_LEN_PRODUCT_INFO_RATE = 38, /* product information with the output rate */
    LEP_LEN_RATED = 28,             /* rated values */
    LEP_LEN_FILTER = 8,             /* the answer to a filter query (0xB6) */
    LEP_LEN_SAMPLE = 20             /* a sample (handshake or stream) */
};

/* Status bits of a sample (spec 6.1); 1 = fault. */
enum lep_status_bit {
    LEP_STATUS_CALIBRATION = 0x01,  /* calibration data in ROM corrupt */
    LEP_STATUS_SENSOR_FAULT = 0x02, /* sensor error */
    LEP_STATUS_OVERLOAD = 0x04      /* load beyond rating detected */
};

/* Raw scale: +/-10000 counts = +/- rated value; and the saturation magnitude
 * of v1.13 firmware, and as reported for later firmware. */
enum lep_raw_scale {
    LEP_RAW_FULL_SCALE = 10000,  /* counts at the rated value */
    LEP_SATURATION_V113 = 32000, /* saturation magnitude of v1.13 firmware */
    LEP_SATURATION_LATER = 15000 /* saturation magnitude as reported for later firmware */
};

/* Highest filter code of the spec (0 off, 1..3 FIR cut-offs). */
enum lep_filter_limit { LEP_FILTER_MAX = 3 };

/* Widths of the product-information text fields, in characters (without the
 * terminating NUL of lep_product_info's arrays). */
enum lep_info_length {
    LEP_MODEL_LEN = 16,
    LEP_SERIAL_LEN = 8,
    LEP_FIRMWARE_LEN = 4,
    LEP_RATE_LEN = 6
};

/* A command. filter is used by LEP_CMD_FILTER_SET only. */
typedef struct lep_command {
    uint8_t code;
    uint8_t filter;
} lep_command;

/* Product information (0x2A). Fields are printable ASCII (0x20..0x7E),
 * NUL-terminated, with the padding (trailing spaces and NULs) removed;
 * encoding pads them with spaces again. Decoding rejects (LEP_E_VALUE) a field
 * with any other byte before its padding (a control byte, a byte >= 0x80, a
 * NUL followed by text); encoding rejects a non-printable or too long field.
 * The serial is digits on v1.13 ("00000000".."99999999"); seven digits padded
 * with a space or a NUL are accepted as sent. */
typedef struct lep_product_info {
    char model[LEP_MODEL_LEN + 1];
    char serial[LEP_SERIAL_LEN + 1];
    char firmware[LEP_FIRMWARE_LEN + 1];
    char output_rate[LEP_RATE_LEN + 1]; /* empty in the 32-byte v1.13 form */
    uint8_t has_output_rate;            /* 1 for the 38-byte form, else 0 */
    uint32_t output_rate_hz;            /* output_rate as a number, 0 if absent or not numeric */
} lep_product_info;

/* Rated (full-scale) values (0x2B): Fx Fy Fz [N], Mx My Mz [N m]; finite, > 0. */
typedef struct lep_rated {
    float axis[LEP_AXES];
} lep_rated;

/* One sample (0x30 answer or 0x32 continuous data). The last reserved byte
 * of the message ("0x00 fixed" in v1.13, unspecified on later firmware) is
 * accepted with any value and not kept (the client counts non-zero ones). */
typedef struct lep_sample {
    int16_t raw[LEP_AXES]; /* counts: +/-10000 = +/- rated; |raw| <= 32000 (else LEP_E_VALUE) */
    uint16_t reserved; /* the two undefined bytes (LE); leptrino-sim puts a sequence number here */
    uint8_t status;    /* LEP_STATUS_* bits */
} lep_sample;

/* A response. Which member of u is valid depends on code, result and stream. */
typedef struct lep_response {
    uint8_t code;   /* LEP_CMD_* answered */
    uint8_t result; /* LEP_RESULT_*; when non-zero the message had no data */
    uint8_t stream; /* 1: a continuous-output data message (code 0x32, 20 bytes), else 0 */
    union {
        lep_product_info info; /* LEP_CMD_PRODUCT_INFO */
        lep_rated rated;       /* LEP_CMD_RATED */
        uint8_t filter;        /* LEP_CMD_FILTER_GET */
        lep_sample sample;     /* LEP_CMD_SAMPLE, or stream data */
    } u;
} lep_response;

/* Host side: encode cmd into msg[0..cap). Errors, in this order: LEP_E_ARG
 * (a NULL argument), LEP_E_UNEXPECTED (unknown code), LEP_E_VALUE (filter
 * code > 3), LEP_E_BUFFER; *len is 0 on failure (when len is not NULL). The
 * bytes are lep_command_frame's without the framing. */
LEP_API int lep_command_encode(const lep_command *cmd, uint8_t *msg, size_t cap, size_t *len);

/* Sensor side: decode a command message. On failure returns LEP_E_LENGTH,
 * LEP_E_RESERVED, LEP_E_UNEXPECTED or LEP_E_VALUE and sets *result to the
 * result code a sensor answers with (LEP_RESULT_LENGTH, _UNDEFINED, _VALUE);
 * cmd->code holds msg[2] whenever len >= 3 (else 0: nothing to answer). */
LEP_API int lep_command_decode(const uint8_t *msg, size_t len, lep_command *cmd, uint8_t *result);

/* Host side: decode and validate a response message. Returns LEP_OK;
 * LEP_E_SENSOR for a well-formed answer with a non-zero result (r->code and
 * r->result set); LEP_E_LENGTH, LEP_E_RESERVED, LEP_E_UNEXPECTED (unknown
 * code) or LEP_E_VALUE (non-finite or non-positive rating, filter code > 3,
 * |raw| > 32000, product-info text that is not printable ASCII + padding). */
LEP_API int lep_response_decode(const uint8_t *msg, size_t len, lep_response *r);

/* Sensor side: encode r into msg[0..cap). A non-zero result gives the 4-byte
 * form (for any code, so unknown commands can be answered). Errors: LEP_E_ARG,
 * LEP_E_UNEXPECTED (unknown code with result 0), LEP_E_VALUE (what decoding
 * would reject: a bad rating or filter code, |raw| > 32000, text that is not
 * printable ASCII or too long), LEP_E_BUFFER. */
LEP_API int lep_response_encode(const lep_response *r, uint8_t *msg, size_t cap, size_t *len);

/* Encode straight to a wire frame (message codec + frame codec). Errors as
 * the encoders', and LEP_E_BUFFER when the frame does not fit; *len is 0 on
 * failure. lep_command_frame writes the frame itself (a command holds no
 * DLE, so nothing is stuffed) and needs no frame encoder. */
LEP_API int lep_command_frame(const lep_command *cmd, uint8_t *out, size_t cap, size_t *len);
LEP_API int lep_response_frame(const lep_response *r, uint8_t *out, size_t cap, size_t *len);

/* physical = raw * rated / 10000, per axis, into si[6] (N, N m). */
LEP_API void lep_sample_to_si(const lep_sample *s, const lep_rated *rated, double si[LEP_AXES]);

/* The same in single precision, for MCUs whose FPU (or budget) has no double. */
LEP_API void lep_sample_to_si_f(const lep_sample *s, const lep_rated *rated, float si[LEP_AXES]);

/* Bit i set when |raw[i]| >= limit (LEP_SATURATION_V113 or _LATER). */
LEP_API uint8_t lep_sample_saturated(const lep_sample *s, int16_t limit);

/* Static label of a filter code per spec v1.13 ("off", "10 Hz", "100 Hz",
 * "200 Hz"; "invalid" otherwise). The code is the truth; models differ. */
LEP_API const char *lep_filter_label(uint8_t code);

/* Static name of a command code ("product info", ...; "unknown"). */
LEP_API const char *lep_command_name(uint8_t code);

#ifdef __cplusplus
}
#endif

#endif
