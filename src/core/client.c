/* Host-side client: transactions with resending, streaming, recovery, watchdog.
 *
 * How this file is organised, top to bottom:
 *  1. the phases (what the client waits for) and the small accessors;
 *  2. sending a command: transmit() writes it and arms its deadline;
 *  3. what happens when an attempt ends: settle(), on_answer(),
 *     attempt_failed();
 *  4. the decoder's events: on_message() and on_event();
 *  5. the clock: the attempt's timeout, a recovery's drain, the watchdog;
 *  6. stepping: step() feeds input to the frame decoder and handles its events
 *     until an outcome; lep_client_step and lep_client_step_byte call it;
 *  7. the blocking calls, one waiting loop (wait_for) over step().
 *
 * The message of the last outcome (LEP_STEP_RESPONSE or LEP_STEP_SAMPLE) stays
 * in the frame decoder's buffer until the next step: c->kept_len says how long
 * it is (0: none), and lep_client_response decodes it from there. */
#include "leptrino/client.h"

#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "leptrino/error.h"

/* What the client waits for (lep_client.phase). A transaction and a recovery's
 * stop wait for an answer (PH_PLAIN .. PH_STOP_START: waiting()); a recovery's
 * drain waits for a quiet line (PH_DRAIN_SYNC, PH_DRAIN_START: draining()). */
enum phase {
    PH_NONE = 0,       /* no transaction or recovery */
    PH_PLAIN = 1,      /* a transaction */
    PH_RESTARTED = 2,  /* the start sent again after a recovery (not recovered twice) */
    PH_STOP_SYNC = 3,  /* lep_client_recover: its stop is out */
    PH_STOP_START = 4, /* a start refused with 0x04: the stop of its recovery is out */
    PH_DRAIN_SYNC = 5, /* lep_client_recover: waiting for a quiet line, then the query */
    PH_DRAIN_START = 6 /* a start's recovery: waiting for a quiet line, then start again */
};

/* Single-byte steps between two looks at the clock while a deadline is armed. */
#define CHECK_EVERY 32u
/* A deadline that is not armed. */
#define NEVER 0xFFFFFFFFu
/* The drain's timeout part is capped so the limit stays below 2^31 ms. */
#define DRAIN_TIMEOUT_CAP ((0x7FFFFFFFu - 0xFFFFu) / LEP_CLIENT_DRAIN_TIMEOUTS)

size_t lep_client_sizeof(void)
{
    return sizeof(lep_client);
}

size_t lep_client_rx_sizeof(void)
{
    return sizeof(lep_client_rx);
}

int lep_client_init(lep_client *c, const lep_io *io)
{
    if (c == NULL || io == NULL || io->write == NULL || io->now_ms == NULL) {
        return LEP_E_ARG;
    }
    memset(c, 0, sizeof(*c)); /* (the decoder too: all zero is what lep_frame_decoder_init
                                 gives, test_init_zeroes_like_decoder_init checks it) */
    c->io = *io;
    c->timeout_ms = LEP_CLIENT_DEFAULT_TIMEOUT_MS;
    c->max_retries = (uint8_t)LEP_CLIENT_DEFAULT_RETRIES;
    c->quiet_ms = (uint16_t)LEP_CLIENT_DEFAULT_QUIET_MS;
    return LEP_OK;
}

int lep_client_set_rx(lep_client *c, lep_client_rx *rx)
{
    if (c == NULL) {
        return LEP_E_ARG;
    }
    c->rx = rx;
    if (rx != NULL) {
        rx->pos = 0;
        rx->len = 0;
    }
    return LEP_OK;
}

int lep_client_set_timeout(lep_client *c, int timeout_ms)
{
    if (c == NULL || timeout_ms <= 0) {
        return LEP_E_ARG;
    }
    c->timeout_ms = (uint32_t)timeout_ms;
    return LEP_OK;
}

int lep_client_set_retries(lep_client *c, int retries)
{
    if (c == NULL || retries < 0 || retries > 255) {
        return LEP_E_ARG;
    }
    c->max_retries = (uint8_t)retries;
    return LEP_OK;
}

