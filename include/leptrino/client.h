/* Host-side client over caller-provided I/O.
 *
 * Not thread-safe; one context per port. The context is caller-allocated
 * (static memory on an MCU is fine), holds no pointers to globals, and uses
 * no allocation: several clients in one process are independent.
 *
 * Two ways to drive it:
 *  - blocking calls (lep_client_product_info, lep_client_next_sample, ...),
 *    which use io.read with timeouts and io.now_ms for deadlines;
 *  - the step API (lep_client_send + lep_client_step), which never reads:
 *    the caller feeds received bytes (from a super-loop or an ISR-fed ring
 *    buffer) and polls the outcome. The blocking calls are built on it.
 * NULL arguments as leptrino.h says. */
#ifndef LEPTRINO_CLIENT_H
#define LEPTRINO_CLIENT_H

#include <stddef.h>
#include <stdint.h>

#include "export.h"
#include "frame.h"
#include "message.h"

#ifdef __cplusplus
extern "C" {
#endif

/* I/O table. Timeouts in milliseconds: < 0 waits forever, 0 polls. */
typedef struct lep_io {
    /* Write all len bytes. Return 0, or a negative LEP_E_* code. */
    int (*write)(void *user, const uint8_t *data, size_t len);
    /* Wait up to timeout_ms for input and read what is available, at most
     * cap bytes. Return the count (> 0), 0 on timeout, or a negative LEP_E_*
     * code (LEP_E_DISCONNECTED when the port is gone); a count above cap is
     * taken as LEP_E_IO. Not needed by the step API (may be NULL there). */
    int (*read)(void *user, uint8_t *buf, size_t cap, int timeout_ms);
    /* Monotonic clock in milliseconds (wraps at 2^32). */
    uint32_t (*now_ms)(void *user);
    void *user;
} lep_io;

/* Client counters; they only grow (wrap at 2^32). */
typedef struct lep_client_stats {
    uint32_t messages;        /* framed messages with a good BCC */
    uint32_t bcc_errors;      /* frames rejected for a BCC mismatch */
    uint32_t frame_errors;    /* frames rejected otherwise (bad escape, > 128 bytes, restart) */
    uint32_t bytes_discarded; /* received bytes that were not part of a good message or NAK */
    uint32_t naks;            /* DLE NAK received */
    uint32_t retries;         /* commands sent again after a NAK */
    uint32_t unexpected;      /* good messages of the wrong type, skipped (a stale stream's data,
                                 samples arriving while a blocking query waits, late answers) */
    uint32_t invalid;         /* good frames whose message failed validation (wrong length or
                                 reserved byte, |raw| > 32000, non-printable product-info text,
                                 ...), and empty frames: never delivered */
    uint32_t timeouts;        /* transactions that failed with LEP_E_TIMEOUT, and blocking reads
                                 of samples that timed out */
    uint32_t samples;         /* stream samples delivered to the caller (LEP_STEP_SAMPLE) */
    /* Since 0.2: */
    uint32_t resent_after_timeout; /* commands sent again because no answer came in time */
    uint32_t resent_confirmed;     /* resent starts/stops taken as done because their first copy had
                                      been executed (answered 0x04, or a start's data flowing) */
    uint32_t recoveries;           /* starts refused with 0x04 (a stream already running) that were
                                      recovered by stop, drain, start */
    uint32_t reserved_nonzero;     /* accepted data messages whose last reserved byte was not 0x00
                                      (unspecified on later firmware) */
    uint32_t stalls;               /* stream watchdog expiries (LEP_E_STALLED) */
} lep_client_stats;

/* Step outcomes (non-negative); failures are negative LEP_E_* codes. */
enum lep_step {
    LEP_STEP_NONE = 0, /* input consumed, nothing to report */
    LEP_STEP_RESPONSE =
        1,              /* the transaction (or start-up recovery) finished: lep_client_response() */
    LEP_STEP_SAMPLE = 2 /* a stream sample arrived: lep_client_get_sample() */
};

/* The client's defaults and its recovery's limit. */
enum lep_client_default {
    LEP_CLIENT_DEFAULT_TIMEOUT_MS = 100, /* per attempt of a transaction (lep_client_set_timeout) */
    LEP_CLIENT_DEFAULT_RETRIES = 3,      /* resends per transaction (lep_client_set_retries) */
    LEP_CLIENT_DEFAULT_QUIET_MS = 50,    /* quiet time of a recovery's drain */
    /* The drain of a recovery gives up (LEP_E_NO_SYNC) after this many
     * timeouts plus the quiet time. */
    LEP_CLIENT_DRAIN_TIMEOUTS = 20
};

/* Size of the blocking calls' read buffer (lep_client_rx), in bytes. */
enum lep_client_rx_size { LEP_CLIENT_RX_SIZE = 128 };

/* Read buffer of the blocking calls: bytes read from io.read but not yet
 * stepped. Caller-allocated; fields are private. Not needed by the step API.
 * Evolution rule: the layout is public only so that C and firmware can
 * allocate it statically. Other languages allocate lep_client_rx_sizeof()
 * bytes (aligned for a uint16_t) and never read its fields; the fields may
 * change between minor versions while the version is 0.x. */
typedef struct lep_client_rx {
    uint16_t pos;
    uint16_t len;
    uint8_t buf[LEP_CLIENT_RX_SIZE];
} lep_client_rx;

/* Client context. Caller-allocated (static memory on an MCU is fine); its
 * fields are private.
 * Evolution rule: the layout is public only so that C and firmware can
 * allocate it statically. Other languages allocate lep_client_sizeof() bytes
 * (aligned for a pointer and a uint32_t) and never read its fields; the fields
 * may change between minor versions while the version is 0.x. */
typedef struct lep_client {
    uint8_t phase;       /* what the client waits for (client.c's enum phase) */
    uint8_t tries;       /* copies of the pending command sent again */
    uint8_t max_retries; /* resends allowed per transaction */
    uint8_t last_result; /* result code of the last sensor answer */
    lep_command cmd;     /* the pending command (its filter is read only by a filter set) */
    uint8_t streaming;   /* 1: continuous output is on */
    uint8_t fresh;       /* 1: a sample arrived since the watchdog last looked */
    uint8_t kept_len;    /* length of the last outcome's message (in dec.buf), 0: none */
    uint8_t clock_in;    /* single-byte steps left before the clock is looked at */
    uint16_t watchdog_ms;
    uint16_t quiet_ms; /* the drain's quiet time */
    uint32_t t_start;  /* when the transaction attempt or the quiet time began */
    uint32_t t_aux;    /* when the drain began, or the watchdog's reference time */
    uint32_t timeout_ms;
    lep_client_rx *rx; /* read buffer of the blocking calls, or NULL */
    lep_io io;
    /* The client's own counters (lep_client_stats has their meaning). */
    uint32_t retries;
    uint32_t unexpected;
    uint32_t invalid;
    uint32_t timeouts;
    uint32_t samples;
    uint32_t resent_after_timeout;
    uint32_t resent_confirmed;
    uint32_t recoveries;
    uint32_t reserved_nonzero;
    uint32_t stalls;
    lep_frame_decoder dec; /* the frame decoder; it also holds the kept message */
} lep_client;

/* sizeof(lep_client), for callers that allocate it as bytes. */
LEP_API size_t lep_client_sizeof(void);

/* sizeof(lep_client_rx), for callers that allocate it as bytes. */
LEP_API size_t lep_client_rx_sizeof(void);

/* Bind c to io (copied) with the default timeout and retry limit, no read
 * buffer and no watchdog. Returns LEP_E_ARG when c or io is NULL or io lacks
 * write or now_ms. */
LEP_API int lep_client_init(lep_client *c, const lep_io *io);

/* Give the blocking calls their read buffer (caller-owned, must outlive its
 * use by c; NULL detaches it). Without one, the blocking calls work the same
 * but read one byte per io.read call. lep_serial_client_init attaches one. */
LEP_API int lep_client_set_rx(lep_client *c, lep_client_rx *rx);

/* Timeout in ms (> 0), default 100, for each attempt of a transaction. An
 * attempt that gets no answer in time, or a DLE NAK, sends the command again,
 * up to the retry limit; so a transaction ends within
 * (retries + 1) x timeout ms (default 4 x 100 = 400 ms), and a start that is
 * recovered (stop, drain, start) within 3 x (retries + 1) x timeout +
 * (20 x timeout + quiet time). Returns LEP_E_ARG if <= 0. */
LEP_API int lep_client_set_timeout(lep_client *c, int timeout_ms);

/* Times a command is sent again (after a NAK or a timeout, one shared budget)
 * before LEP_E_NAK / LEP_E_TIMEOUT (0..255, else LEP_E_ARG), default 3. */
LEP_API int lep_client_set_retries(lep_client *c, int retries);

/* Stream watchdog: while streaming, no sample for ms milliseconds makes a
 * step return LEP_E_STALLED once (counted in stalls), then it re-arms. The
 * stream stays on: the application decides (e.g. lep_client_recover). 0 (the
 * default) turns it off. */
LEP_API int lep_client_set_watchdog(lep_client *c, uint16_t ms);

/* Copy the counters (framing counters included) into *out. */
LEP_API void lep_client_get_stats(const lep_client *c, lep_client_stats *out);

/* Result code of the last sensor answer (LEP_RESULT_*): why LEP_E_SENSOR. */
LEP_API uint8_t lep_client_last_result(const lep_client *c);

/* 1 between a successful start and the stop, else 0. */
LEP_API int lep_client_streaming(const lep_client *c);

/* Decode the message that completed the last LEP_STEP_RESPONSE or
 * LEP_STEP_SAMPLE into *out. Valid only until the next lep_client_step or
 * lep_client_send (the bytes live in the frame decoder): LEP_E_STATE when
 * there is none (e.g. a start confirmed by its data has no answer of its own
 * and gives that data message). LEP_E_ARG for NULL. */
LEP_API int lep_client_response(const lep_client *c, lep_response *out);

/* The sample of the last LEP_STEP_SAMPLE (or of a handshake answer), same
 * validity as lep_client_response; LEP_E_STATE when there is none. */
LEP_API int lep_client_get_sample(const lep_client *c, lep_sample *out);

/* ---- Step API (non-blocking; never calls io.read) ---- */

/* Start a transaction: frame cmd, write it, arm the deadline. A previous
 * unfinished transaction or recovery is abandoned. LEP_E_ARG, LEP_E_VALUE,
 * LEP_E_UNEXPECTED (unknown code), or the io.write error. A start command
 * enters streaming when it succeeds; a stop leaves it, ignoring data messages
 * that arrive before its answer.
 * Resending: a start whose resent copy is answered 0x04, or whose stream data
 * arrives, counts as started; a stop whose resent copy is answered 0x04
 * counts as stopped. A start whose first copy is refused with 0x04 while the
 * client is not streaming (a stale stream runs) is recovered once by stop,
 * drain, start inside the same transaction; a start while the client itself
 * streams stays LEP_E_SENSOR (0x04). */
LEP_API int lep_client_send(lep_client *c, const lep_command *cmd);

/* Non-blocking start-up recovery: send a stop (its answer, a timeout, a NAK
 * or a refusal all go on), drain until no byte has been fed for quiet_ms
 * (0: 50 ms), then query the product info. Driven by lep_client_step, like a
 * transaction (lep_client_busy is 1 meanwhile); it ends with
 * LEP_STEP_RESPONSE (lep_client_response gives the product info),
 * LEP_E_NO_SYNC when the line never goes quiet (about 20 timeouts), or the
 * query's error. Streaming is off afterwards. Stale data is counted as
 * unexpected. Errors now: LEP_E_ARG, or the io.write error. */
LEP_API int lep_client_recover(lep_client *c, uint16_t quiet_ms);

/* Feed received bytes data[0..len): consumes up to and including the byte
 * that completes an outcome, storing the count in *consumed; call again with
 * the rest. len 0 just checks the clock. Returns an enum lep_step value, or
 * for the transaction: LEP_E_SENSOR (see lep_client_last_result), LEP_E_NAK
 * (retries exhausted after NAKs), LEP_E_TIMEOUT (no answer to the last
 * copy), LEP_E_NO_SYNC (recovery), a write error from a retransmission; or
 * LEP_E_STALLED from the watchdog. A NAK or a timed-out attempt is answered by
 * sending the command again; messages of the wrong type are skipped and
 * counted. LEP_E_STALLED does not end a transaction that is under way (it
 * goes on; lep_client_busy says so). The clock (io.now_ms) is read on every
 * call with len != 1 and at least every 32 single-byte steps (len == 1, or
 * lep_client_step_byte; every one during a recovery), so timeouts are noticed
 * within 32 bytes when input never pauses; feed len 0 when the line is idle
 * (e.g. on each tick). Never blocks; calls io.write only to send a command
 * again (or the next command of a recovery). */
LEP_API int lep_client_step(lep_client *c, const uint8_t *data, size_t len, size_t *consumed);

/* One received byte b: lep_client_step(c, &b, 1, &used) in effect (the same
 * outcomes, counters and clock reads; the two may be mixed), for a caller fed
 * one byte at a time (an ISR-fed ring buffer): pop a byte, step, act on the
 * outcome. When it returns LEP_STEP_SAMPLE and out is not NULL, *out also
 * receives the sample (what lep_client_get_sample gives). LEP_E_ARG when c is
 * NULL. */
LEP_API int lep_client_step_byte(lep_client *c, uint8_t b, lep_sample *out);

/* 1 while a transaction or a recovery waits for its answer, else 0. */
LEP_API int lep_client_busy(const lep_client *c);

/* ---- Blocking calls (use io.read; return within the bounds above) ---- */

/* Send cmd and wait for its answer (resending after NAKs and timeouts);
 * *resp may be NULL. While streaming, samples that arrive meanwhile are
 * skipped (counted as unexpected), and a watchdog stall is counted but does
 * not end the wait. LEP_E_ARG without io.read. */
LEP_API int lep_client_transact(lep_client *c, const lep_command *cmd, lep_response *resp);

/* Start-up recovery (lep_client_recover, run to its end): stop any running
 * stream (its data is counted as unexpected), drain until the line has been
 * quiet for quiet_ms (<= 0: 50 ms; at most 65535), then confirm the sensor
 * answers a product-info query, stored in *info when not NULL.
 * LEP_E_NO_SYNC when the line never goes quiet; else the query's error. */
LEP_API int lep_client_sync(lep_client *c, int quiet_ms, lep_product_info *info);

/* Queries; out must not be NULL (LEP_E_ARG). Errors as lep_client_transact. */
LEP_API int lep_client_product_info(lep_client *c, lep_product_info *out);
LEP_API int lep_client_rated(lep_client *c, lep_rated *out);
LEP_API int lep_client_filter_get(lep_client *c, uint8_t *code);
/* Takes effect only after the sensor is power-cycled. LEP_E_VALUE if code > 3. */
LEP_API int lep_client_filter_set(lep_client *c, uint8_t code);
/* One handshake-mode sample (0x30). LEP_E_STATE while streaming. */
LEP_API int lep_client_sample(lep_client *c, lep_sample *out);

/* Start continuous output (resent and recovered as lep_client_send says). */
LEP_API int lep_client_start(lep_client *c);
/* Next stream sample within timeout_ms (< 0 forever, 0 only what is already
 * received or comes with one read that does not wait). Bytes that arrive
 * without completing a sample do not extend the wait. LEP_E_STATE when not
 * streaming; LEP_E_TIMEOUT; LEP_E_STALLED (watchdog); a read error. */
LEP_API int lep_client_next_sample(lep_client *c, lep_sample *out, int timeout_ms);
/* Up to max samples: waits up to timeout_ms for the first, then returns what
 * is already received without waiting again. *n gets the count. */
LEP_API int lep_client_next_samples(lep_client *c, lep_sample *out, size_t max, size_t *n,
                                    int timeout_ms);
/* Stop continuous output; data messages of our stream that arrive before the
 * answer are discarded (not counted). */
LEP_API int lep_client_stop(lep_client *c);

#ifdef __cplusplus
}
#endif

#endif
