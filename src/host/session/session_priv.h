/* Private: the session's state and who owns which part of it.
 *
 * The session is a pipeline; each file calls only the files listed after it
 * (test/checks/depgraph.py fails the build on a cycle):
 *
 *   session.c           options, open, close, start, stop, accessors (lep_session)
 *   session_guard.c     the thread guard of the driving calls and close
 *                       (session_guard)
 *   session_read.c      lep_session_read, lep_session_read_one (inside the
 *                       guard, in passes that see a close): waiting,
 *                       the latency budget, reading the port (rbuf, backlog)
 *   session_reconnect.c loss of the stream and reconnection (session_reconnect)
 *   session_port.c      connecting and disconnecting the port: open, start-up
 *                       recovery, identity check (the port fields of lep_session)
 *   session_feed.c      port bytes -> frames -> samples -> stamped, processed
 *                       rows (no struct of its own)
 *   session_timing.c    stamps and gaps: applies the timeline's verdicts
 *                       (session_timeline.c: the sensor's clock, sans-I/O),
 *                       gaps from sequence numbers and reconnects
 *                       (session_timing); it sets rows.held for a suspected
 *                       hole and restarts the low-pass's settling count
 *   session_rows.c      processed rows waiting for a read, delivery into a
 *                       batch (session_rows)
 *   session_proc.c      overload, tare, low-pass, decimation, rotation, end of
 *                       run (session_proc)
 *   session_load.c      payload compensation and limits on the SI values
 *                       (session_load)
 *   session_health.c    health counters (session_health_state; session_proc.c
 *                       counts processed rows and h.overloads itself;
 *                       session_read.c counts h.delivered as rows are returned)
 *   session_events.c    the event queue (session_events)
 *   session_clock.c     UTC offset of the monotonic clock, waits in ms
 *   session_meta.c      metadata and its JSON (reads the structs above)
 *
 * Threads: the driving thread owns everything not marked [mu]; [mu] parts
 * are also read or written by the any-thread calls, under s->mu. */
#ifndef LEPTRINO_POSIX_SESSION_PRIV_H
#define LEPTRINO_POSIX_SESSION_PRIV_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/serial.h"
#include "leptrino/session.h"
#include "leptrino/sim.h"
#include "struct_api.h"
#include "session_timeline.h"

/* Bytes taken from the port per read: 16 KiB is 0.55 s of a 1.2 kHz stream,
 * so a latency budget of up to half a second needs one read per wake-up. */
#define SESSION_RBUF 16384u
/* What a latency budget may leave in the kernel between reads: half of the
 * 64 KiB a Linux tty buffers before the sender blocks (1.1 s at 1.2 kHz,
 * 131 ms at 10 kHz). */
#define SESSION_KERNEL_BYTES 32768.0
/* Smallest wire size of a data frame (DLE STX, 20 bytes, DLE ETX, BCC). */
#define SESSION_MIN_FRAME 25u
/* Samples one read can complete: every byte in whole frames, plus the frame
 * begun by the previous read. */
#define SESSION_PENDING (SESSION_RBUF / SESSION_MIN_FRAME + 2u)
/* Rows kept for reads: those held back while a hole is suspected (one read's
 * worth at most) and the next read's. */
#define SESSION_ROWS (2u * SESSION_PENDING)
/* How soon a read judges a suspected hole when a latency budget would wait longer. */
#define SESSION_CONFIRM_S 0.02
/* How often a vanished port is looked for while reconnecting. */
#define SESSION_WATCH_S 0.02
/* Events kept until lep_session_next_event takes them; beyond, the oldest go
 * (counted in lep_session_health_info.events_dropped). */
#define SESSION_EVENTS 1024u
/* A wall-clock step smaller than this is measurement jitter, not a step. */
#define SESSION_UTC_STEP_S 1e-3