int lep_client_set_watchdog(lep_client *c, uint16_t ms)
{
    if (c == NULL) {
        return LEP_E_ARG;
    }
    c->watchdog_ms = ms;
    c->clock_in = 0; /* the next step looks at the clock */
    c->fresh = true; /* the watchdog's time runs from that look */
    return LEP_OK;
}

void lep_client_get_stats(const lep_client *c, lep_client_stats *out)
{
    const lep_frame_stats *f;
    if (c == NULL || out == NULL) {
        return;
    }
    f = &c->dec.stats;
    out->messages = f->messages;
    out->bcc_errors = f->bcc_errors;
    out->frame_errors = f->escape_errors + f->overruns + f->restarts;
    out->bytes_discarded = f->bytes_discarded;
    out->naks = f->naks;
    out->retries = c->retries;
    out->unexpected = c->unexpected;
    out->invalid = c->invalid;
    out->timeouts = c->timeouts;
    out->samples = c->samples;
    out->resent_after_timeout = c->resent_after_timeout;
    out->resent_confirmed = c->resent_confirmed;
    out->recoveries = c->recoveries;
    out->reserved_nonzero = c->reserved_nonzero;
    out->stalls = c->stalls;
}

uint8_t lep_client_last_result(const lep_client *c)
{
    return c == NULL ? 0u : c->last_result;
}

int lep_client_streaming(const lep_client *c)
{
    return c != NULL && c->streaming != 0u;
}

int lep_client_busy(const lep_client *c)
{
    return c != NULL && c->phase != PH_NONE;
}

int lep_client_response(const lep_client *c, lep_response *out)
{
    if (c == NULL || out == NULL) {
        return LEP_E_ARG;
    }
    if (c->kept_len == 0u) {
        return LEP_E_STATE;
    }
    /* validated when it arrived; a refusal (0x04) gives LEP_E_SENSOR */
    (void)lep_response_decode(c->dec.buf, c->kept_len, out);
    return LEP_OK;
}

int lep_client_get_sample(const lep_client *c, lep_sample *out)
{
    lep_response r;
    if (c == NULL || out == NULL) {
        return LEP_E_ARG;
    }
    if (c->kept_len != LEP_LEN_SAMPLE) {
        return LEP_E_STATE; /* (a sample is the only 20-byte message that makes an outcome) */
    }
    (void)lep_response_decode(c->dec.buf, LEP_LEN_SAMPLE, &r); /* (validated when it came) */
    *out = r.u.sample;
    return LEP_OK;
}

static uint32_t now(const lep_client *c)
{
    return c->io.now_ms(c->io.user);
}

/* A transaction (or a recovery's stop) waits for its answer. */
static bool waiting(const lep_client *c)
{
    return c->phase >= PH_PLAIN && c->phase <= PH_STOP_START;
}

/* A recovery waits for a quiet line. */
static bool draining(const lep_client *c)
{
    return c->phase >= PH_DRAIN_SYNC;
}

/* The transaction or recovery is over; returns rc, its outcome. */
static int finish(lep_client *c, int rc)
{
    c->phase = PH_NONE;
    return rc;
}

/* ---- Starting a transaction ---- */

/* Send the command code (with the filter code of c->cmd, which
 * lep_command_encode reads only for a filter set) in phase, as copy number
 * tries + 1 of it (tries 0: a new transaction or the next part of a recovery;
 * more: sent again), and restart the attempt's clock. */
static int transmit(lep_client *c, uint8_t code, enum phase phase, uint8_t tries)
{
    uint8_t frame[2u * LEP_LEN_FILTER_SET_CMD + 5u]; /* the longest command, every byte stuffed */
    size_t n;
    int rc;
    c->kept_len = 0;
    c->cmd.code = code;
    c->phase = (uint8_t)phase;
    c->tries = tries;
    c->clock_in = 0; /* a deadline is armed: look at the clock on the next step */
    rc = lep_command_frame(&c->cmd, frame, sizeof(frame), &n);
    if (rc == LEP_OK) {
        rc = c->io.write(c->io.user, frame, n);
    }
    if (rc < 0) {
        return finish(c, rc);
    }
    c->t_start = now(c);
    return LEP_OK;
}

