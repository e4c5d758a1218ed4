/* Host session (OS layer): what a user does with one sensor, written once,
 * callable from any language.
 *
 * Every function here takes and returns handles (lep_session, lep_options),
 * integers, doubles, pointers to flat arrays of those, and NUL-terminated
 * strings: no struct to mirror, no bool. Constants are enumerators; the
 * sizes of the flat arrays are enumerators too (LEP_EVF_COUNT, ...) and
 * functions (lep_session_event_fields(), ...), so a caller built against an
 * older header keeps working: it passes its own (smaller) count and gets the
 * fields it knows. Evolution rule: fields are only ever appended to those
 * arrays and options only added by name; a field's index never changes.
 *
 * A session owns a port (a serial path, or an in-process virtual sensor that
 * it starts and stops) and a client on it. Opening does the start-up
 * recovery (stop a stale stream, drain, identify), reads the rated values
 * and the sensor's filter. While streaming it delivers samples into caller
 * arrays, each with a monotonic arrival time, a UTC time, raw counts,
 * tare-zeroed counts, SI values (tare, host low-pass, payload compensation,
 * decimation, rotation and moment-point shift applied, in that order; then
 * checked against limits), the sensor's status bits and the session's flags.
 * Events (gaps, disconnects, reconnects, tare changes, overload begin/end,
 * limit exceeded/cleared) are queued beside the data.
 *
 * Threads: the driving calls (lep_session_start, _read, _read_one, _stop,
 * and lep_session_set* of "latency") are for one thread at a time. One made
 * while another thread is inside a driving call is refused: it returns
 * LEP_E_STATE at once and changes nothing (no wait, no shared data).
 * lep_session_tare, _untare, _set_tare, _get_tare, _taring, lep_session_set*
 * of the other live options, lep_session_get*, _health, _metadata, _rated,
 * _info and _next_event may be called from any thread at any time before
 * close (a mutex inside the session); they never block on I/O.
 * lep_session_close may be called from another thread while a driving call
 * runs: that call returns LEP_E_STATE within about 50 ms (plus the latency
 * budget; start and stop finish their transaction first) and close waits for
 * it to return before freeing. After close has begun no call may be made
 * (the handle is freed: the caller orders that). The client and the sim
 * (lep_session_client, _sim) belong to the driving thread. Sessions are
 * independent: several in one process just work.
 *
 * Errors are LEP_E_* codes (leptrino/error.h, lep_strerror); functions taking
 * err/errlen also write a one-line message there (naming the port or the
 * option) when err is not NULL. Text results follow the rule of
 * leptrino/options.h: *len gets the length needed, LEP_E_BUFFER when it does
 * not fit. */
#ifndef LEPTRINO_SESSION_H
#define LEPTRINO_SESSION_H

#include <stddef.h>
#include <stdint.h>

#include "client.h"
#include "export.h"
#include "options.h"
#include "serial.h"
#include "sim.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lep_session lep_session;

enum lep_session_constants {
    /* Nominal output rate of the spec when the sensor does not report its own, Hz. */
    LEP_SESSION_NOMINAL_HZ = 1200,
    /* Events kept while nobody takes them; beyond, the oldest is dropped. */
    LEP_SESSION_EVENT_QUEUE = 1024
};

/* Per-sample flags (the flags array of lep_session_read). */
enum lep_sample_flag {
    LEP_SF_GAP = 0x01,      /* a gap (hole, disconnect) lies just before this sample */
    LEP_SF_OVERLOAD = 0x02, /* overload status bit, or an axis at saturation */
    LEP_SF_TARING = 0x04,   /* a tare is averaging this sample (zeroed uses the old offset) */
    LEP_SF_SETTLING = 0x08, /* the host low-pass has not settled since start or a gap */
    LEP_SF_LIMIT = 0x10     /* an SI value is beyond its limit (option "limit") */
};

/* ---- Open, start, stop, close ---- */

