/* Host session (OS layer): what a user does with one sensor, written once.
 *
 * A session owns a port (a serial path, or an in-process virtual sensor that
 * it starts and stops) and a client on it. Opening does the start-up
 * recovery (stop a stale stream, drain, identify), reads the rated values
 * and the sensor's filter. While streaming it delivers samples in batches of
 * plain C arrays (struct of arrays, so bindings hand them to numpy without
 * per-sample work), each with a monotonic arrival time, a UTC time, raw
 * counts, tare-zeroed counts, SI values (tare, host low-pass, payload
 * compensation, decimation, rotation and moment-point shift applied, in that
 * order; then checked against limits), the sensor's status bits and the
 * session's flags. Events (gaps, disconnects, reconnects, tare changes,
 * overload begin/end, limit exceeded/cleared) are queued beside the data.
 *
 * Threads: the driving calls (lep_session_start, _read, _read_one, _stop,
 * _set_latency) are for one thread at a time. One made while another thread
 * is inside a driving call is refused: it returns LEP_E_STATE at once and
 * changes nothing (no wait, no shared data). lep_session_tare, _untare,
 * _set_tare, _get_tare, _taring, _set_lowpass, _set_rotation, _set_payload,
 * _set_gravity, _set_limits, _get_health, _get_metadata, _metadata_json and
 * _next_event may be called from any thread at any time before close (a
 * mutex inside the session); they never block on I/O. lep_session_close may
 * be called from another thread while a driving call runs: that call returns
 * LEP_E_STATE within about 50 ms (plus the latency budget; start and stop
 * finish their transaction first) and close waits for it to return before
 * freeing. After close has begun no call may be made (the handle is freed:
 * the caller orders that, as Python's Sensor does). The client and the sim
 * (lep_session_client, _sim) belong to the driving thread. Sessions are
 * independent: several in one process just work.
 *
 * Errors are LEP_E_* codes (leptrino/error.h); functions taking err/errlen
 * also write a one-line message there (naming the port) when err is not NULL. */
#ifndef LEPTRINO_SESSION_H
#define LEPTRINO_SESSION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "client.h"
#include "export.h"
#include "message.h"
#include "payload.h"
#include "serial.h"
#include "sim.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lep_session lep_session;

/* Nominal output rate of the spec when the sensor does not report its own. */
#define LEP_SESSION_NOMINAL_HZ 1200.0

/* Options; start from lep_session_options_init(). Copied at open. */
typedef struct lep_session_options {
    /* ---- the port ---- */
    const char *port;    /* serial port path (used when use_sim is false) */
    bool use_sim;        /* start an in-process virtual sensor with sim instead */
    lep_sim_options sim; /* its options (lep_sim_options_init'ed by default) */
    /* ---- start-up and transactions ---- */
    int timeout_ms;    /* answer timeout per attempt, default 500 */
    int sync_quiet_ms; /* quiet time that ends the start-up drain, default 30 */
    /* ---- stream ---- */
    int data_timeout_ms;      /* no sample for this long while streaming: a disconnect
                                (reconnect) or LEP_E_TIMEOUT, default 2000 */
    double gap_periods;       /* a hole longer than this many nominal periods is a gap, default 3 */
    double nominal_hz;        /* 0 (default): the sensor's output-rate field, else the virtual
                                sensor's rate_hz with use_sim, else 1200 */
    bool reconnect;           /* after a disconnect or data timeout, reopen with backoff,
                                re-sync and restart the stream (default false) */
    int reconnect_min_ms;     /* backoff from ... (default 100) */
    int reconnect_max_ms;     /* ... doubling up to this (default 1000) */
    int reconnect_give_up_ms; /* give up after this long without the sensor, < 0 never (default) */
    int latency_ms;           /* latency budget: how long delivery may hold samples back to
                                save wake-ups; 0 (default) delivers as soon as a read returns */
    /* ---- processing (all can be changed later except tare_samples) ---- */
    unsigned tare_samples; /* tare over the first N samples after start; they are not
                                delivered (0 = none) */
    double lowpass_hz;     /* host low-pass cut-off on SI values, 0 = off */
    unsigned decimate;     /* deliver every Nth sample (after the low-pass), default 1 */
    double rotation[9];    /* row-major R: output force = R f, moment = R m (identity) */
    double shift_m[3];     /* moment reference point, in the output frame, metres: the
                                moment about it is m' - r x f' (default 0) */
    /* ---- end of stream ---- */
    double duration_s; /* lep_session_read gives LEP_E_END after this long from the
                                first delivered sample's arrival, 0 = none */
    uint64_t count;    /* ... or after this many samples delivered, 0 = none */
    /* ---- payload and limits (added later; all can be changed while streaming) ---- */
    lep_payload payload;    /* the tool on the sensor (leptrino/payload.h): its gravity wrench
                               at `gravity` is removed from the SI values; mass 0 (default):
                               none */
    double gravity[3];      /* gravity in the sensor frame, m/s^2, default (0, 0, -9.80665) */
    double limit[LEP_AXES]; /* per axis, N and N m: an SI value (compensated, in the output
                               frame) beyond +/- limit is a limit episode; 0 (default): none */
} lep_session_options;