int lep_client_send(lep_client *c, const lep_command *cmd)
{
    if (c == NULL || cmd == NULL) {
        return LEP_E_ARG;
    }
    c->cmd.filter = cmd->filter;
    return transmit(c, cmd->code, PH_PLAIN, 0u);
}

int lep_client_recover(lep_client *c, uint16_t quiet_ms)
{
    if (c == NULL) {
        return LEP_E_ARG;
    }
    c->quiet_ms = quiet_ms != 0u ? quiet_ms : (uint16_t)LEP_CLIENT_DEFAULT_QUIET_MS;
    c->streaming = false; /* a stream's data is stale from here on */
    return transmit(c, LEP_CMD_STOP, PH_STOP_SYNC, 0u);
}

/* ---- The end of an attempt ---- */

/* The attempt is over with rc (LEP_STEP_RESPONSE: it ended well, streaming
 * follows the command; else its error). A recovery's stop (answered, refused
 * or never got through) goes on to its drain instead: LEP_STEP_NONE. */
static int settle(lep_client *c, int rc)
{
    if (c->phase == PH_STOP_SYNC || c->phase == PH_STOP_START) {
        c->phase = c->phase == PH_STOP_SYNC ? PH_DRAIN_SYNC : PH_DRAIN_START;
        c->t_start = now(c); /* the quiet time and the drain's limit run from here */
        c->t_aux = c->t_start;
        return LEP_STEP_NONE;
    }
    if (rc == LEP_E_TIMEOUT) {
        c->timeouts++;
    } else if (rc == LEP_STEP_RESPONSE && c->cmd.code == LEP_CMD_START) {
        if (c->phase == PH_RESTARTED) {
            c->recoveries++;
        }
        c->streaming = true;
        c->fresh = true;
    } else if (rc == LEP_STEP_RESPONSE && c->cmd.code == LEP_CMD_STOP) {
        c->streaming = false;
    }
    return finish(c, rc);
}

/* The answer to the pending command arrived: kept is its result code, result
 * what it means here (the same, or LEP_RESULT_STATE for data of a stream a
 * resent start began, whose first copy was executed). */
static int on_answer(lep_client *c, uint8_t kept, unsigned result)
{
    c->last_result = kept;
    if (result == LEP_RESULT_STATE &&
        (c->cmd.code == LEP_CMD_START || c->cmd.code == LEP_CMD_STOP) &&
        c->phase <= PH_RESTARTED) { /* (not a recovery's stop: any answer to it will do) */
        if (c->tries > 0u) {
            c->resent_confirmed++; /* an earlier copy was executed */
            result = LEP_RESULT_OK;
        } else if (c->cmd.code == LEP_CMD_START && c->phase == PH_PLAIN && !c->streaming) {
            /* A stream we did not start (a stale one) already runs: recover. */
            return transmit(c, LEP_CMD_STOP, PH_STOP_START, 0u); /* LEP_OK is LEP_STEP_NONE */
        }
    }
    return settle(c, result == LEP_RESULT_OK ? LEP_STEP_RESPONSE : LEP_E_SENSOR);
}

/* The attempt failed, after a NAK or a timeout (after_nak false): send again
 * (counted in retries or resent_after_timeout), or give up with LEP_E_NAK or
 * LEP_E_TIMEOUT. */
static int attempt_failed(lep_client *c, bool after_nak)
{
    if (!waiting(c)) {
        return LEP_STEP_NONE; /* (a NAK or a deadline of no attempt) */
    }
    if (c->tries < c->max_retries) {
        if (after_nak) {
            c->retries++;
        } else {
            c->resent_after_timeout++;
        }
        return transmit(c, c->cmd.code, (enum phase)c->phase, (uint8_t)(c->tries + 1u));
    }
    /* (a stop of a recovery that never got through does not end it) */
    return settle(c, after_nak ? LEP_E_NAK : LEP_E_TIMEOUT);
}

/* ---- The decoder's events ---- */