/* A processed sample waiting for lep_session_read. */
typedef struct session_row {
    double t_mono;
    double t_utc;
    int16_t raw[LEP_AXES];
    double zeroed[LEP_AXES];
    double si[LEP_AXES];
    uint8_t status;
    uint8_t flags;
    uint16_t seq;
    double arrived; /* return of the read that brought it (session_feed.c) */
} session_row;

/* session_events.c: [mu] events kept until lep_session_next_event. */
typedef struct session_events {
    lep_session_event ev[SESSION_EVENTS];
    size_t head, len;
    uint64_t pushed;  /* queued since open (tells a read it has news) */
    uint64_t dropped; /* pushed out of a full queue since start */
    /* An event waits until the rows before its sample are returned: the head
     * goes when its sample <= gate (rows returned; UINT64_MAX when stopped).
     * An event queued while stopped, or still queued at a start, is at the
     * stream's row 0 (its sample is made 0). */
    uint64_t gate;
    /* The stream's row number of the current read's batch row 0 (rows
     * returned before that read, less the rows the batch held already);
     * 0 while stopped. An event's row in the batch is sample - row_base. */
    int64_t row_base;
} session_events;

/* session_health.c: [mu] the health counters and what they are computed from. */
typedef struct session_health_state {
    lep_session_health_info h; /* h.delivered: rows returned by lep_session_read */
    uint64_t processed;        /* rows processed: the next row's number (events' sample) */
    double first_t;
    double window_t;
    uint64_t window_n;
    uint64_t errors_before;      /* errors counted on earlier connections */
    uint64_t data_timeouts;      /* data timeouts (each counted as an error) */
    lep_client_stats base_stats; /* the connection's counters at start or reconnect */
} session_health_state;

/* session_proc.c: 2nd-order Butterworth low-pass, one section per axis
 * (direct form II transposed), run on raw counts. */
typedef struct session_lowpass {
    double cutoff_hz; /* 0: off */
    double b0, b1, b2, a1, a2;
    double z1[LEP_AXES], z2[LEP_AXES];
    bool primed;       /* state set from a sample (steady state) */
    uint32_t settle;   /* samples left flagged LEP_SF_SETTLING */
    uint32_t settle_n; /* samples of one settling period */
    double delay_s;    /* group delay at 0 Hz */
} session_lowpass;

/* session_guard.c: the public entry points' thread guard. */
typedef struct session_guard {
    pthread_mutex_t mu;
    pthread_cond_t left; /* a call left */
    unsigned inside;     /* threads inside a driving call (0 or 1) */
    bool driving;        /* a driving call (start, read, read_one, stop, set_latency) runs */
    bool closing;        /* lep_session_close has begun */
} session_guard;

/* session_proc.c: [mu] the processing of each sample. */
typedef struct session_proc {
    double tare[LEP_AXES];
    bool tared;
    bool taring;
    bool tare_hold;       /* the start-up tare: its samples are not delivered */
    uint32_t tare_n_goal; /* samples to average (0: by time) */
    double tare_until;    /* by time: arrival time that ends it (set at its first sample) */
    double tare_duration;
    double tare_sum[LEP_AXES];
    uint32_t tare_n;
    session_lowpass lp;
    double rot[9];
    double shift[3];
    unsigned decimate;
    uint32_t dec_phase;
    uint8_t carry_flags; /* LEP_SF_GAP of a sample that decimation dropped */
    bool overloaded;
    bool ended; /* duration or count reached */
    double first_delivered_t;
} session_proc;

/* session_load.c: [mu] the payload's gravity wrench removed from the SI
 * values, and the limits on what is left. */
typedef struct session_load {
    lep_payload payload;     /* mass 0: none */
    double gravity[3];       /* sensor frame, m/s^2 */
    double wrench[LEP_AXES]; /* the payload's gravity wrench at gravity (N, N m, sensor frame) */
    double limit[LEP_AXES];  /* N, N m on the output SI values; 0: none */
    bool beyond;             /* in a limit episode */
} session_load;