/* Per-sample flags (lep_session_batch.flags). */
#define LEP_SF_GAP 0x01u      /* a gap (hole, disconnect) lies just before this sample */
#define LEP_SF_OVERLOAD 0x02u /* overload status bit, or an axis at saturation */
#define LEP_SF_TARING 0x04u   /* a tare is averaging this sample (zeroed uses the old offset) */
#define LEP_SF_SETTLING 0x08u /* the host low-pass has not settled since start or a gap */
#define LEP_SF_LIMIT 0x10u    /* an SI value is beyond its limit (lep_session_set_limits) */

/* Destination arrays, caller-owned. Every pointer may be NULL to skip that
 * column. lep_session_read appends from n up to cap. */
typedef struct lep_session_batch {
    size_t cap;      /* capacity in samples */
    size_t n;        /* samples filled so far */
    double *t_mono;  /* [cap] s, lep_monotonic_seconds() when the read delivering it returned */
    double *t_utc;   /* [cap] s since 1970-01-01 UTC, the same instant on the wall clock */
    int16_t *raw;    /* [cap*6] counts as received */
    double *zeroed;  /* [cap*6] raw - tare offset, counts */
    double *si;      /* [cap*6] N, N m: zeroed, low-passed, decimated, rotated, shifted */
    uint8_t *status; /* [cap] the sensor's LEP_STATUS_* bits */
    uint8_t *flags;  /* [cap] LEP_SF_* */
    uint16_t *seq;   /* [cap] the reserved bytes (leptrino-sim's sequence number) */
} lep_session_batch;

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

typedef struct lep_session_event {
    int type;        /* enum lep_session_event_type */
    uint64_t sample; /* index (count of samples delivered before it) where it applies */
    double t_mono;   /* when, monotonic s */
    double t_utc;    /* when, UTC s */
    double gap_from; /* GAP/RECONNECTED: arrival of the last sample before (mono s);
                              DISCONNECTED: the same, the last sample received */
    double gap_to;   /* ... and of the first after */
    uint32_t lost;   /* GAP: samples estimated lost (from sequence numbers on the
                              virtual sensor, from arrival times otherwise) */
    int error;       /* DISCONNECTED, and RECONNECTED (what caused the loss):
                              LEP_E_DISCONNECTED or LEP_E_TIMEOUT; 0 otherwise */
    uint8_t axes;    /* OVERLOAD_*: bit i = axis i saturated; status bits in status */
    uint8_t status;
    double tare[LEP_AXES];   /* TARE: the offsets now in force (counts; zeros when untared) */
    double wrench[LEP_AXES]; /* LIMIT_*: the sample's SI values (N, N m) */
} lep_session_event;