/* Handle one good frame; returns an outcome, or LEP_STEP_NONE to go on. */
static int on_message(lep_client *c, const lep_frame_event *ev)
{
    lep_response r;
    int rc = lep_response_decode(ev->msg, ev->len, &r);
    bool mine;
    if (rc != LEP_OK && rc != LEP_E_SENSOR) {
        c->invalid++;
        return LEP_STEP_NONE;
    }
    if (r.stream && c->streaming) {
        if (c->cmd.code == LEP_CMD_STOP && waiting(c)) {
            return LEP_STEP_NONE; /* our data still in flight before the stop answer */
        }
        c->samples++;
        c->fresh = true;
        return LEP_STEP_SAMPLE;
    }
    mine = waiting(c) && r.code == c->cmd.code; /* (a data message's code is the start's) */
    if (mine && (!r.stream || c->tries > 0u)) {
        /* Our answer; or data of a stream we are starting: the first copy of
         * our resent start was executed, as if a copy were refused with 0x04
         * (the data's result is 0, which is kept). */
        return on_answer(c, r.result, r.result | (r.stream ? LEP_RESULT_STATE : 0u));
    }
    c->unexpected++; /* e.g. a stream we did not start (a stale one), a late answer */
    return LEP_STEP_NONE;
}

/* Handle the decoder's event ev (not LEP_FRAME_NONE): an outcome, or
 * LEP_STEP_NONE to go on. An outcome's message is kept (c->kept_len). */
static int on_event(lep_client *c, const lep_frame_event *ev)
{
    int rc = LEP_STEP_NONE;
    if (ev->type == LEP_FRAME_MESSAGE) {
        rc = on_message(c, ev);
    } else if (ev->type == LEP_FRAME_NAK) {
        rc = attempt_failed(c, true);
    } else if (ev->error == LEP_E_LENGTH) { /* (a rejected frame's error) */
        c->invalid++;                       /* an empty frame */
    }
    if (rc > 0) { /* a response or a sample: its message stays at dec.buf */
        c->kept_len = (uint8_t)ev->len;
        if (ev->len == LEP_LEN_SAMPLE && ev->msg[LEP_LEN_SAMPLE - 1u] != 0u) {
            c->reserved_nonzero++; /* a sample's last reserved byte (unspecified) */
        }
    }
    return rc;
}

/* ---- The clock ---- */

/* What is left at t of span begun at t0 (0 once it has passed); NEVER when
 * span is 0 (the timer is not armed). */
static uint32_t left_of(uint32_t t, uint32_t t0, uint32_t span)
{
    uint32_t spent = t - t0;
    if (span == 0u) {
        return NEVER;
    }
    return spent >= span ? 0u : span - spent;
}

/* Whether span has passed at t since t0. */
static bool expired(uint32_t t, uint32_t t0, uint32_t span)
{
    return t - t0 >= span;
}

/* The drain's limit: LEP_CLIENT_DRAIN_TIMEOUTS timeouts plus the quiet time. */
static uint32_t drain_limit(const lep_client *c, uint32_t quiet)
{
    uint32_t timeout = c->timeout_ms;
    return (timeout < DRAIN_TIMEOUT_CAP ? timeout : DRAIN_TIMEOUT_CAP) * LEP_CLIENT_DRAIN_TIMEOUTS +
           quiet;
}

/* A drain at the clock's time t, fed saying bytes came in: still draining,
 * given up (LEP_E_NO_SYNC), or quiet: the query (lep_client_recover) or the
 * start again (a start's recovery) goes out. */
static int check_drain(lep_client *c, uint32_t t, bool fed)
{
    uint32_t quiet = c->quiet_ms;
    bool sync;
    if (fed) {
        c->t_start = t; /* not quiet yet */
    }
    if (expired(t, c->t_aux, drain_limit(c, quiet))) {
        return finish(c, LEP_E_NO_SYNC);
    }
    if (!expired(t, c->t_start, quiet)) {
        return LEP_STEP_NONE;
    }
    sync = c->phase == PH_DRAIN_SYNC;
    return transmit(c, sync ? LEP_CMD_PRODUCT_INFO : LEP_CMD_START, sync ? PH_PLAIN : PH_RESTARTED,
                    0u);
}

/* The deadlines at the clock's time, fed saying bytes came in. Two timers:
 * the attempt's (the answer's timeout, or a drain's quiet time; from t_start)
 * and the other (a drain's limit, or the stream watchdog; from t_aux). A
 * drain's are armed throughout (quiet_ms and timeout_ms are never 0) and it
 * runs with streaming off; otherwise the attempt's is armed while a
 * transaction waits, the watchdog (watch) while streaming with watchdog_ms not 0. */
