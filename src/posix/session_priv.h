/* Private: the session's state, shared by session.c (open/close/start/stop,
 * reconnect), session_stream.c (reading, timestamps, gaps, health, events),
 * session_proc.c (tare, low-pass, decimation, rotation) and session_meta.c
 * (metadata and its JSON). */
#ifndef LEPTRINO_POSIX_SESSION_PRIV_H
#define LEPTRINO_POSIX_SESSION_PRIV_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/serial.h"
#include "leptrino/session.h"
#include "leptrino/sim.h"

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
/* How soon a read judges a suspected hole when a latency budget would wait longer. */
#define SESSION_CONFIRM_S 0.02
/* How often a vanished port is looked for while reconnecting. */
#define SESSION_WATCH_S 0.02
/* Events kept until lep_session_next_event takes them; beyond, the oldest go. */
#define SESSION_EVENTS 1024u

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
} session_row;

/* 2nd-order Butterworth low-pass, one section per axis (direct form II
 * transposed), run on raw counts. */
typedef struct session_lowpass {
    double cutoff_hz; /* 0: off */
    double b0, b1, b2, a1, a2;
    double z1[LEP_AXES], z2[LEP_AXES];
    bool primed;       /* state set from a sample (steady state) */
    uint32_t settle;   /* samples left flagged LEP_SF_SETTLING */
    uint32_t settle_n; /* samples of one settling period */
    double delay_s;    /* group delay at 0 Hz */
} session_lowpass;

enum session_conn { CONN_UP = 0, CONN_DOWN = 1 };

/* The public entry points' thread guard (session_guard.c). */
typedef struct session_guard {
    pthread_mutex_t mu;
    pthread_cond_t left; /* a call left */
    unsigned inside;     /* threads inside a driving call (0 or 1) */
    bool driving;        /* a driving call (start, read, stop, set_latency) runs */
    bool closing;        /* lep_session_close has begun */
} session_guard;

struct lep_session {
    lep_session_options opt; /* copied; strings point into the buffers below */
    char port_buf[256];
    char link_buf[128];
    lep_sim *sim;
    lep_serial *serial; /* NULL while disconnected */
    lep_client client;
    lep_product_info info;       /* [mu] of the current connection */
    lep_product_info first_info; /* of the connection at open (a reconnect must find the same) */
    lep_rated rated;
    int sensor_filter; /* -1: refused or unanswered */
    double nominal_hz;
    double period_s;
    int16_t saturation;

    pthread_mutex_t mu; /* guards everything below marked [mu] */

    /* ---- streaming state (driving thread) ---- */
    bool streaming;
    int conn;   /* enum session_conn */
    int failed; /* sticky error after a loss without reconnect (0: none) */
    bool ended; /* duration or count reached */
    uint8_t rbuf[SESSION_RBUF];
    session_row pending[SESSION_PENDING];
    size_t pend_head, pend_len;
    bool backlog;            /* more may be waiting: read again before sleeping */
    double last_read_t;      /* when the last read returned */
    double last_data_read_t; /* when the last read that completed a sample returned */
    double last_sample_t;    /* reconstructed arrival of the last sample */
    bool have_sample;        /* a sample came since start (or since the reconnect) */
    bool have_seq;
    uint16_t last_seq;
    uint8_t carry_flags; /* LEP_SF_GAP of a sample that decimation dropped */
    bool gap_next;       /* the next sample follows a gap (reconnect) */
    double gap_from;
    int gap_error; /* what caused the disconnect before a reconnect */
    double down_since;
    double next_attempt;
    bool port_missing; /* the last reconnect attempt found no port */
    int backoff_ms;
    uint32_t dec_phase;
    double first_delivered_t;
    bool overloaded;
    /* holes found from arrival times (no sequence numbers) */
    bool tm_started;
    double tm_anchor_t;
    uint64_t tm_anchor_k, tm_k;
    double tm_window_t, tm_window_min;
    size_t held; /* newest pending rows held back: a suspected hole before them */
    double suspect_from, suspect_to;
    uint64_t suspect_index;
    lep_client_stats base_stats; /* the connection's counters at start or reconnect */

    /* ---- [mu] processing ---- */
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

    /* ---- [mu] health ---- */
    lep_session_health h;
    double first_t;
    double window_t;
    uint64_t window_n;
    uint64_t errors_before; /* errors counted on earlier connections */
    uint64_t data_timeouts;

    /* UTC - monotonic offset the samples are stamped with (the reading thread
     * only): held between batches so UTC intervals equal monotonic ones, and
     * moved only when the wall clock steps by more than SESSION_UTC_STEP_S. */
    double utc_off;

    /* ---- [mu] metadata ---- */
    double start_utc;
    double start_mono;

    /* ---- [mu] events ---- */
    lep_session_event ev[SESSION_EVENTS];
    size_t ev_head, ev_len;
    uint64_t ev_pushed; /* events queued since open (to tell a read it has news) */

    session_guard guard; /* the driving calls' thread guard, and close's */
};

/* session.c */
int lep_priv_session_connect(lep_session *s, char *err, size_t errlen);
void lep_priv_session_disconnect(lep_session *s);
/* Take over the bytes the client read past the start answer into rbuf-free
 * processing (they are stepped at once). */
void lep_priv_session_stream_reset(lep_session *s, double now);

/* session_guard.c: enter refuses (LEP_E_STATE) while another thread drives
 * or a close has begun; close marks the session closing and waits until no
 * thread is inside (true the first time). */
int lep_priv_guard_init(session_guard *g);
void lep_priv_guard_destroy(session_guard *g);
int lep_priv_guard_enter(session_guard *g);
void lep_priv_guard_leave(session_guard *g);
bool lep_priv_guard_closing(session_guard *g);
bool lep_priv_guard_close(session_guard *g);

/* session_stream.c */
/* lep_session_read's work, for one thread (session_guard.c calls it). */
int lep_priv_session_read(lep_session *s, lep_session_batch *b, int timeout_ms);
void lep_priv_session_push_event(lep_session *s, const lep_session_event *ev); /* [mu] held */
void lep_priv_session_event_init(lep_session_event *ev, int type, uint64_t sample, double t_mono);
double lep_priv_utc_offset(void);
/* A wall-clock step smaller than this is measurement jitter, not a step. */
#define SESSION_UTC_STEP_S 1e-3
/* Step bytes through the client and process the samples they complete,
 * stamped as arriving by t_read. [mu] not held. */
void lep_priv_session_feed(lep_session *s, const uint8_t *data, size_t len, double t_read);

/* session_proc.c */
/* Process one sample: tare, low-pass, decimation, rotation; false when it is
 * not delivered (start-up tare, decimation, end reached). [mu] held. */
bool lep_priv_session_process(lep_session *s, const lep_sample *smp, double t, double t_utc,
                              uint8_t flags, session_row *row);
void lep_priv_lowpass_design(session_lowpass *lp, double cutoff_hz, double fs);
void lep_priv_lowpass_restart(session_lowpass *lp);
void lep_priv_session_begin_tare(lep_session *s, unsigned n, double duration_s, bool hold);

#endif