/* session_rows.c: processed rows waiting for a read (driving thread). */
typedef struct session_rows {
    session_row pending[SESSION_ROWS];
    size_t head, len;
    size_t held; /* newest rows held back: a suspected hole before them */
} session_rows;

/* session_timing.c: stamps and gaps (driving thread; its gap events and
 * counters go through [mu]). The model of the sensor's clock, the stamps and
 * the gaps from arrival times are the timeline's (session_timeline.h); the
 * rest here is the session's side: sequence numbers, reconnects, the UTC
 * offset, and the index of the rows held back. */
typedef struct session_timing {
    session_timeline tl;
    double last_read_t;      /* when the last read returned */
    double last_data_read_t; /* when the last read that completed a sample returned */
    double last_sample_t;    /* stamp of the last sample */
    bool have_seq;
    uint16_t last_seq;
    bool gap_next; /* the next sample follows a gap (reconnect) */
    double gap_from;
    int gap_error;          /* what caused the disconnect before a reconnect */
    uint64_t suspect_index; /* sample index of the first row held back */
    /* UTC - monotonic offset the samples are stamped with: held between
     * batches so UTC intervals equal monotonic ones, and moved only when the
     * wall clock steps by more than SESSION_UTC_STEP_S. */
    double utc_off;
} session_timing;

/* session_reconnect.c: loss and reconnection (driving thread). */
typedef struct session_reconnect {
    int failed; /* sticky outcome after a loss that is not reconnected (0: none) */
    double down_since;
    double next_attempt;
    bool port_missing; /* the last attempt found no port */
    int backoff_ms;
} session_reconnect;

enum session_conn { CONN_UP = 0, CONN_DOWN = 1 };

struct lep_session {
    lep_session_options opt; /* copied; strings point into the buffers below */
    char port_buf[256];
    char link_buf[128];
    lep_sim *sim;
    /* ---- the port (session_port.c) ---- */
    lep_serial *serial; /* NULL while disconnected */
    lep_client client;
    int conn;                    /* enum session_conn */
    lep_product_info info;       /* [mu] of the current connection */
    lep_product_info first_info; /* of the connection at open (a reconnect must find the same) */
    /* ---- identity, set at open (session.c) ---- */
    lep_rated rated;
    int sensor_filter; /* -1: refused or unanswered */
    double nominal_hz;
    double period_s;
    int16_t saturation;

    pthread_mutex_t mu; /* guards every part marked [mu] */

    /* ---- streaming (driving thread) ---- */
    bool streaming;
    bool backlog; /* more may be waiting: read again before sleeping (session_read.c) */
    uint8_t rbuf[SESSION_RBUF]; /* session_read.c */
    session_rows rows;
    session_timing tm;
    session_reconnect rc;

    /* ---- [mu] ---- */
    session_proc proc;
    session_load load;
    session_health_state hs;
    session_events events;
    double start_utc; /* metadata */
    double start_mono;

    session_guard guard; /* the driving calls' thread guard, and close's (session_guard.c) */
};

/* ---- session_reconnect.c ---- */
void lep_priv_reconnect_start(session_reconnect *r);
/* The stream is lost at now (error: LEP_E_DISCONNECTED, port gone, or
 * LEP_E_TIMEOUT, no data for data_timeout_ms): the event, the counters;
 * without reconnect the sticky outcome (LEP_E_LOST after a data timeout,
 * LEP_E_DISCONNECTED), with it the port is closed and the backoff begins. */
void lep_priv_reconnect_lost(lep_session *s, int error, double now);
/* While disconnected: give up (sets failed), sleep towards the next attempt
 * (no later than deadline), or attempt. False when deadline passed asleep. */
bool lep_priv_reconnect_wait(lep_session *s, double now, double deadline);

/* ---- session_port.c ---- */
/* Open the port, start-up recovery, identify (s->info). */
int lep_priv_session_connect(lep_session *s, char *err, size_t errlen);
void lep_priv_session_disconnect(lep_session *s);
/* The sensor that answered a reconnect is the one the session opened. */
bool lep_priv_session_same_sensor(lep_session *s);