static int check_clock(lep_client *c, bool fed, bool watch)
{
    uint32_t t = now(c);
    if (draining(c)) {
        return check_drain(c, t, fed);
    }
    if (c->fresh) {
        /* The watchdog's time runs from here. (Without streaming t_aux is not
         * read here; a start that succeeds sets fresh again.) */
        c->fresh = false;
        c->t_aux = t;
    }
    if (expired(t, c->t_start, c->timeout_ms)) { /* (attempt_failed: if one waits) */
        int rc = attempt_failed(c, false);
        if (rc != LEP_STEP_NONE) {
            return rc;
        }
    }
    if (watch && expired(t, c->t_aux, c->watchdog_ms)) {
        c->t_aux = t;
        c->stalls++;
        return LEP_E_STALLED;
    }
    return LEP_STEP_NONE;
}

/* A step consumed its input without an outcome and the clock is due: look at
 * it if a deadline is armed. Then the next look is due after CHECK_EVERY
 * single-byte steps at most a plain transaction waits, else at the next step. */
static int clock_due(lep_client *c, bool fed)
{
    const bool watch = c->streaming && c->watchdog_ms != 0u;
    const bool armed = c->phase != PH_NONE || watch;
    c->clock_in = (uint8_t)(c->phase <= PH_PLAIN ? CHECK_EVERY - 1u : 0u);
    return armed ? check_clock(c, fed, watch) : LEP_STEP_NONE;
}

/* ---- Stepping ---- */

/* Feed data[0..len) to the decoder and handle its events, up to and including
 * the byte that completes an outcome (*consumed: the bytes taken). Without an
 * outcome, the clock is looked at: at every step but a single byte, and
 * every CHECK_EVERY-th single-byte step (c->clock_in counts them down). */
static int step(lep_client *c, const uint8_t *data, size_t len, size_t *consumed)
{
    size_t pos = 0;
    int rc = LEP_STEP_NONE;
    bool due = true;
    c->kept_len = 0; /* the last outcome's message may be overwritten from here */
    if (len == 1u && c->clock_in > 0u) {
        c->clock_in--;
        due = false;
    }
    while (pos < len && rc == LEP_STEP_NONE) {
        lep_frame_event ev;
        pos += lep_frame_decoder_feed(&c->dec, data + pos, len - pos, &ev);
        if (ev.type != LEP_FRAME_NONE) {
            rc = on_event(c, &ev);
        }
    }
    *consumed = pos;
    if (rc != LEP_STEP_NONE || !due) {
        return rc; /* (a clock that was due stays due after an outcome) */
    }
    return clock_due(c, len > 0u);
}

int lep_client_step(lep_client *c, const uint8_t *data, size_t len, size_t *consumed)
{
    if (c == NULL || consumed == NULL || (data == NULL && len > 0)) {
        return LEP_E_ARG;
    }
    return step(c, data, len, consumed);
}

int lep_client_step_byte(lep_client *c, uint8_t b, lep_sample *out)
{
    size_t used;
    int rc;
    if (c == NULL) {
        return LEP_E_ARG;
    }
    rc = step(c, &b, 1u, &used);
    if (rc == LEP_STEP_SAMPLE && out != NULL) {
        (void)lep_client_get_sample(c, out); /* (LEP_OK: the sample just came) */
    }
    return rc;
}

/* ---- Blocking calls ---- */

/* Milliseconds until the next deadline of check_clock's two timers (at most
 * 0x7FFFFFFF: timeout_ms comes from an int), or NEVER when none is armed.
 * (The clock check just before took any fresh sample into the watchdog.) */
static uint32_t next_deadline(const lep_client *c)
{
    uint32_t t = now(c);
    uint32_t span = c->timeout_ms;
    uint32_t other = c->watchdog_ms;
    if (draining(c)) {
        span = c->quiet_ms;
        other = drain_limit(c, span);
    } else {
        if (c->phase == PH_NONE) {
            span = 0;
        }
        if (!c->streaming) {
            other = 0;
        }
    }
    span = left_of(t, c->t_start, span);
    other = left_of(t, c->t_aux, other);
    return other < span ? other : span;
}