/* Open with the options of o (leptrino/options.h: "port", or "sim" = 1 for
 * an in-process virtual sensor configured by the "sim-*" options; the
 * timeouts; the processing). o is copied: it may be freed at once. Start-up
 * recovery, product info, rated values, filter code (a refusal or no answer
 * is not an error: LEP_MD_SENSOR_FILTER = -1). Blocks up to a few answer
 * timeouts. On success *out owns everything; on failure nothing is left
 * open and *out is NULL. LEP_E_ARG for bad options (message in err), the
 * serial/sim/client error otherwise (LEP_E_NOT_FOUND for a missing port,
 * LEP_E_BUSY, LEP_E_PERMISSION, LEP_E_TIMEOUT ...). On success err holds ""
 * or the virtual sensor's warning. */
LEP_API int lep_session_open(const lep_options *o, lep_session **out, char *err, size_t errlen);

/* Stop the stream if running (best effort), close the port, stop the virtual
 * sensor, free. NULL is fine. Safe while another thread is inside a driving
 * call (it returns LEP_E_STATE first; see Threads above); call it once. */
LEP_API void lep_session_close(lep_session *s);

/* Start streaming (resends and recovery as in the client); clears the
 * health counters and sets the start time. LEP_E_STATE when already
 * streaming (or another thread is inside a driving call). */
LEP_API int lep_session_start(lep_session *s);

/* Stop streaming. Samples already received and not yet read are lost. The
 * stop command is sent again once when it gets no answer, except after the
 * stream was lost to silence ("data-timeout"): then one transaction,
 * lep_session_stop_wait(s) at most. */
LEP_API int lep_session_stop(lep_session *s);

/* How long one stop transaction may wait for a sensor that does not answer,
 * s: (retries + 1) x timeout, from the session's own options ("retries",
 * "timeout"). After LEP_E_LOST, lep_session_stop waits this long at most (a
 * front end says so before it stops a sensor that went quiet); otherwise it
 * may try twice. 0 for NULL. Any thread. */
LEP_API double lep_session_stop_wait(const lep_session *s);

/* 1 while streaming, 0 otherwise (and for NULL). */
LEP_API int lep_session_streaming(const lep_session *s);

/* ---- Samples ---- */

/* Read up to cap samples into caller arrays, from index 0; *n gets how many
 * were written (always, whatever the return). Every array may be NULL to
 * skip that column; the others must hold cap (t_mono, t_utc, status, flags,
 * seq) or cap * 6 (si, raw, zeroed: row-major, fx fy fz mx my mz) elements:
 *   t_mono  s, the monotonic clock (lep_monotonic_seconds) at arrival
 *   t_utc   s since 1970-01-01 UTC, the same instant on the wall clock
 *   si      N, N m: zeroed, low-passed, compensated, decimated, rotated, shifted
 *   raw     counts as received
 *   zeroed  raw - tare offset, counts
 *   status  the sensor's status bits (LEP_STATUS_*)
 *   flags   LEP_SF_*
 *   seq     the two reserved bytes (leptrino-sim's sequence number)
 * Waits up to timeout_ms (< 0 forever) for the first sample; then returns
 * when cap are written, or at once when the latency budget ("latency") is
 * 0, or when the budget since the first new sample's arrival has run out.
 * Returns LEP_OK when at least one sample was written or an event was
 * queued; LEP_E_TIMEOUT when nothing came within timeout_ms, and only then:
 * the stream may still come (a front end waits again); LEP_E_LOST when the
 * stream is lost: without "reconnect", after "data-timeout" without a sample
 * (LEP_EV_DISCONNECTED with error LEP_E_TIMEOUT is queued), then and on
 * every later call until stop: a front end gives up on LEP_E_LOST, never on
 * LEP_E_TIMEOUT; LEP_E_END once "duration" or "count" is reached (the
 * samples up to the limit are written first); LEP_E_DISCONNECTED when the
 * port went away without reconnect, or "reconnect-give-up" passed (then and
 * on later calls); LEP_E_UNEXPECTED when a reconnect found another sensor
 * (model or serial differ); LEP_E_STATE when not streaming, when another
 * thread is inside a driving call, or when lep_session_close began in
 * another thread; LEP_E_ARG for NULL s or n. Samples are never lost across
 * calls: what does not fit waits for the next call. LEP_E_END and the errors
 * may come with samples (*n > 0): use them. cap 0 returns LEP_OK at once.
 * Times of samples that one port read brought together are reconstructed
 * (docs/session.md). */
