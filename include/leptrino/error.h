/* Error codes shared by every layer of leptrino.
 *
 * 0 is success; library failures are negative LEP_E_* values. A sensor that
 * answers with a non-zero result code yields LEP_E_SENSOR, and the code itself
 * (LEP_RESULT_*) is kept apart so it is never confused with a library error. */
#ifndef LEPTRINO_ERROR_H
#define LEPTRINO_ERROR_H

#include <stdint.h>

#include "config.h"
#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

enum lep_error {
    LEP_OK = 0,
    LEP_E_ARG = -1,           /* invalid argument (NULL pointer, out-of-range value) */
    LEP_E_BUFFER = -2,        /* caller buffer too small */
    LEP_E_TOO_LONG = -3,      /* message longer than 128 bytes */
    LEP_E_BCC = -4,           /* frame check byte mismatch */
    LEP_E_ESCAPE = -5,        /* illegal byte after DLE inside a frame */
    LEP_E_LENGTH = -6,        /* Length field or message size wrong for its type */
    LEP_E_RESERVED = -7,      /* reserved byte does not hold its fixed value */
    LEP_E_UNEXPECTED = -8,    /* unknown code, or a message of the wrong type */
    LEP_E_VALUE = -9,         /* field value invalid (non-finite rating, bad filter code) */
    LEP_E_SENSOR = -10,       /* sensor answered with a non-zero result code */
    LEP_E_NAK = -11,          /* sensor kept answering DLE NAK past the retry limit */
    LEP_E_TIMEOUT = -12,      /* no answer within the timeout */
    LEP_E_IO = -13,           /* read or write failed */
    LEP_E_DISCONNECTED = -14, /* the port went away (hang-up, device unplugged) */
    LEP_E_BUSY = -15,         /* port already in use by another program */
    LEP_E_NOT_FOUND = -16,    /* no such port */
    LEP_E_PERMISSION = -17,   /* no permission to open the port */
    LEP_E_NOT_TTY = -18,      /* path is not a terminal device */
    LEP_E_STATE = -19,        /* call not valid in the client's current state */
    LEP_E_NO_SYNC = -20,      /* the line never went quiet during recovery */
    LEP_E_UNSUPPORTED = -21,  /* not supported on this platform or port */
    LEP_E_END = -22,          /* a session reached its duration or count (not a failure) */
    LEP_E_STALLED = -23,      /* streaming, but no sample within the watchdog time */
    LEP_E_LOST = -24          /* a session's stream is lost (no data for its data timeout) */
};

/* Sensor result codes (spec 3.2.1). */
enum lep_result {
    LEP_RESULT_OK = 0x00,
    LEP_RESULT_LENGTH = 0x01,    /* length error */
    LEP_RESULT_UNDEFINED = 0x02, /* undefined command */
    LEP_RESULT_VALUE = 0x03,     /* invalid setting value */
    LEP_RESULT_STATE = 0x04      /* state error */
};

/* Static, never-NULL description of a LEP_E_* code (or "unknown error");
 * "" when built with LEP_CONFIG_NO_ERROR_STRINGS. */
LEP_API const char *lep_strerror(int err);

/* Static, never-NULL meaning of a sensor result code (or "unknown result
 * code"); "" when built with LEP_CONFIG_NO_ERROR_STRINGS. */
LEP_API const char *lep_result_str(uint8_t result);

#ifdef __cplusplus
}
#endif

#endif