/* Health, since lep_session_start. */
typedef struct lep_session_health {
    double elapsed_s;   /* from the first sample to the last */
    double nominal_hz;  /* as lep_session_options.nominal_hz says */
    double measured_hz; /* (samples received - 1) / elapsed (decimation not applied) */
    double recent_hz;   /* over the last second or so (the run so far in its first second) */
    bool shortfall;     /* measured_hz below 98 % of nominal over at least 1 s */
    uint64_t received;  /* samples received (tare samples included) */
    uint64_t delivered; /* samples returned by lep_session_read (after decimation) */
    uint64_t lost;      /* samples estimated lost in gaps */
    uint64_t gaps;
    uint64_t errors;         /* framing, BCC, invalid messages, timeouts (all connections) */
    uint64_t overloads;      /* overload episodes begun */
    uint64_t limit_episodes; /* limit episodes begun (LEP_EV_LIMIT_EXCEEDED queued) */
    uint64_t disconnects;
    uint64_t reconnects;
    uint64_t events_dropped; /* events pushed out of the full queue (1024) before
                                lep_session_next_event took them */
    double max_gap_s;
    lep_client_stats client; /* the current connection's counters */
} lep_session_health;

/* What a recording says about itself. Strings are NUL-terminated. */
typedef struct lep_session_metadata {
    lep_product_info info; /* model, serial, firmware, output-rate field */
    char protocol[24];     /* "v1.13 (32-byte info)" or "rate field (38-byte)" */
    lep_rated rated;
    int sensor_filter; /* the sensor's filter code, -1 when it refused or did not answer */
    char sensor_filter_label[24]; /* lep_filter_label, or "not supported by sensor" */
    double nominal_hz;
    double lowpass_hz;      /* host low-pass cut-off, 0 off */
    char lowpass_name[48];  /* the filter's name, "" when off */
    double lowpass_delay_s; /* its group delay at low frequency */
    unsigned decimate;
    double rotation[9];
    double shift_m[3];
    bool tared;
    double tare[LEP_AXES]; /* counts */
    double start_utc;      /* UTC s of the last lep_session_start (of open before one) */
    double start_mono;     /* monotonic s of the same instant */
    char port[256];
    bool sim;
    char library_version[16]; /* lep_version() */
    lep_payload payload;      /* mass 0: none */
    double gravity[3];
    double limit[LEP_AXES]; /* 0: none */
} lep_session_metadata;

/* Defaults as documented on each field. o must not be NULL. */
LEP_API void lep_session_options_init(lep_session_options *o);

/* Rotation matrix (row-major) from roll, pitch, yaw in radians (R = Rz(yaw)
 * Ry(pitch) Rx(roll)). */
LEP_API void lep_rotation_from_rpy(double roll, double pitch, double yaw, double r[9]);

/* Open: start the virtual sensor or open the port, start-up recovery,
 * product info, rated values, filter code (a refusal or no answer is not an
 * error: sensor_filter = -1). Blocks up to a few answer timeouts. On success
 * *out owns everything; on failure nothing is left open. LEP_E_ARG for bad
 * options (message in err), the serial/sim/client error otherwise. On
 * success err holds "" or the virtual sensor's warning (lep_sim_start). */
LEP_API int lep_session_open(const lep_session_options *o, lep_session **out, char *err,
                             size_t errlen);

/* Stop the stream if running (best effort), close the port, stop the virtual
 * sensor, free. NULL is fine. Safe while another thread is inside a driving
 * call (it returns LEP_E_STATE first; see Threads above); call it once. */
LEP_API void lep_session_close(lep_session *s);

/* Start streaming (resends and recovery as in the client); clears the
 * health counters and sets start_utc. LEP_E_STATE when already streaming
 * (or another thread is inside a driving call). */
LEP_API int lep_session_start(lep_session *s);

/* Stop streaming. Samples already received and not yet read are lost. The
 * stop command is sent again once when it gets no answer, except after the
 * stream was lost to silence (data_timeout_ms): then one transaction,
 * (retries + 1) x timeout_ms at most. */
LEP_API int lep_session_stop(lep_session *s);

