/* Host-side client: transactions, NAK retransmission, streaming, recovery. */
#include "leptrino/client.h"

#include <string.h>

#include "leptrino/error.h"

#define ST_WAIT 0x01u   /* a transaction waits for its answer */
#define ST_STREAM 0x02u /* continuous output is on */

#define SYNC_DEFAULT_QUIET_MS 50
#define SYNC_DRAIN_TIMEOUTS 20

size_t lep_client_size(void)
{
    return sizeof(lep_client);
}

int lep_client_init(lep_client *c, const lep_io *io)
{
    if (c == NULL || io == NULL || io->write == NULL || io->now_ms == NULL) {
        return LEP_E_ARG;
    }
    memset(c, 0, sizeof(*c));
    c->io = *io;
    lep_frame_decoder_init(&c->dec);
    c->timeout_ms = LEP_CLIENT_DEFAULT_TIMEOUT_MS;
    c->max_retries = (uint8_t)LEP_CLIENT_DEFAULT_RETRIES;
    return LEP_OK;
}

int lep_client_set_timeout(lep_client *c, int timeout_ms)
{
    if (c == NULL || timeout_ms <= 0) {
        return LEP_E_ARG;
    }
    c->timeout_ms = timeout_ms;
    return LEP_OK;
}

int lep_client_set_retries(lep_client *c, unsigned retries)
{
    if (c == NULL || retries > 255u) {
        return LEP_E_ARG;
    }
    c->max_retries = (uint8_t)retries;
    return LEP_OK;
}

void lep_client_get_stats(const lep_client *c, lep_client_stats *out)
{
    if (c == NULL || out == NULL) {
        return;
    }
    *out = c->stats;
    out->messages = c->dec.stats.messages;
    out->bcc_errors = c->dec.stats.bcc_errors;
    out->frame_errors = c->dec.stats.escape_errors + c->dec.stats.overruns + c->dec.stats.restarts;
    out->bytes_discarded = c->dec.stats.bytes_discarded;
    out->naks = c->dec.stats.naks;
}

uint8_t lep_client_last_result(const lep_client *c)
{
    return c == NULL ? 0u : c->last_result;
}

bool lep_client_streaming(const lep_client *c)
{
    return c != NULL && (c->state & ST_STREAM) != 0u;
}

bool lep_client_busy(const lep_client *c)
{
    return c != NULL && (c->state & ST_WAIT) != 0u;
}

const lep_response *lep_client_response(const lep_client *c)
{
    return c == NULL ? NULL : &c->resp;
}

static uint32_t now(const lep_client *c)
{
    return c->io.now_ms(c->io.user);
}

/* Milliseconds from now until t (negative when t has passed). */
static int32_t until(const lep_client *c, uint32_t t)
{
    uint32_t d = t - now(c);
    return d < 0x80000000u ? (int32_t)d : -(int32_t)(0xFFFFFFFFu - d) - 1;
}

static void end_wait(lep_client *c)
{
    c->state = (uint8_t)(c->state & ~ST_WAIT);
}

static int write_pending(lep_client *c)
{
    int rc = c->io.write(c->io.user, c->tx, c->tx_len);
    if (rc < 0) {
        end_wait(c);
        return rc;
    }
    c->deadline = now(c) + (uint32_t)c->timeout_ms;
    return LEP_OK;
}

int lep_client_send(lep_client *c, const lep_command *cmd)
{
    size_t n;
    int rc;
    if (c == NULL || cmd == NULL) {
        return LEP_E_ARG;
    }
    end_wait(c);
    rc = lep_command_frame(cmd, c->tx, sizeof(c->tx), &n);
    if (rc != LEP_OK) {
        return rc;
    }
    c->tx_len = (uint8_t)n;
    c->pending = *cmd;
    c->tries = 0;
    c->state = (uint8_t)(c->state | ST_WAIT);
    return write_pending(c);
}

/* The answer to the pending command arrived (rc is OK or LEP_E_SENSOR). */
static int finish(lep_client *c, int rc)
{
    end_wait(c);
    c->last_result = c->resp.result;
    if (rc != LEP_OK) {
        return rc;
    }
    if (c->pending.code == LEP_CMD_START) {
        c->state = (uint8_t)(c->state | ST_STREAM);
    } else if (c->pending.code == LEP_CMD_STOP) {
        c->state = (uint8_t)(c->state & ~ST_STREAM);
    }
    return LEP_STEP_RESPONSE;
}

/* Handle one good frame; returns an outcome, or LEP_STEP_NONE to go on. */
static int on_message(lep_client *c, const lep_frame_event *ev)
{
    bool waiting = (c->state & ST_WAIT) != 0u;
    int rc = lep_response_decode(ev->msg, ev->len, &c->resp);
    if (rc != LEP_OK && rc != LEP_E_SENSOR) {
        c->stats.invalid++;
        return LEP_STEP_NONE;
    }
    if (c->resp.stream && rc == LEP_OK) {
        if ((c->state & ST_STREAM) == 0u) {
            c->stats.unexpected++; /* a stream we did not start (e.g. a stale one) */
            return LEP_STEP_NONE;
        }
        if (waiting && c->pending.code == LEP_CMD_STOP) {
            return LEP_STEP_NONE; /* our data still in flight before the stop answer */
        }
        c->stats.samples++;
        return LEP_STEP_SAMPLE;
    }
    if (waiting && c->resp.code == c->pending.code) {
        return finish(c, rc);
    }
    c->stats.unexpected++;
    return LEP_STEP_NONE;
}