/* v as an int (16 bits on some MCUs), saturated. */
static int clamp_int(int32_t v)
{
    const int max = (int)((unsigned)-1 >> 1);
    return v > (int32_t)max ? max : (int)v;
}

/* The read buffer: the attached one, or a one-byte one on the caller's stack. */
typedef struct reader {
    lep_client_rx *rx;
    size_t cap;
} reader;

static reader reader_of(lep_client *c, lep_client_rx *local)
{
    reader r;
    r.rx = c->rx != NULL ? c->rx : local;
    r.cap = c->rx != NULL ? sizeof(c->rx->buf) : 1u;
    local->pos = 0;
    local->len = 0;
    return r;
}

/* Step over the bytes already read, then (when they are all stepped without
 * an outcome, or there were none) check the clock: a blocking call never
 * reads past a deadline. */
static int step_buffered(lep_client *c, const reader *rd)
{
    size_t used = 0;
    lep_client_rx *rx = rd->rx;
    int rc = LEP_STEP_NONE;
    if (rx->pos < rx->len) {
        rc = step(c, rx->buf + rx->pos, (size_t)(rx->len - rx->pos), &used);
        rx->pos = (uint16_t)(rx->pos + used);
    }
    if (rc == LEP_STEP_NONE) { /* (all of it was consumed) */
        rc = step(c, NULL, 0, &used);
    }
    return rc;
}

/* Read more input (only once the bytes there are all stepped); > 0 bytes,
 * 0 on timeout, < 0 error. A read claiming more than it was allowed is a
 * broken backend: LEP_E_IO rather than a guess at the bytes. */
static int fill(lep_client *c, const reader *rd, int timeout_ms)
{
    int n = c->io.read(c->io.user, rd->rx->buf, rd->cap, timeout_ms);
    if (n > (int)rd->cap) {
        return LEP_E_IO;
    }
    if (n > 0) {
        rd->rx->pos = 0;
        rd->rx->len = (uint16_t)n;
    }
    return n;
}

/* The blocking calls' one waiting loop. With out NULL, drive the pending
 * transaction or recovery to its outcome (LEP_OK or its error; samples that
 * arrive meanwhile are skipped, a watchdog stall does not end it, a read
 * error ends it); the caller passes timeout_ms -1 (its deadlines bound it).
 * Otherwise wait for the next stream sample into *out; count_timeout says
 * whether a timeout is news. Once the time is up, one more read that does not
 * wait is made (so timeout 0 takes what is readable now); bytes that keep
 * arriving without completing a sample never extend the wait. */
static int wait_for(lep_client *c, lep_sample *out, int timeout_ms, bool count_timeout)
{
    lep_client_rx local;
    reader rd = reader_of(c, &local);
    uint32_t start = timeout_ms >= 0 ? now(c) : 0u;
    bool polled = false; /* the read after the time was up has been made */
    for (;;) {
        int rc = step_buffered(c, &rd);
        int n;
        int wait = timeout_ms;
        uint32_t clock;
        if (out == NULL) {
            if (rc == LEP_E_STALLED) {
                continue; /* counted; the transaction goes on (found by fuzz_client) */
            }
            if (rc == LEP_STEP_RESPONSE) {
                return LEP_OK;
            }
            if (rc == LEP_STEP_SAMPLE) {
                c->samples--; /* not delivered: skipped while waiting for another answer */
                c->unexpected++;
            }
        } else if (rc == LEP_STEP_SAMPLE) {
            return lep_client_get_sample(c, out);
        }
        if (rc < 0) {
            return rc;
        }
        if (rd.rx->pos < rd.rx->len) {
            continue;
        }
        if (timeout_ms >= 0) {
            uint32_t spent = now(c) - start;
            wait = spent >= (uint32_t)timeout_ms ? 0 : timeout_ms - (int)spent;
            if (wait == 0 && polled) {
                break;
            }
        }
        clock = next_deadline(c); /* (armed while a transaction or recovery is under way) */
        /* the sooner of the two (NEVER and a wait < 0 are forever) */
        n = fill(c, &rd, clock < (uint32_t)(int32_t)wait ? clamp_int((int32_t)clock) : wait);
        if (n < 0) {
            return out == NULL ? finish(c, n) : n;
        }
        polled = wait == 0;
        if (n == 0 && timeout_ms >= 0 && (wait == 0 || now(c) - start >= (uint32_t)timeout_ms)) {
            break;
        }
    }
    if (count_timeout) {
        c->timeouts++;
    }
    return LEP_E_TIMEOUT;
}