/* ---- session_guard.c ---- */
/* enter refuses (LEP_E_STATE) while another thread drives or a close has
 * begun; close marks the session closing and waits until no thread is inside
 * (true the first time). */
int lep_priv_guard_init(session_guard *g);
void lep_priv_guard_destroy(session_guard *g);
int lep_priv_guard_enter(session_guard *g);
void lep_priv_guard_leave(session_guard *g);
bool lep_priv_guard_closing(session_guard *g);
bool lep_priv_guard_close(session_guard *g);

/* ---- session_feed.c ---- */
/* Step bytes through the client and process the samples they complete,
 * stamped as arriving by t_read. [mu] not held. */
void lep_priv_session_feed(lep_session *s, const uint8_t *data, size_t len, double t_read);
/* The stream (re)starts at now: take over the bytes the client read past the
 * start answer (they are stepped at once). */
void lep_priv_session_stream_reset(lep_session *s, double now);

/* ---- session_timing.c ---- */
/* A stream starts: gaps start over, the UTC offset is measured; the timeline
 * decides gaps from arrival times unless arrival_gaps is false (the
 * in-process virtual sensor numbers its samples). */
void lep_priv_timing_start(session_timing *tm, double period_s, double gap_periods,
                           bool arrival_gaps);
/* A loss: a suspected hole ends in it, the timeline starts over. */
void lep_priv_timing_lost(lep_session *s);
/* The next sample follows a reconnect: gap from gap_from, caused by error. */
void lep_priv_timing_reconnected(session_timing *tm, double gap_from, int error);
/* Samples known to be missing before each of got[0..n) (the virtual
 * sensor's sequence numbers, when numbered) into lost[]; their sum. */
uint64_t lep_priv_timing_seq(session_timing *tm, bool numbered, const lep_sample *got, size_t n,
                             double t_read, double hz, uint32_t *lost);
/* Apply the timeline's verdict on the rows held back: a gap before them
 * (flag, event, their stamps moved), or their release. [mu] held. */
void lep_priv_timing_judged(lep_session *s, const timeline_verdict *v);
/* Gap before a sample stamped t (a reconnect, or `lost` missing sequence
 * numbers): queues the event, returns LEP_SF_GAP or 0. [mu] held. */
uint8_t lep_priv_timing_sample(lep_session *s, uint32_t lost, double t);

/* ---- session_rows.c ---- */
void lep_priv_rows_clear(session_rows *r);
/* The slot the next row is written to, or NULL when full. */
session_row *lep_priv_rows_slot(session_rows *r);
/* Keep the row written to the slot. */
void lep_priv_rows_push(session_rows *r);
/* The row `back` rows before the newest pending one (0: the newest). */
session_row *lep_priv_rows_back(session_rows *r, size_t back);
/* Append one row to b (b->n < b->cap). */
void lep_priv_rows_append(lep_session_batch *b, const session_row *r);
/* Move rows not held back into b; *first gets the arrival of the first moved
 * (unchanged when none). */
void lep_priv_rows_deliver(session_rows *r, lep_session_batch *b, double *first);

/* ---- session_proc.c ---- */
/* Process one sample: overload, tare, low-pass, decimation, rotation; false
 * when it is not delivered (start-up tare, decimation, end reached). [mu] held. */
bool lep_priv_session_process(lep_session *s, const lep_sample *smp, double t, double t_utc,
                              uint8_t flags, session_row *row);
/* A handshake sample (outside the stream) into row: the tare offsets, SI
 * units and output frame in force; LEP_SF_OVERLOAD when overloaded. No
 * low-pass, decimation or tare averaging (they are the stream's), no event.
 * [mu] held. */
void lep_priv_proc_one(const lep_session *s, const lep_sample *smp, double t, double t_utc,
                       session_row *row);