LEP_API int lep_session_read(lep_session *s, int timeout_ms, size_t cap, size_t *n, double *t_mono,
                             double *t_utc, double *si, int16_t *raw, double *zeroed,
                             uint8_t *status, uint8_t *flags, uint16_t *seq);

/* One sample in handshake mode (command 0x30), outside the stream, into the
 * same arrays as lep_session_read with room for one sample (any may be
 * NULL): raw counts, zeroed with the tare offsets in force, SI values through
 * the rated values, payload compensation, rotation and moment-point shift in
 * force, the status bits, LEP_SF_OVERLOAD when the sensor reports overload
 * or an axis is at saturation, the times when the answer arrived. The host
 * low-pass, decimation and tare averaging do not apply; no event is queued
 * and the health counters do not change. Blocks for one transaction.
 * LEP_OK; LEP_E_STATE while streaming or while another thread is inside a
 * driving call; LEP_E_DISCONNECTED while disconnected; the client's error
 * otherwise (arrays unchanged). */
LEP_API int lep_session_read_one(lep_session *s, double *t_mono, double *t_utc, double *si,
                                 int16_t *raw, double *zeroed, uint8_t *status, uint8_t *flags,
                                 uint16_t *seq);

/* ---- Events ---- */

enum lep_session_event_type {
    LEP_EV_GAP = 1,          /* a hole in the data: lost samples, a stall, a stolen read */
    LEP_EV_DISCONNECTED = 2, /* the port went away or the data timed out (error says which) */
    LEP_EV_RECONNECTED = 3,  /* the stream runs again after a disconnect */
    LEP_EV_TARE = 4,         /* the tare offsets changed (tare done, untare, set) */
    LEP_EV_OVERLOAD_BEGIN = 5,
    LEP_EV_OVERLOAD_END = 6,
    LEP_EV_LIMIT_EXCEEDED = 7, /* an SI value went beyond its limit (axes: which) */
    LEP_EV_LIMIT_CLEARED = 8   /* every SI value is back within 95 % of its limit */
};

/* The fields of an event, as indices into the array lep_session_next_event
 * fills (every field a double; integers are exact). */
enum lep_event_field {
    LEP_EVF_TYPE = 0,     /* enum lep_session_event_type */
    LEP_EVF_SAMPLE = 1,   /* its row in the stream: the samples lep_session_read returned
                             before it since lep_session_start; 0 for an event queued
                             before that start or while stopped (an untare) */
    LEP_EVF_T_MONO = 2,   /* when, monotonic s */
    LEP_EVF_T_UTC = 3,    /* when, UTC s */
    LEP_EVF_GAP_FROM = 4, /* GAP/RECONNECTED: arrival of the last sample before (mono s);
                             DISCONNECTED: the same, the last sample received */
    LEP_EVF_GAP_TO = 5,   /* ... and of the first after */
    LEP_EVF_LOST = 6,     /* GAP: samples estimated lost */
    LEP_EVF_ERROR = 7,    /* DISCONNECTED and RECONNECTED: LEP_E_DISCONNECTED or
                             LEP_E_TIMEOUT; 0 otherwise */
    LEP_EVF_AXES = 8,     /* OVERLOAD_*, LIMIT_*: bit i = axis i */
    LEP_EVF_STATUS = 9,   /* OVERLOAD_*: the sensor's status bits */
    LEP_EVF_TARE = 10,    /* TARE: 6 fields, the offsets now in force (counts; 0 untared) */
    LEP_EVF_WRENCH = 16,  /* LIMIT_*: 6 fields, the sample's SI values (N, N m) */
    LEP_EVF_ROW = 22,     /* its row in the batch of the last lep_session_read: the index
                             in that call's arrays of the first sample after it (SAMPLE
                             less the samples returned before that call). Taken after a
                             read and before the next: 0 .. n of that read (n: after its
                             last row); negative when it lay in an earlier batch. While
                             stopped: SAMPLE. A front end that takes the events after
                             each read puts them at its own row count before the read
                             plus ROW, with no count of the library's. */
    LEP_EVF_COUNT = 23
};

/* Number of event fields this library fills (LEP_EVF_COUNT of its header). */
LEP_API size_t lep_session_event_fields(void);

