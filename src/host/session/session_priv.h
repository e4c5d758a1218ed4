/* Private: the session (struct lep_session), composed of units that own
 * their state. Each unit is a struct with its own header, which says what
 * it owns, what it reads, what it is given and its thread rule; its
 * functions take that struct (and explicit inputs), never the session:
 *
 *   session_reader.h   the port, the client on it, the latency budget of a
 *                      read, loss and reconnection (session_reader.c,
 *                      session_reader_reconnect.c)
 *   session_timing.h   stamps and gaps: the timeline (session_timeline.h,
 *                      sans-I/O), sequence numbers, reconnects, the UTC
 *                      offset; it hands each stamped sample to the chain
 *                      (session_timing.c)
 *   session_chain.h    tare, low-pass, payload, limits, decimation, rotation,
 *                      the run's end (session_chain.c, session_chain_load.c)
 *   session_sink.h     the rows waiting for a read, the event queue, the
 *                      health counters they imply (session_sink.c,
 *                      session_sink_events.c, session_sink_health.c)
 *   session_clock.h    clock helpers, owning nothing (session_clock.c)
 *
 * Only the files of the lifecycle and the API include this header and see
 * the session; they wire the units and write only the session's own fields
 * below (the units' fields through the units' functions):
 *
 *   session.c          options, open, close, start, stop, accessors
 *   session_read.c     lep_session_read, read_one: the reader's samples
 *                      into the pipeline (timing -> chain -> sink, each
 *                      stage given the next), the sink's rows out into the
 *                      caller's batch; loss and reconnection told to each
 *   session_live.c     the any-thread calls (tare, low-pass, rotation,
 *                      payload, limits, events, health)
 *   session_meta.c     the metadata and its JSON
 *   session_api.c      the flat public functions (leptrino/session.h)
 *   session_guard.c    the driving calls' thread guard (session_guard)
 *
 * Files:  session.c, session_read.c, session_live.c, session_meta.c,
 *         session_api.c, session_guard.c
 *
 * test/checks/unit_fields.py holds this map to the code (the units' headers
 * say their own files in the same way).
 *
 * Threads: the driving thread (inside the guard) owns everything not marked
 * [mu]; [mu] parts are also read or written by the any-thread calls, under
 * s->mu. */
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
#include "session_reader.h"
#include "session_sink.h"
#include "session_timing.h"

/* session_guard.c: the public entry points' thread guard. */
typedef struct session_guard {
    pthread_mutex_t mu;
    pthread_cond_t left; /* a call left */
    unsigned inside;     /* threads inside a driving call (0 or 1) */
    bool driving;        /* a driving call (start, read, read_one, stop, set_latency) runs */
    bool closing;        /* lep_session_close has begun */
} session_guard;

struct lep_session {
    lep_session_options opt; /* [mu] copied; strings point into the buffers below */
    char port_buf[256];
    char link_buf[128];
    lep_sim *sim;
    /* ---- identity, set at open ---- */
    lep_product_info info; /* [mu] of the current connection */
    lep_rated rated;
    int sensor_filter; /* -1: refused or unanswered */
    double nominal_hz;
    double period_s;
    int16_t saturation;

    pthread_mutex_t mu; /* guards every part marked [mu] */
    bool streaming;     /* driving thread */
    double start_utc;   /* [mu] metadata */
    double start_mono;  /* [mu] */

    /* ---- the units ---- */
    session_reader rd;   /* driving thread */
    session_timing tm;   /* driving thread ([mu] where given the sink) */
    session_chain chain; /* [mu] */
    session_sink sink;   /* rows: driving thread; events, health: [mu] */
    session_guard guard; /* its own mutex */
};

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

/* ---- session_read.c ---- */
/* The stream (re)starts at now: the reader takes over the bytes the client
 * read past the start answer, and they are fed at once. */
void lep_priv_session_resume(lep_session *s, double now);

#endif