/* Append samples to b (from b->n up to b->cap). Waits up to timeout_ms
 * (< 0 forever) for the first one; then returns when b is full, or at once
 * when the latency budget is 0, or when the budget since the first new
 * sample's arrival has run out. Returns LEP_OK when at least one sample was
 * appended or an event was queued; LEP_E_TIMEOUT when nothing came within
 * timeout_ms, and only then: the stream may still come (a front end waits
 * again); LEP_E_LOST when the stream is lost: without reconnect, after
 * data_timeout_ms without a sample (LEP_EV_DISCONNECTED with error
 * LEP_E_TIMEOUT is queued), then and on every later call until stop: a front
 * end gives up on LEP_E_LOST, never on LEP_E_TIMEOUT; LEP_E_END once
 * duration_s or count is reached (the samples up to the limit are appended
 * first); LEP_E_DISCONNECTED when the port went away without reconnect, or
 * reconnect_give_up_ms passed (then and on later calls); LEP_E_STATE when not
 * streaming, when another thread is inside a driving call, or when
 * lep_session_close began in another thread; LEP_E_ARG. Samples are never
 * lost across calls: a full b leaves the rest queued for the next call. With
 * reconnect the session reconnects inside this call and reports it as events
 * (a data timeout is then never LEP_E_LOST). */
LEP_API int lep_session_read(lep_session *s, lep_session_batch *b, int timeout_ms);
/* With reconnect, a port that comes back with another sensor (model or
 * serial number differ) is not streamed from: LEP_E_UNEXPECTED, then and on
 * later calls. Whatever it returns, b->n counts the samples appended (LEP_E_END and the
 * errors may come with samples: write them). A b already full returns LEP_OK
 * at once. t_mono of samples that one read brought together is reconstructed
 * (docs/session.md): the last at the read's time, earlier ones a nominal
 * period apart, never before the previous sample or the previous read. On a
 * port (not the in-process virtual sensor) a read that leaves the stream
 * late by more than gap_periods is held back until the next read confirms
 * the hole or sees the late samples arrive. */

/* One sample in handshake mode (command 0x30), outside the stream, appended
 * to b as lep_session_read appends a stream sample: raw counts, zeroed with
 * the tare offsets in force, SI values through the rated values, payload
 * compensation, rotation and moment-point shift in force, the status bits, LEP_SF_OVERLOAD when the
 * sensor reports overload or an axis is at saturation, t_mono and t_utc when
 * the answer arrived. The host low-pass, decimation and tare averaging are
 * the stream's and do not apply (a lone sample has no history); no event is
 * queued and the health counters do not change. Blocks for one transaction
 * (timeout_ms per attempt, with the client's resends). LEP_OK; LEP_E_STATE
 * while streaming or while another thread is inside a driving call;
 * LEP_E_DISCONNECTED while disconnected; LEP_E_ARG for NULL
 * or a full b (b->n >= b->cap); the client's error otherwise (b unchanged). */
LEP_API int lep_session_read_one(lep_session *s, lep_session_batch *b);

/* Pop the oldest queued event into *ev; false when none. A full queue (1024
 * events) drops its oldest to take a new one: counted in
 * lep_session_health.events_dropped. While streaming, an event is returned
 * once lep_session_read has returned the samples before it (ev->sample <= the
 * samples read so far: it applies at most to the next sample to be read),
 * though a read may have processed more rows than its batch took; stopped,
 * every queued event is returned. */
LEP_API bool lep_session_next_event(lep_session *s, lep_session_event *ev);

/* Tare: average the raw counts of the next n samples (or of duration_s
 * seconds when n is 0) while the stream goes on, then make the mean the
 * offset and queue LEP_EV_TARE. Replaces a tare in progress. LEP_E_ARG when
 * both are 0. Usable before start (it begins with the stream). */
LEP_API int lep_session_tare(lep_session *s, unsigned n, double duration_s);
/* Zero offsets (queues LEP_EV_TARE; cancels a tare in progress). */
LEP_API int lep_session_untare(lep_session *s);
/* Set the offsets in counts (queues LEP_EV_TARE). */
LEP_API int lep_session_set_tare(lep_session *s, const double offset[LEP_AXES]);
/* Current offsets; returns true when a tare is in force. */
LEP_API bool lep_session_get_tare(lep_session *s, double offset[LEP_AXES]);
/* True while a tare is averaging. */
LEP_API bool lep_session_taring(lep_session *s);

/* Change the host low-pass (0 = off; LEP_E_VALUE above 0.45 x nominal rate)
 * and the output frame (rotation NULL = identity, shift_m NULL = 0; LEP_E_VALUE
 * for a matrix that is not orthonormal to 1e-6, or non-finite values). They
 * apply to samples received after the call: up to one read's worth already
 * received (at most the latency budget) keeps the old setting. The low-pass
 * is a 2nd-order Butterworth (docs/session.md: group delay, settling). */
