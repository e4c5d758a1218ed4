/* The session's reader: the port and the client on it, the bytes read from
 * it with their read times, the latency budget of a read call, and the
 * loss and reconnection of the stream.
 *
 * Owns:   session_reader (the serial port, the client, the read buffer,
 *         the times of the last reads, the reconnection's state, the
 *         identity found at the first connection).
 * Reads:  its configuration (reader_config, set at open).
 * Given:  the call's budget and deadline (reader_call, which it advances),
 *         whether rows are held back (a suspected hole is judged soon).
 * Returns: bytes (in rbuf) and their read time, samples stepped out of
 *         bytes, the outcome of a reconnection wait; it writes nothing of
 *         another unit: the loss's event, the counters and the stamps are
 *         the caller's to pass on.
 * Files:  session_reader.c (the port, the budgeted read), session_reader_reconnect.c
 *         (loss and reconnection).
 * Threads: the driving thread's (inside the thread guard). */
#ifndef LEPTRINO_HOST_SESSION_READER_H
#define LEPTRINO_HOST_SESSION_READER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/client.h"
#include "leptrino/serial.h"
#include "session_sizes.h"
#include "struct_api.h"

/* What a latency budget may leave in the kernel between reads: half of the
 * 64 KiB a Linux tty buffers before the sender blocks (1.1 s at 1.2 kHz,
 * 131 ms at 10 kHz). */
#define SESSION_KERNEL_BYTES 32768.0
/* How soon a read judges a suspected hole when a latency budget would wait longer. */
#define SESSION_CONFIRM_S 0.02
/* How often a vanished port is looked for while reconnecting. */
#define SESSION_WATCH_S 0.02

typedef struct reader_config {
    const char *port; /* lives as long as the session */
    int timeout_ms;
    int retries;
    int sync_quiet_ms;
    int data_timeout_ms;
    bool reconnect;
    int reconnect_min_ms;
    int reconnect_max_ms;
    int reconnect_give_up_ms;
    double nominal_hz;
} reader_config;

typedef struct session_reader {
    reader_config cfg;
    lep_serial *serial; /* NULL while disconnected */
    lep_client client;
    bool up;                /* connected */
    bool identified;        /* first holds the identity found at open */
    lep_product_info first; /* a reconnect must find the same sensor */
    bool backlog;           /* more may be waiting: read again before sleeping */
    uint8_t rbuf[SESSION_RBUF];
    double last_read_t;      /* when the last read returned */
    double last_data_read_t; /* when the last read that completed a sample returned */
    uint32_t probes;         /* budgeted reads' probes made: their dither */
    /* loss and reconnection (session_reader_reconnect.c) */
    int failed; /* sticky outcome after a loss that is not reconnected (0: none) */
    double down_since;
    double next_attempt;
    bool port_missing; /* the last attempt found no port */
    int backoff_ms;
} session_reader;

/* One lep_session_read call's budget (the reader advances its stage). */
typedef struct reader_call {
    double budget;   /* latency budget, s */
    double deadline; /* of the call's timeout, monotonic s (INFINITY: none) */
    double probe;    /* drain this long before the budget ends, then wait (0: no probe) */
    double wake;     /* the budget's end */
    int arrivals;    /* arrivals the probe still takes */
    int stage;       /* where the budget is */
} reader_call;

/* What a reconnection wait came to. */
enum reader_wait {
    READER_WAITED,     /* slept towards the next attempt, time left */
    READER_TIMED_OUT,  /* slept past the deadline */
    READER_GAVE_UP,    /* reconnect_give_up_ms passed: failed is set */
    READER_NOT_YET,    /* an attempt failed; the backoff goes on */
    READER_OTHER,      /* another sensor answered: failed is set */
    READER_RECONNECTED /* the stream runs again: resume it */
};

/* ---- session_reader.c ---- */
void lep_priv_reader_init(session_reader *rd, const reader_config *cfg);
/* The sensor's nominal rate, once known (the budget is counted in periods). */
void lep_priv_reader_set_rate(session_reader *rd, double nominal_hz);
/* Open the port, start-up recovery, identify (*info; the first connection's
 * is kept to compare a reconnect's with). */
int lep_priv_reader_connect(session_reader *rd, lep_product_info *info, char *err, size_t errlen);
void lep_priv_reader_disconnect(session_reader *rd);
bool lep_priv_reader_up(const session_reader *rd);
/* The client while connected (handshakes outside the stream), else NULL. */
lep_client *lep_priv_reader_client(session_reader *rd);
/* The port's latency settings: LEP_E_DISCONNECTED while disconnected. */
int lep_priv_reader_serial_info(const session_reader *rd, lep_serial_info *out);
int lep_priv_reader_fd(const session_reader *rd);
void lep_priv_reader_stats(const session_reader *rd, lep_client_stats *st);
/* Start the stream (LEP_E_DISCONNECTED while disconnected). */
int lep_priv_reader_start(session_reader *rd);
/* The stream (re)started at now: no outcome, no backlog; the bytes the
 * client read past the start answer into left (their number). */
size_t lep_priv_reader_resume(session_reader *rd, double now, uint8_t left[LEP_CLIENT_RX_SIZE]);
/* Stop the stream (one more try after a lost answer, not after a silence
 * that lost the stream); LEP_OK when the port is gone. */
int lep_priv_reader_stop(session_reader *rd);
/* One handshake sample (not streaming). */
int lep_priv_reader_sample(session_reader *rd, lep_sample *smp);
/* Step bytes read at t_read through the client; the samples they complete
 * into got[] (their number). */
size_t lep_priv_reader_samples(session_reader *rd, const uint8_t *data, size_t len,
                               lep_sample got[SESSION_PENDING], double t_read);
/* A read call with latency_ms of budget at nominal_hz, timeout_ms (< 0: none). */
void lep_priv_reader_call(const session_reader *rd, reader_call *c, int latency_ms, int timeout_ms);
/* One read of the port, waiting as the call's budget says (got: the call
 * has something, first: the stamp of its first row, < 0 none; holding: rows
 * are held back); the bytes in rbuf, their number (0: none came) or an
 * error; *t the read's return. */
int lep_priv_reader_read(session_reader *rd, reader_call *c, double now, bool got, double first,
                         bool holding, double *t);
/* Whether a call that has something (rows: among them rows) may return. */
bool lep_priv_reader_call_over(const session_reader *rd, const reader_call *c, double now,
                               bool rows, double first);
/* The bytes of the last read. */
const uint8_t *lep_priv_reader_bytes(const session_reader *rd);
/* No data for data_timeout_ms at now. */
bool lep_priv_reader_silent(const session_reader *rd, double now);
/* The sticky outcome of a loss not reconnected (0: none). */
int lep_priv_reader_failed(const session_reader *rd);

/* ---- session_reader_reconnect.c ---- */
/* The stream is lost at now (error: LEP_E_DISCONNECTED, port gone, or
 * LEP_E_TIMEOUT, no data for data_timeout_ms): without reconnect the sticky
 * outcome (LEP_E_LOST after a data timeout, LEP_E_DISCONNECTED), with it the
 * port is closed and the backoff begins. */
void lep_priv_reader_lost(session_reader *rd, int error, double now);
/* While disconnected: give up, sleep towards the next attempt (no later
 * than deadline), or attempt (enum reader_wait). *identified: a sensor
 * answered, its identity in *info. */
int lep_priv_reader_wait(session_reader *rd, double now, double deadline, lep_product_info *info,
                         bool *identified);

#endif