/* Take the oldest queued event into fields[0..nfields) (the first
 * min(nfields, lep_session_event_fields()) fields, see enum lep_event_field).
 * Returns 1 when an event was taken, 0 when none is queued, LEP_E_ARG for
 * NULL s or fields. A full queue drops its oldest to take a new one
 * (LEP_H_EVENTS_DROPPED). While streaming, an event is returned once
 * lep_session_read has returned the samples before it (its sample field <=
 * the samples read so far); stopped, every queued event is returned. Where
 * it lies: LEP_EVF_SAMPLE in the stream, LEP_EVF_ROW in the last batch. */
LEP_API int lep_session_next_event(lep_session *s, double *fields, size_t nfields);

/* ---- Tare ---- */

/* Average the raw counts of the next `samples` samples (or of duration_s
 * seconds when samples is 0) while the stream goes on, then make the mean
 * the offset and queue LEP_EV_TARE. Replaces a tare in progress. LEP_E_ARG
 * when both are 0 or negative. Usable before start (it begins with the
 * stream). With a payload set, the tare removes the bias only
 * (docs/session.md). */
LEP_API int lep_session_tare(lep_session *s, int samples, double duration_s);
/* Zero offsets (queues LEP_EV_TARE; cancels a tare in progress). */
LEP_API int lep_session_untare(lep_session *s);
/* Set the offsets in counts (queues LEP_EV_TARE). LEP_E_ARG for NULL or
 * non-finite values. */
LEP_API int lep_session_set_tare(lep_session *s, const double offset[6]);
/* Current offsets into offset[6] (may be NULL); returns 1 when a tare is in
 * force, 0 when not, LEP_E_ARG for NULL s. */
LEP_API int lep_session_get_tare(lep_session *s, double offset[6]);
/* 1 while a tare is averaging, else 0. */
LEP_API int lep_session_taring(lep_session *s);

/* ---- Options of an open session ---- */

/* Change an option while the session is open, as lep_options_set* do on a
 * handle (same names, types, checks and messages). Only the options of scope
 * LEP_SCOPE_LIVE may change: "lowpass" (0 = off; above 0.45 x the nominal
 * rate is refused: LEP_E_VALUE), "rotation" and "shift" (a matrix that is
 * not orthonormal to 1e-6 is refused: LEP_E_VALUE), "payload", "gravity",
 * "limit", and "latency" (from the thread that reads: a driving call).
 * Another option gives LEP_E_STATE ("... cannot change on an open
 * session"). They apply to samples received after the call: up to one
 * read's worth already received keeps the old setting. */
LEP_API int lep_session_set(lep_session *s, const char *name, const char *value, char *err,
                            size_t errlen);
LEP_API int lep_session_set_int(lep_session *s, const char *name, int64_t value, char *err,
                                size_t errlen);
LEP_API int lep_session_set_double(lep_session *s, const char *name, double value, char *err,
                                   size_t errlen);
LEP_API int lep_session_set_doubles(lep_session *s, const char *name, const double *values,
                                    size_t n, char *err, size_t errlen);
/* Read any option as the session uses it now (the live ones as last set
 * through lep_session_set*; "port" the path opened). As lep_options_get*. */
LEP_API int lep_session_get(lep_session *s, const char *name, char *buf, size_t cap, size_t *len);
LEP_API int lep_session_get_int(lep_session *s, const char *name, int64_t *out);
LEP_API int lep_session_get_double(lep_session *s, const char *name, double *out);
LEP_API int lep_session_get_doubles(lep_session *s, const char *name, double *out, size_t cap,
                                    size_t *n);

/* Limits as text, the `--limit` syntax of the leptrino tool and the bridge:
 * AXIS=VALUE pairs separated by commas, AXIS one of fx fy fz mx my mz, VALUE
 * a finite number > 0 (N, N m), e.g. "fz=50,mz=2". Fills limit[6] (axes not
 * named set to 0: none). LEP_E_ARG for NULL or malformed text, or an axis
 * named twice (limit then untouched). The option "limit" takes this text too.
 * Re-entrant, no allocation. */
LEP_API int lep_limits_parse(const char *text, double limit[6]);