static int on_nak(lep_client *c)
{
    if ((c->state & ST_WAIT) == 0u) {
        return LEP_STEP_NONE;
    }
    if (c->tries >= c->max_retries) {
        end_wait(c);
        return LEP_E_NAK;
    }
    c->tries++;
    c->stats.retries++;
    return write_pending(c);
}

int lep_client_step(lep_client *c, const uint8_t *data, size_t len, size_t *consumed)
{
    size_t pos = 0;
    int rc = LEP_STEP_NONE;
    if (c == NULL || consumed == NULL || (data == NULL && len > 0)) {
        return LEP_E_ARG;
    }
    while (pos < len) {
        lep_frame_event ev;
        pos += lep_frame_decoder_feed(&c->dec, data + pos, len - pos, &ev);
        if (ev.type == LEP_FRAME_MESSAGE) {
            rc = on_message(c, &ev);
        } else if (ev.type == LEP_FRAME_NAK) {
            rc = on_nak(c);
        } else if (ev.type == LEP_FRAME_ERROR && ev.error == LEP_E_LENGTH) {
            c->stats.invalid++; /* an empty frame */
        }
        if (rc != LEP_STEP_NONE) {
            *consumed = pos;
            return rc;
        }
    }
    *consumed = pos;
    if ((c->state & ST_WAIT) != 0u && until(c, c->deadline) <= 0) {
        end_wait(c);
        c->stats.timeouts++;
        return LEP_E_TIMEOUT;
    }
    return LEP_STEP_NONE;
}

/* Step over the bytes already read into c->rx (or just check the deadline). */
static int step_buffered(lep_client *c)
{
    size_t used = 0;
    int rc = lep_client_step(c, c->rx + c->rx_pos, (size_t)(c->rx_len - c->rx_pos), &used);
    c->rx_pos = (uint16_t)(c->rx_pos + used);
    return rc;
}

/* Read more input into c->rx (only once the bytes there are all stepped);
 * > 0 bytes, 0 on timeout, < 0 error. A read claiming more than it was
 * allowed is a broken backend: LEP_E_IO rather than a guess at the bytes. */
static int fill(lep_client *c, int timeout_ms)
{
    int n = c->io.read(c->io.user, c->rx, sizeof(c->rx), timeout_ms);
    if (n > (int)sizeof(c->rx)) {
        return LEP_E_IO;
    }
    if (n > 0) {
        c->rx_pos = 0;
        c->rx_len = (uint16_t)n;
    }
    return n;
}

int lep_client_transact(lep_client *c, const lep_command *cmd, lep_response *resp)
{
    int rc;
    if (c == NULL || cmd == NULL) {
        return LEP_E_ARG;
    }
    if (c->io.read == NULL) {
        return LEP_E_ARG;
    }
    rc = lep_client_send(c, cmd);
    while (rc >= 0) {
        int32_t left;
        rc = step_buffered(c);
        if (rc == LEP_STEP_RESPONSE) {
            if (resp != NULL) {
                *resp = c->resp;
            }
            return LEP_OK;
        }
        if (rc == LEP_STEP_SAMPLE) {
            /* A stream sample while waiting for another answer: skipped, not delivered. */
            c->stats.samples--;
            c->stats.unexpected++;
        }
        if (rc < 0 || c->rx_pos < c->rx_len) {
            continue; /* an error ends the loop; a sample leaves bytes to step over */
        }
        left = until(c, c->deadline);
        rc = fill(c, left > 0 ? (int)left : 0);
        if (rc < 0) {
            end_wait(c);
        }
    }
    return rc;
}

/* Wait for the next stream sample; count_timeout says whether a timeout is news.
 * Once the time is up, one more read that does not wait is made (so timeout 0
 * takes what is readable now); bytes that keep arriving without completing a
 * sample never extend the wait. */
static int next_sample(lep_client *c, lep_sample *out, int timeout_ms, bool count_timeout)
{
    uint32_t start = now(c);
    bool polled = false; /* the read after the time was up has been made */
    for (;;) {
        int rc = step_buffered(c);
        int n;
        int wait = timeout_ms;
        if (rc == LEP_STEP_SAMPLE) {
            *out = c->resp.u.sample;
            return LEP_OK;
        }
        if (rc < 0) {
            return rc;
        }
        if (c->rx_pos < c->rx_len) {
            continue;
        }
        if (timeout_ms >= 0) {
            uint32_t spent = now(c) - start;
            wait = spent >= (uint32_t)timeout_ms ? 0 : timeout_ms - (int)spent;
            if (wait == 0 && polled) {
                break;
            }
        }
        n = fill(c, wait);
        if (n < 0) {
            return n;
        }
        polled = wait == 0;
        if (n == 0 && timeout_ms >= 0 && (wait == 0 || now(c) - start >= (uint32_t)timeout_ms)) {
            break;
        }
    }
    if (count_timeout) {
        c->stats.timeouts++;
    }
    return LEP_E_TIMEOUT;
}

