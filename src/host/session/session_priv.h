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
 *   session_reader.c      connecting and disconnecting the port: open, start-up
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
#include "session_chain.h"
#include "session_clock.h"
#include "session_sink.h"
#include "session_timeline.h"

/* What a latency budget may leave in the kernel between reads: half of the
 * 64 KiB a Linux tty buffers before the sender blocks (1.1 s at 1.2 kHz,
 * 131 ms at 10 kHz). */
#define SESSION_KERNEL_BYTES 32768.0
/* How soon a read judges a suspected hole when a latency budget would wait longer. */
#define SESSION_CONFIRM_S 0.02
/* How often a vanished port is looked for while reconnecting. */
#define SESSION_WATCH_S 0.02

/* session_guard.c: the public entry points' thread guard. */
typedef struct session_guard {
    pthread_mutex_t mu;
    pthread_cond_t left; /* a call left */
    unsigned inside;     /* threads inside a driving call (0 or 1) */
    bool driving;        /* a driving call (start, read, read_one, stop, set_latency) runs */
    bool closing;        /* lep_session_close has begun */
} session_guard;

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
    /* ---- the port (session_reader.c) ---- */
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
    session_timing tm;
    session_reconnect rc;

    /* ---- [mu] ---- */
    session_chain chain;
    session_sink sink; /* rows (driving thread), events and health [mu] */
    double start_utc;  /* metadata */
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

/* ---- session_reader.c ---- */
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

#endif