/* Several limit texts (a repeated --limit): add the axes of text to those
 * limit[6] holds already (0: none). The one merge rule: the axes add up, and
 * an axis limited twice (already in limit, or named twice in text) is
 * refused rather than one value dropped: LEP_E_ARG, limit untouched (so
 * "fz=50" then "mz=2" is "fz=50,mz=2"; "fz=50" then "fz=60" is an error).
 * LEP_E_ARG too for NULL, malformed text, or a negative or non-finite value
 * in limit. lep_limits_parse is this on six zeros. */
LEP_API int lep_limits_add(const char *text, double limit[6]);

/* Rotation matrix (row-major, 9 doubles) from roll, pitch, yaw in radians
 * (R = Rz(yaw) Ry(pitch) Rx(roll)), for the option "rotation". */
LEP_API void lep_rotation_from_rpy(double roll, double pitch, double yaw, double r[9]);

/* ---- Identity, health, metadata ---- */

/* Texts of lep_session_info. */
enum lep_session_text {
    LEP_INFO_MODEL = 0,           /* product info: model ("PFS055YA501U6") */
    LEP_INFO_SERIAL = 1,          /* serial number */
    LEP_INFO_FIRMWARE = 2,        /* firmware version ("1.13") */
    LEP_INFO_OUTPUT_RATE = 3,     /* the output-rate field as sent, "" in the 32-byte form */
    LEP_INFO_PROTOCOL = 4,        /* "v1.13 (32-byte info)" or "rate field (38-byte)" */
    LEP_INFO_FILTER_LABEL = 5,    /* the sensor filter's label, or "not supported by sensor" */
    LEP_INFO_LOWPASS_NAME = 6,    /* the host low-pass filter's name, "" when off */
    LEP_INFO_PORT = 7,            /* the port's path */
    LEP_INFO_LIBRARY_VERSION = 8, /* lep_version() */
    LEP_INFO_METADATA_JSON = 9,   /* the metadata as one JSON object (no newline): every
                                     front end writes this same object */
    LEP_INFO_COUNT = 10
};

/* A text about the session into buf (the text rule of leptrino/options.h).
 * LEP_E_ARG for NULL s or an unknown which. */
LEP_API int lep_session_info(lep_session *s, int which, char *buf, size_t cap, size_t *len);

/* The rated values into rated[6]: Fx Fy Fz in N, Mx My Mz in N m. LEP_E_ARG
 * for NULL. */
LEP_API int lep_session_rated(lep_session *s, double rated[6]);

/* Health since lep_session_start, as indices into the array
 * lep_session_health fills (every field a double; counts are exact). */
enum lep_health_field {
    LEP_H_ELAPSED_S = 0,   /* from the first sample to the last */
    LEP_H_NOMINAL_HZ = 1,  /* the nominal rate ("nominal-rate", else the sensor's) */
    LEP_H_MEASURED_HZ = 2, /* (samples received - 1) / elapsed (before decimation) */
    LEP_H_RECENT_HZ = 3,   /* over the last second or so */
    LEP_H_SHORTFALL = 4,   /* 1 when measured below 98 % of nominal over >= 1 s */
    LEP_H_RECEIVED = 5,    /* samples received (tare samples included) */
    LEP_H_DELIVERED = 6,   /* samples returned by lep_session_read (after decimation) */
    LEP_H_LOST = 7,        /* samples estimated lost in gaps */
    LEP_H_GAPS = 8,
    LEP_H_ERRORS = 9,          /* framing, BCC, invalid messages, timeouts (all connections) */
    LEP_H_OVERLOADS = 10,      /* overload episodes begun */
    LEP_H_LIMIT_EPISODES = 11, /* limit episodes begun */
    LEP_H_DISCONNECTS = 12,
    LEP_H_RECONNECTS = 13,
    LEP_H_EVENTS_DROPPED = 14, /* events pushed out of the full queue */
    LEP_H_MAX_GAP_S = 15,
    /* The current connection's client counters (leptrino/client.h, lep_client_stats): */
    LEP_H_MESSAGES = 16,
    LEP_H_BCC_ERRORS = 17,
    LEP_H_FRAME_ERRORS = 18,
    LEP_H_BYTES_DISCARDED = 19,
    LEP_H_NAKS = 20,
    LEP_H_RETRIES = 21,
    LEP_H_UNEXPECTED = 22,
    LEP_H_INVALID = 23,
    LEP_H_TIMEOUTS = 24,
    LEP_H_SAMPLES = 25,
    LEP_H_RESENT_AFTER_TIMEOUT = 26,
    LEP_H_RESENT_CONFIRMED = 27,
    LEP_H_RECOVERIES = 28,
    LEP_H_RESERVED_NONZERO = 29,
    LEP_H_STALLS = 30,
    LEP_H_COUNT = 31
};

