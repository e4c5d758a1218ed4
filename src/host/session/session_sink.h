/* The session's sink: what the stream leaves for the caller -- the rows
 * waiting for a read, the event queue, and the health counters they imply.
 *
 * Owns:   session_sink (rows, events, health); nothing else is written.
 * Reads:  nothing of another unit.
 * Given:  rows and events (from the chain and the timing), the client's
 *         counters, times, the caller's batch to fill.
 * Files:  session_sink.c (the rows, delivery, and the entry points that
 *         count what they are given), session_sink_events.c (the queue),
 *         session_sink_health.c (the counters' arithmetic).
 * Threads: the rows are the driving thread's; the events and the health
 *         are [mu]: every function marked [mu] is called with the session's
 *         mutex held (the any-thread calls read them too). */
#ifndef LEPTRINO_HOST_SESSION_SINK_H
#define LEPTRINO_HOST_SESSION_SINK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/client.h"
#include "session_sizes.h"
#include "struct_api.h"

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
    double arrived; /* return of the read that brought it */
} session_row;

/* Processed rows waiting for a read (driving thread). */
typedef struct session_rows {
    session_row pending[SESSION_ROWS];
    size_t head, len;
    size_t held; /* newest rows held back: a suspected hole before them */
} session_rows;

/* [mu] events kept until lep_session_next_event. */
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

/* [mu] the health counters and what they are computed from. */
typedef struct session_health_state {
    lep_session_health_info h; /* h.delivered: rows returned by lep_session_read */
    uint64_t processed;        /* rows kept: the next row's number (events' sample) */
    double first_t;
    double window_t;
    uint64_t window_n;
    uint64_t errors_before;      /* errors counted on earlier connections */
    uint64_t data_timeouts;      /* data timeouts (each counted as an error) */
    lep_client_stats base_stats; /* the connection's counters at start or reconnect */
} session_health_state;

typedef struct session_sink {
    session_rows rows;       /* driving thread */
    session_events events;   /* [mu] */
    session_health_state hs; /* [mu] */
} session_sink;

/* ---- session_sink.c ---- */
/* Opened, not streaming: events go as they come. [mu] */
void lep_priv_sink_open(session_sink *sk);
/* A stream starts: no rows, the counters from zero (the client's at base);
 * events queued stay and go out ahead of the new stream's. [mu] */
void lep_priv_sink_start(session_sink *sk, double nominal_hz, const lep_client_stats *base);
/* The stream stopped: the rows go, and every event queued may go. [mu] */
void lep_priv_sink_stop(session_sink *sk);
/* A read begins, its batch holding `held` rows already: the events' batch
 * rows count from its row 0. [mu] held. */
void lep_priv_sink_batch(session_sink *sk, size_t held);
/* Keep a processed row: it is row number lep_priv_sink_processed(). [mu] */
void lep_priv_sink_row(session_sink *sk, const session_row *row);
/* Rows kept since start: the next row's number. [mu] */
uint64_t lep_priv_sink_processed(const session_sink *sk);
/* Rows waiting, held back or not. */
size_t lep_priv_sink_pending(const session_sink *sk);
/* Rows held back while a hole is suspected. */
size_t lep_priv_sink_held(const session_sink *sk);
/* Hold back the rows kept since the sink had `before` pending (extend: as
 * well as those held already); their number. */
size_t lep_priv_sink_hold_since(session_sink *sk, size_t before, bool extend);
/* Let the rows held back go as they are. */
void lep_priv_sink_release(session_sink *sk);
/* The rows held back are judged; they go. A hole before them (gap): their
 * stamps move by shift (each no later than its read's return), the first is
 * flagged LEP_SF_GAP, and true is returned (false: none were held). */
bool lep_priv_sink_judged(session_sink *sk, bool gap, double shift);
/* The run ended: when only rows held back wait, nothing comes to judge them
 * by: they go (true); false while other rows wait to be delivered. */
bool lep_priv_sink_end(session_sink *sk);
/* Move the rows not held back into b: the number moved; *first gets the
 * stamp of the first moved (unchanged when none). Driving thread, no [mu]. */
size_t lep_priv_sink_deliver(session_sink *sk, lep_session_batch *b, double *first);
/* n rows were returned to the caller: counted, their events free to go. [mu] */
void lep_priv_sink_returned(session_sink *sk, size_t n);
/* Queue an event, counted by its type (an overload or a limit episode
 * begun, a gap or reconnect with its lost samples); a full queue drops its
 * oldest (counted). LEP_EV_DISCONNECTED goes through lep_priv_sink_lost. [mu] */
void lep_priv_sink_event(session_sink *sk, const lep_session_event *ev);
/* The connection ended (ev: LEP_EV_DISCONNECTED; its error LEP_E_TIMEOUT
 * counts a data timeout), the client's counters at the end. [mu] */
void lep_priv_sink_lost(session_sink *sk, const lep_session_event *ev, const lep_client_stats *st);
/* A new connection's client counters start at base. [mu] */
void lep_priv_sink_reconnected(session_sink *sk, const lep_client_stats *base);
/* The client's counters now. [mu] */
void lep_priv_sink_client(session_sink *sk, const lep_client_stats *st);
/* A sample received, stamped t, counted: whether its row can be kept. [mu] */
bool lep_priv_sink_received(session_sink *sk, double t);
/* Events queued since open. [mu] */
uint64_t lep_priv_sink_pushed(const session_sink *sk);
/* The oldest event, once the rows before its sample are returned. [mu] */
bool lep_priv_sink_pop(session_sink *sk, lep_session_event *ev);
/* The health counters now. [mu] */
void lep_priv_sink_health(const session_sink *sk, lep_session_health_info *out);
/* Append one row to b (b->n < b->cap). */
void lep_priv_row_append(lep_session_batch *b, const session_row *r);

/* ---- session_sink_events.c ---- */
void lep_priv_event_init(lep_session_event *ev, int type, uint64_t sample, double t_mono);
void lep_priv_events_start(session_events *q);
void lep_priv_events_stop(session_events *q);
void lep_priv_events_returned(session_events *q, uint64_t rows);
void lep_priv_events_batch(session_events *q, uint64_t rows, size_t held);
void lep_priv_events_push(session_events *q, const lep_session_event *ev);
bool lep_priv_events_pop(session_events *q, lep_session_event *ev);

/* ---- session_sink_health.c ---- */
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

#endif