int lep_client_next_sample(lep_client *c, lep_sample *out, int timeout_ms)
{
    if (c == NULL || out == NULL || c->io.read == NULL) {
        return LEP_E_ARG;
    }
    if ((c->state & ST_STREAM) == 0u) {
        return LEP_E_STATE;
    }
    return next_sample(c, out, timeout_ms, true);
}

int lep_client_next_samples(lep_client *c, lep_sample *out, size_t max, size_t *n, int timeout_ms)
{
    int rc;
    if (n != NULL) {
        *n = 0;
    }
    if (out == NULL || n == NULL || max == 0) {
        return LEP_E_ARG;
    }
    rc = lep_client_next_sample(c, &out[0], timeout_ms);
    if (rc != LEP_OK) {
        return rc;
    }
    *n = 1;
    while (*n < max && next_sample(c, &out[*n], 0, false) == LEP_OK) {
        (*n)++;
    }
    return LEP_OK;
}

static int simple(lep_client *c, uint8_t code, uint8_t filter)
{
    lep_command cmd;
    cmd.code = code;
    cmd.filter = filter;
    return lep_client_transact(c, &cmd, NULL);
}

int lep_client_start(lep_client *c)
{
    return simple(c, LEP_CMD_START, 0);
}

int lep_client_stop(lep_client *c)
{
    return simple(c, LEP_CMD_STOP, 0);
}

int lep_client_product_info(lep_client *c, lep_product_info *out)
{
    int rc = out == NULL ? LEP_E_ARG : simple(c, LEP_CMD_PRODUCT_INFO, 0);
    if (rc == LEP_OK) {
        *out = c->resp.u.info;
    }
    return rc;
}

int lep_client_rated(lep_client *c, lep_rated *out)
{
    int rc = out == NULL ? LEP_E_ARG : simple(c, LEP_CMD_RATED, 0);
    if (rc == LEP_OK) {
        *out = c->resp.u.rated;
    }
    return rc;
}

int lep_client_filter_get(lep_client *c, uint8_t *code)
{
    int rc = code == NULL ? LEP_E_ARG : simple(c, LEP_CMD_FILTER_GET, 0);
    if (rc == LEP_OK) {
        *code = c->resp.u.filter;
    }
    return rc;
}

int lep_client_filter_set(lep_client *c, uint8_t code)
{
    if (code > LEP_FILTER_MAX) {
        return LEP_E_VALUE;
    }
    return simple(c, LEP_CMD_FILTER_SET, code);
}

int lep_client_sample(lep_client *c, lep_sample *out)
{
    int rc;
    if (c == NULL || out == NULL) {
        return LEP_E_ARG;
    }
    if ((c->state & ST_STREAM) != 0u) {
        return LEP_E_STATE;
    }
    rc = simple(c, LEP_CMD_SAMPLE, 0);
    if (rc == LEP_OK) {
        *out = c->resp.u.sample;
    }
    return rc;
}

/* Read and decode (for the counters) until quiet_ms pass without a byte. */
static int drain(lep_client *c, int quiet_ms)
{
    uint32_t start = now(c);
    uint32_t limit = 0x7FFFFFFFu; /* saturated: at most about 24 days */
    if ((uint32_t)c->timeout_ms < (limit - (uint32_t)quiet_ms) / SYNC_DRAIN_TIMEOUTS) {
        limit = (uint32_t)c->timeout_ms * SYNC_DRAIN_TIMEOUTS + (uint32_t)quiet_ms;
    }
    while (c->rx_pos < c->rx_len) {
        (void)step_buffered(c); /* what the stop's reads brought after its answer */
    }
    for (;;) {
        int n = fill(c, quiet_ms);
        if (n == 0) {
            return LEP_OK;
        }
        if (n < 0) {
            return n;
        }
        while (c->rx_pos < c->rx_len) {
            (void)step_buffered(c);
        }
        if (now(c) - start > limit) {
            return LEP_E_NO_SYNC;
        }
    }
}

int lep_client_sync(lep_client *c, int quiet_ms, lep_product_info *info)
{
    lep_product_info local;
    int rc;
    if (c == NULL || c->io.read == NULL) {
        return LEP_E_ARG;
    }
    if (quiet_ms <= 0) {
        quiet_ms = SYNC_DEFAULT_QUIET_MS;
    }
    end_wait(c);
    /* Assume a stream may be running: stop it, tolerating data before the answer. */
    c->state = (uint8_t)(c->state & ~ST_STREAM);
    rc = lep_client_stop(c);
    if (rc != LEP_OK && rc != LEP_E_SENSOR && rc != LEP_E_TIMEOUT && rc != LEP_E_NAK) {
        return rc;
    }
    c->state = (uint8_t)(c->state & ~ST_STREAM);
    rc = drain(c, quiet_ms);
    if (rc != LEP_OK) {
        return rc;
    }
    return lep_client_product_info(c, info != NULL ? info : &local);
}