/* Number of health fields this library fills. */
LEP_API size_t lep_session_health_fields(void);
/* Name of health field i ("received", "bcc_errors", ...), NULL past the end. */
LEP_API const char *lep_session_health_field_name(size_t i);
/* One consistent snapshot of the first min(n, lep_session_health_fields())
 * fields into out. LEP_OK, LEP_E_ARG for NULL. */
LEP_API int lep_session_health(lep_session *s, double *out, size_t n);

/* Numbers of what a recording says about itself, as indices into the array
 * lep_session_metadata fills (texts: lep_session_info). */
enum lep_metadata_field {
    LEP_MD_RATED = 0,          /* 6 fields: rated values, N and N m */
    LEP_MD_OUTPUT_RATE_HZ = 6, /* the output-rate field as a number, 0 when absent */
    LEP_MD_SENSOR_FILTER = 7,  /* the sensor's filter code, -1 when it refused */
    LEP_MD_NOMINAL_HZ = 8,
    LEP_MD_LOWPASS_HZ = 9,       /* host low-pass cut-off, 0 off */
    LEP_MD_LOWPASS_DELAY_S = 10, /* its group delay at low frequency */
    LEP_MD_DECIMATE = 11,
    LEP_MD_ROTATION = 12,          /* 9 fields, row-major */
    LEP_MD_SHIFT_M = 21,           /* 3 fields */
    LEP_MD_TARED = 24,             /* 1 when a tare is in force */
    LEP_MD_TARE = 25,              /* 6 fields, counts */
    LEP_MD_START_UTC = 31,         /* UTC s of the last start (of open before one) */
    LEP_MD_START_MONO = 32,        /* monotonic s of the same instant */
    LEP_MD_SIM = 33,               /* 1 for an in-process virtual sensor */
    LEP_MD_PAYLOAD = 34,           /* 4 fields: mass kg, centre of mass x y z m; mass 0: none */
    LEP_MD_GRAVITY = 38,           /* 3 fields, m/s^2, sensor frame */
    LEP_MD_LIMIT = 41,             /* 6 fields, N and N m, 0: none */
    LEP_MD_OUTPUT_RATE_FIELD = 47, /* 1 when the sensor answered product info in the 38-byte
                                      form (with the output-rate field), 0 in the 32-byte */
    LEP_MD_COUNT = 48
};

/* Number of metadata fields this library fills. */
LEP_API size_t lep_session_metadata_fields(void);
/* The first min(n, lep_session_metadata_fields()) fields into out. LEP_OK,
 * LEP_E_ARG for NULL. */
LEP_API int lep_session_metadata(lep_session *s, double *out, size_t n);

/* ---- The port ---- */

/* The client, for commands the session does not wrap (filter set); do not
 * start or stop the stream through it. NULL while disconnected. */
LEP_API lep_client *lep_session_client(lep_session *s);
/* The virtual sensor when "sim" = 1, else NULL (for fault injection). */
LEP_API lep_sim *lep_session_sim(lep_session *s);
/* The port's path (static for the life of s). */
LEP_API const char *lep_session_port(const lep_session *s);
/* The fd to poll for input (-1 while disconnected). */
LEP_API int lep_session_fd(const lep_session *s);

/* What the serial port of the current connection applied for latency
 * (leptrino/serial.h, enum lep_serial_info_field): the first
 * min(n, LEP_SERIAL_INFO_COUNT) fields into out. LEP_E_DISCONNECTED while
 * disconnected (out zeroed), LEP_E_ARG for NULL. Driving thread. */
LEP_API int lep_session_serial_info(lep_session *s, int *out, size_t n);

#ifdef __cplusplus
}
#endif

#endif
