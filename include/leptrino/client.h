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
 *    buffer) and polls the outcome. The blocking calls are built on it. */
#ifndef LEPTRINO_CLIENT_H
#define LEPTRINO_CLIENT_H

#include <stdbool.h>
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
    uint32_t invalid;         /* good frames whose message failed validation, and empty frames */
    uint32_t timeouts;        /* transactions or reads that timed out */
    uint32_t samples;         /* stream samples delivered to the caller (LEP_STEP_SAMPLE) */
} lep_client_stats;

/* Step outcomes (non-negative); failures are negative LEP_E_* codes. */
enum lep_step {
    LEP_STEP_NONE = 0,     /* input consumed, nothing to report */
    LEP_STEP_RESPONSE = 1, /* the transaction finished: lep_client_response() */
    LEP_STEP_SAMPLE = 2    /* a stream sample arrived: lep_client_response()->u.sample */
};

#define LEP_CLIENT_DEFAULT_TIMEOUT_MS 100
#define LEP_CLIENT_DEFAULT_RETRIES 3u
#define LEP_CLIENT_RX_SIZE 128u
#define LEP_CLIENT_TX_SIZE 24u

/* Client context. Caller-allocated; fields are private. */
typedef struct lep_client {
    lep_io io;
    lep_frame_decoder dec;
    lep_response resp;
    lep_client_stats stats;
    lep_command pending;
    uint32_t deadline;
    int timeout_ms;
    uint16_t rx_pos;
    uint16_t rx_len;
    uint8_t state;
    uint8_t tries;
    uint8_t max_retries;
    uint8_t last_result;
    uint8_t tx_len;
    uint8_t tx[LEP_CLIENT_TX_SIZE];
    uint8_t rx[LEP_CLIENT_RX_SIZE];
} lep_client;

/* sizeof(lep_client), for FFI callers that allocate it as bytes. */
LEP_API size_t lep_client_size(void);

/* Bind c to io (copied) with the default timeout and retry limit.
 * Returns LEP_E_ARG when c or io is NULL or io lacks write or now_ms. */
LEP_API int lep_client_init(lep_client *c, const lep_io *io);

/* Transaction timeout in ms (> 0), default 100, for each attempt: a NAK
 * restarts it for the retransmission, so a transaction takes at most
 * (retries + 1) x timeout. Returns LEP_E_ARG if <= 0. */
LEP_API int lep_client_set_timeout(lep_client *c, int timeout_ms);

/* Times a NAKed command is sent again before LEP_E_NAK (0..255), default 3. */
LEP_API int lep_client_set_retries(lep_client *c, unsigned retries);

/* Copy the counters (framing counters included) into *out. */
LEP_API void lep_client_get_stats(const lep_client *c, lep_client_stats *out);

/* Result code of the last sensor answer (LEP_RESULT_*): why LEP_E_SENSOR. */
LEP_API uint8_t lep_client_last_result(const lep_client *c);

/* True between a successful start and the stop. */
LEP_API bool lep_client_streaming(const lep_client *c);

/* The last response or sample decoded; valid until the next step. */
LEP_API const lep_response *lep_client_response(const lep_client *c);

/* ---- Step API (non-blocking; never calls io.read) ---- */

/* Start a transaction: frame cmd, write it, arm the deadline. A previous
 * unfinished transaction is abandoned. LEP_E_ARG, LEP_E_VALUE, or the
 * io.write error. A start command enters streaming when it succeeds; a stop
 * leaves it, ignoring data messages that arrive before its answer. */
LEP_API int lep_client_send(lep_client *c, const lep_command *cmd);

/* Feed received bytes data[0..len): consumes up to and including the byte
 * that completes an outcome, storing the count in *consumed; call again with
 * the rest. len 0 just checks the deadline. Returns an enum lep_step value, or
 * for the transaction: LEP_E_SENSOR (see lep_client_last_result), LEP_E_NAK
 * (retries exhausted), LEP_E_TIMEOUT, or a write error from a retransmission.
 * A NAK is answered by sending the command again; messages of the wrong type
 * are skipped and counted. */
LEP_API int lep_client_step(lep_client *c, const uint8_t *data, size_t len, size_t *consumed);

/* True while a transaction waits for its answer. */
LEP_API bool lep_client_busy(const lep_client *c);

/* ---- Blocking calls (use io.read; return within about the timeout) ---- */

/* Send cmd and wait for its answer (with NAK retransmission); *resp may be
 * NULL. While streaming, samples that arrive meanwhile are skipped (counted as
 * unexpected). LEP_E_ARG without io.read. */
LEP_API int lep_client_transact(lep_client *c, const lep_command *cmd, lep_response *resp);

/* Start-up recovery: stop any running stream (its data is counted as
 * unexpected), drain until the line has been quiet for quiet_ms (<= 0: 50 ms;
 * gives up after about 20 timeouts), then confirm the sensor answers a
 * product-info query, stored in *info when not NULL. A stop that times out
 * or is refused does not end the recovery. LEP_E_NO_SYNC when the line never
 * goes quiet; else the query's error. */
LEP_API int lep_client_sync(lep_client *c, int quiet_ms, lep_product_info *info);

/* Queries; out must not be NULL (LEP_E_ARG). Errors as lep_client_transact. */
LEP_API int lep_client_product_info(lep_client *c, lep_product_info *out);
LEP_API int lep_client_rated(lep_client *c, lep_rated *out);
LEP_API int lep_client_filter_get(lep_client *c, uint8_t *code);
/* Takes effect only after the sensor is power-cycled. LEP_E_VALUE if code > 3. */
LEP_API int lep_client_filter_set(lep_client *c, uint8_t code);
/* One handshake-mode sample (0x30). LEP_E_STATE while streaming. */
LEP_API int lep_client_sample(lep_client *c, lep_sample *out);

/* Start continuous output. */
LEP_API int lep_client_start(lep_client *c);
/* Next stream sample within timeout_ms (< 0 forever, 0 only what is already
 * received or comes with one read that does not wait). Bytes that arrive
 * without completing a sample do not extend the wait. LEP_E_STATE when not
 * streaming; LEP_E_TIMEOUT; a read error. */
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