/* A new stream: the start-up tare when asked, the low-pass restarted. [mu] held. */
void lep_priv_proc_start(lep_session *s);
/* The stream stopped: a tare in progress ends without a result. [mu] held. */
void lep_priv_proc_stop(session_proc *p);
void lep_priv_lowpass_design(session_lowpass *lp, double cutoff_hz, double fs);
/* The next sample sets the low-pass state again (a new stream, a reconnect). */
void lep_priv_lowpass_restart(session_lowpass *lp);

/* ---- session_load.c ([mu] held for the lep_priv_ ones) ---- */
/* Check the payload, gravity and limits of options o (one line in err). */
int lep_priv_load_check(const lep_session_options *o, char *err, size_t errlen);
/* From checked options. */
void lep_priv_load_init(session_load *l, const lep_session_options *o);
/* A new stream: no limit episode. */
void lep_priv_load_start(session_load *l);
/* Remove the payload's gravity wrench from si (N, N m, sensor frame). */
void lep_priv_load_compensate(const session_load *l, double si[LEP_AXES]);
/* The payload's gravity wrench in counts through rated (for a tare's offset). */
void lep_priv_load_counts(const session_load *l, const lep_rated *rated, double counts[LEP_AXES]);
/* Check a delivered row's SI values (output frame) against the limits: the
 * LEP_SF_LIMIT flag or 0, and the episode's events (before delivered sample
 * number `sample`, at t). */
uint8_t lep_priv_load_limits(lep_session *s, const double si[LEP_AXES], double t, uint64_t sample);

/* ---- session_health.c ([mu] held for all) ---- */
void lep_priv_health_start(session_health_state *hs, double nominal_hz,
                           const lep_client_stats *base);
/* The client's counters now: errors and the current connection's stats. */
void lep_priv_health_client(session_health_state *hs, const lep_client_stats *st);
void lep_priv_health_sample(session_health_state *hs, double t);
void lep_priv_health_gap(session_health_state *hs, double from, double to, uint32_t lost);
/* The connection ended (error: LEP_E_TIMEOUT counts a data timeout). */
void lep_priv_health_lost(session_health_state *hs, const lep_client_stats *st, int error);
/* A new connection's counters start at base. */
void lep_priv_health_reconnected(session_health_state *hs, const lep_client_stats *base);

/* ---- session_events.c ---- */
void lep_priv_event_init(lep_session_event *ev, int type, uint64_t sample, double t_mono);
/* A stream starts: the dropped count starts over; events queued stay and go
 * out ahead of the new stream's, at its row 0. [mu] held. */
void lep_priv_events_start(session_events *q);
/* Not streaming (opened, or stopped: the rows an event waited for are gone):
 * every event queued may go. [mu] held. */
void lep_priv_events_stop(session_events *q);
/* Rows returned so far: the events up to that sample may go. [mu] held. */
void lep_priv_events_returned(session_events *q, uint64_t rows);
/* A read begins: `rows` returned so far, its batch holding `held` rows
 * already; the events' batch rows count from its row 0. [mu] held. */
void lep_priv_events_batch(session_events *q, uint64_t rows, size_t held);
/* Queue ev; a full queue drops its oldest (counted). [mu] held. */
void lep_priv_events_push(session_events *q, const lep_session_event *ev);
/* The oldest event, once the rows before its sample are returned. [mu] held. */
bool lep_priv_events_pop(session_events *q, lep_session_event *ev);

/* ---- session_clock.c ---- */
/* UTC - monotonic offset, measured (the narrowest of three brackets). */
double lep_priv_utc_offset(void);
/* Whether the wall clock may have left utc_off +- SESSION_UTC_STEP_S, from
 * one read bracketed by t_before (monotonic) and now. */
bool lep_priv_utc_may_have_moved(double utc_off, double t_before);
/* Milliseconds from now until t, rounded up, clipped to int; -1 for infinity. */
int lep_priv_ms_until(double t, double now);

#endif