LEP_API int lep_session_set_lowpass(lep_session *s, double cutoff_hz);
LEP_API int lep_session_set_rotation(lep_session *s, const double rotation[9],
                                     const double shift_m[3]);

/* Payload compensation (docs/session.md: the model). The SI values of the
 * samples received after the call have the payload's gravity wrench at the
 * current gravity removed (in the sensor frame, before rotation); raw and
 * zeroed counts stay as measured. p NULL (or mass 0): none. A tare that
 * finishes while a payload is set removes the bias only: the offset is the
 * mean minus the payload's expected wrench (in counts) at the gravity then
 * in force, so the tool's weight is not zeroed away at one pose. Gravity is
 * in the sensor frame, m/s^2; set it as often as the robot moves. LEP_E_ARG
 * for NULL s, a negative mass or non-finite values (nothing changed). */
LEP_API int lep_session_set_payload(lep_session *s, const lep_payload *p);
LEP_API int lep_session_set_gravity(lep_session *s, const double gravity[3]);

/* Limits on the SI values (compensated, in the output frame), per axis in N
 * and N m: an absolute value beyond limit[i] flags the sample LEP_SF_LIMIT;
 * the first such sample queues LEP_EV_LIMIT_EXCEEDED (axes: bit i = axis i
 * beyond; wrench: the sample), and LEP_EV_LIMIT_CLEARED follows at the first
 * sample with every axis back within 95 % of its limit. limit NULL, or 0 for
 * an axis: no limit. LEP_E_ARG for NULL s, negative or non-finite limits. */
LEP_API int lep_session_set_limits(lep_session *s, const double limit[LEP_AXES]);

/* Limits as text, the `--limit` syntax of the leptrino tool and the bridge:
 * AXIS=VALUE pairs separated by commas, AXIS one of fx fy fz mx my mz, VALUE
 * a finite number > 0 (N, N m), e.g. "fz=50,mz=2". Fills limit[] (axes not
 * named set to 0: none). LEP_E_ARG for NULL or malformed text, or an axis
 * named twice (limit then untouched). Re-entrant, no allocation. */
LEP_API int lep_limits_parse(const char *text, double limit[LEP_AXES]);

/* Change the latency budget (0..10000 ms, as latency_ms at open); it applies
 * from the next lep_session_read. Call it from the thread that reads (not
 * one of the any-thread calls). A recording that only returns at its end can
 * raise the budget and save wake-ups; a control loop keeps it at 0.
 * LEP_E_ARG out of range or NULL. */
LEP_API int lep_session_set_latency(lep_session *s, int latency_ms);
/* The latency budget in force, ms (0 for NULL). */
LEP_API int lep_session_latency(const lep_session *s);

LEP_API void lep_session_get_health(lep_session *s, lep_session_health *out);
LEP_API void lep_session_get_metadata(lep_session *s, lep_session_metadata *out);

/* The metadata as one JSON object (no newline) into buf[0..cap); *len gets
 * its length. LEP_E_BUFFER when it does not fit (buf then holds nothing
 * usable). Every front end writes this same object. */
LEP_API int lep_session_metadata_json(lep_session *s, char *buf, size_t cap, size_t *len);

/* The client, for commands the session does not wrap (filter set). Do not start or stop the stream through it. NULL while
 * disconnected. */
LEP_API lep_client *lep_session_client(lep_session *s);
/* The virtual sensor when use_sim, else NULL (for fault injection). */
LEP_API lep_sim *lep_session_sim(lep_session *s);
/* The port's path; the fd to poll for input (-1 while disconnected). */
LEP_API const char *lep_session_port(const lep_session *s);
LEP_API int lep_session_fd(const lep_session *s);
/* The latency settings lep_serial_open applied to the port of the current
 * connection (leptrino/serial.h). LEP_E_DISCONNECTED while disconnected (out
 * zeroed), LEP_E_ARG for NULL. Driving thread. */
LEP_API int lep_session_serial_info(const lep_session *s, lep_serial_info *out);
LEP_API bool lep_session_streaming(const lep_session *s);

#ifdef __cplusplus
}
#endif

#endif