int lep_client_next_sample(lep_client *c, lep_sample *out, int timeout_ms)
{
    if (c == NULL || out == NULL || c->io.read == NULL) {
        return LEP_E_ARG;
    }
    if (!c->streaming) {
        return LEP_E_STATE;
    }
    return wait_for(c, out, timeout_ms, true);
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
    while (*n < max && wait_for(c, &out[*n], 0, false) == LEP_OK) {
        (*n)++;
    }
    return LEP_OK;
}

/* Drive the transaction or recovery just begun (rc: how its beginning went)
 * to its outcome. When it ends well and out is not NULL, out[0..size)
 * receives its answer: the whole lep_response when size is its size, else
 * the member of its union (every member begins at the union's start). */
static int complete(lep_client *c, int rc, void *out, size_t size)
{
    lep_response r;
    if (rc == LEP_OK) {
        rc = wait_for(c, NULL, -1, false);
    }
    if (rc == LEP_OK && out != NULL) {
        rc = lep_client_response(c, &r); /* (LEP_OK: the answer just came) */
        memcpy(out, size == sizeof(r) ? (const void *)&r : (const void *)&r.u, size);
    }
    return rc;
}

/* A blocking transaction of cmd, its answer copied as complete says. */
static int transact(lep_client *c, const lep_command *cmd, void *out, size_t size)
{
    if (c == NULL || cmd == NULL || c->io.read == NULL) {
        return LEP_E_ARG;
    }
    return complete(c, lep_client_send(c, cmd), out, size);
}

int lep_client_transact(lep_client *c, const lep_command *cmd, lep_response *resp)
{
    return transact(c, cmd, resp, sizeof(*resp));
}

/* A transaction of code (with the filter code filter), its answer's member
 * copied into out[0..size). LEP_E_ARG when the query needs out (size > 0)
 * and it is NULL. */
static int query(lep_client *c, uint8_t code, uint8_t filter, void *out, size_t size)
{
    lep_command cmd;
    cmd.code = code;
    cmd.filter = filter;
    if (out == NULL && size > 0u) {
        return LEP_E_ARG;
    }
    return transact(c, &cmd, out, size);
}

int lep_client_start(lep_client *c)
{
    return query(c, LEP_CMD_START, 0, NULL, 0);
}

int lep_client_stop(lep_client *c)
{
    return query(c, LEP_CMD_STOP, 0, NULL, 0);
}

int lep_client_product_info(lep_client *c, lep_product_info *out)
{
    return query(c, LEP_CMD_PRODUCT_INFO, 0, out, sizeof(*out));
}

int lep_client_rated(lep_client *c, lep_rated *out)
{
    return query(c, LEP_CMD_RATED, 0, out, sizeof(*out));
}

int lep_client_filter_get(lep_client *c, uint8_t *code)
{
    return query(c, LEP_CMD_FILTER_GET, 0, code, sizeof(*code));
}

int lep_client_filter_set(lep_client *c, uint8_t code)
{
    if (code > LEP_FILTER_MAX) {
        return LEP_E_VALUE;
    }
    return query(c, LEP_CMD_FILTER_SET, code, NULL, 0);
}

int lep_client_sample(lep_client *c, lep_sample *out)
{
    if (c != NULL && out != NULL && c->streaming) {
        return LEP_E_STATE;
    }
    return query(c, LEP_CMD_SAMPLE, 0, out, sizeof(*out));
}

int lep_client_sync(lep_client *c, int quiet_ms, lep_product_info *info)
{
    int rc;
    if (c == NULL || c->io.read == NULL) {
        return LEP_E_ARG;
    }
    rc = lep_client_recover(c, quiet_ms <= 0                  ? (uint16_t)0u
                               : (uint32_t)quiet_ms > 0xFFFFu ? (uint16_t)0xFFFFu
                                                              : (uint16_t)quiet_ms);
    return complete(c, rc, info, sizeof(*info));
}
