/* Host-side client: transactions with resending, streaming, recovery, watchdog. */
#include "leptrino/client.h"

#include <stddef.h>
#include <string.h>

#include "leptrino/error.h"

#define ST_STREAM 0x01u /* continuous output is on */
#define ST_FRESH 0x02u  /* a sample arrived since the watchdog last looked */

/* Phases: what the client waits for (PH_NONE: nothing). Numbered so that a
 * transaction (or a recovery's stop) waits for its answer in the phases 1..4,
 * a recovery's stop phase + 2 is its drain, the drains are the phases >=
 * PH_DRAIN_SYNC, and a drain's phase - 4 is the phase of what it sends next. */
enum {
    PH_NONE = 0,       /* no transaction or recovery */
    PH_PLAIN = 1,      /* a plain transaction */
    PH_RESTARTED = 2,  /* the start sent after a recovery (not recovered twice) */
    PH_STOP_SYNC = 3,  /* recovery: its stop is out */
    PH_STOP_START = 4, /* a start refused with 0x04: the stop is out */
    PH_DRAIN_SYNC = 5, /* recovery: waiting for a quiet line, then identify */
    PH_DRAIN_START = 6 /* start recovery: waiting for a quiet line, then start again */
};

/* What a drain sends next: the product-info query (PH_DRAIN_SYNC) or the
 * start again (PH_DRAIN_START), as one multiply-add on the phase. */
#define DRAIN_NEXT_CODE(phase) ((phase)*8u + 2u)
typedef char lep_client_drain_codes[DRAIN_NEXT_CODE(PH_DRAIN_SYNC) == LEP_CMD_PRODUCT_INFO &&
                                            DRAIN_NEXT_CODE(PH_DRAIN_START) == LEP_CMD_START
                                        ? 1
                                        : -1];

/* The client's own counters (lep_client.count), in lep_client_stats order from retries on. */
enum {
    N_RETRIES,
    N_UNEXPECTED,
    N_INVALID,
    N_TIMEOUTS,
    N_SAMPLES,
    N_RESENT_TIMEOUT,
    N_RESENT_CONFIRMED,
    N_RECOVERIES,
    N_RESERVED,
    N_STALLS,
    N_COUNTERS
};

/* get_stats copies the counters as one block: the layouts must agree. */
#define COUNTERS_FIT                                                             \
    (sizeof(((lep_client *)0)->count) == N_COUNTERS * sizeof(uint32_t) &&        \
     offsetof(lep_client_stats, stalls) - offsetof(lep_client_stats, retries) == \
         (N_COUNTERS - 1) * sizeof(uint32_t))
typedef char lep_client_counters_fit[COUNTERS_FIT ? 1 : -1];

/* lep_client.fast counts single-byte steps up (lep_client_step_byte adds 1
 * first); the step that brings it to 0 looks at the clock (and at the state).
 * Its values after a look: */
#define CHECK_EVERY 32u                       /* single-byte steps between two clock reads */
#define FAST_CHECKED (0x10000u - CHECK_EVERY) /* a deadline is armed */
#define FAST_LOOK_NEXT 0xFFFFu                /* look at the clock on the next step */
typedef char lep_client_fast_values
    [(uint16_t) ~(CHECK_EVERY - 1u) == FAST_CHECKED && (uint16_t)~0u == FAST_LOOK_NEXT ? 1 : -1];
/* The event handling is inlined into both step entries when optimising for
 * speed (the one-byte entry then makes one call less per frame). */
#if defined(__GNUC__) && defined(__OPTIMIZE__) && !defined(__OPTIMIZE_SIZE__)
#define HOT static inline __attribute__((always_inline))
#else
#define HOT static
#endif

/* Helpers called from several places stay out of line in size builds. */
#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__)
#define SHARED static __attribute__((noinline))
#else
#define SHARED static
#endif

/* A one-liner that costs less than its call's argument set-up everywhere. */
#if defined(__GNUC__)
#define TINY static inline __attribute__((always_inline))
#else
#define TINY static
#endif

/* A deadline that is not armed. */
#define NEVER 0xFFFFFFFFu
/* The drain's timeout part is capped so the limit stays below 2^31 ms. */
#define DRAIN_TIMEOUT_CAP ((0x7FFFFFFFu - 0xFFFFu) / LEP_CLIENT_DRAIN_TIMEOUTS)

size_t lep_client_size(void)
{
    return sizeof(lep_client);
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

int lep_client_set_retries(lep_client *c, unsigned retries)
{
    if (c == NULL || retries > 255u) {
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
    /* The next step looks at the clock (the last outcome's message stays current). */
    c->msg_at = (uint16_t)(c->msg_at - c->fast + FAST_LOOK_NEXT);
    c->fast = (uint16_t)FAST_LOOK_NEXT;
    c->state = (uint8_t)(c->state | ST_FRESH); /* the watchdog's time runs from the next check */
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
    memcpy((unsigned char *)out + offsetof(lep_client_stats, retries), c->count, sizeof(c->count));
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
    return c != NULL && c->phase != PH_NONE;
}

/* When optimising for speed, a message that passed validation leaves its
 * decoded sample member (what lep_client_get_sample gives for a 20-byte one)
 * at the end of the decoder's buffer, past the longest valid message (room
 * the decoder writes only with a later frame's bytes, so it lives as long as
 * the message): a sample is read out without decoding the message again.
 * Size builds decode the kept message again instead (the same sample). */
#if !defined(__OPTIMIZE_SIZE__)
#define SPARE_SAMPLE(c) ((c)->dec.buf + (LEP_MAX_MESSAGE - sizeof(lep_sample)))
typedef char lep_client_spare_fits[LEP_LEN_PRODUCT_INFO_RATE + sizeof(lep_sample) <= LEP_MAX_MESSAGE
                                       ? 1
                                       : -1];
#endif

/* The message of the last outcome: LEP_OK, LEP_E_ARG (c or out NULL), or
 * LEP_E_STATE (none, or a single-byte step came since). */
static int outcome_kept(const lep_client *c, const void *out)
{
    if (c == NULL || out == NULL) {
        return LEP_E_ARG;
    }
    return c->msg_len == 0u || c->msg_at != c->fast ? LEP_E_STATE : LEP_OK;
}

int lep_client_response(const lep_client *c, lep_response *out)
{
    int rc = outcome_kept(c, out);
    if (rc == LEP_OK) {
        /* validated when it arrived; a refusal (0x04) gives LEP_E_SENSOR */
        (void)lep_response_decode(c->dec.buf, c->msg_len, out);
    }
    return rc;
}

int lep_client_get_sample(const lep_client *c, lep_sample *out)
{
#if defined(__OPTIMIZE_SIZE__)
    lep_response r;
    int rc = out == NULL ? LEP_E_ARG : lep_client_response(c, &r); /* (LEP_E_ARG, LEP_E_STATE) */
    if (rc == LEP_OK && c->msg_len != LEP_LEN_SAMPLE) {
        rc = LEP_E_STATE; /* (a sample is the only 20-byte message that makes an outcome) */
    }
    if (rc == LEP_OK) {
        *out = r.u.sample;
    }
    return rc;
#else
    if (c == NULL || out == NULL) {
        return LEP_E_ARG;
    }
    /* (a sample is the only 20-byte message that makes an outcome) */
    if (c->msg_len != LEP_LEN_SAMPLE || c->msg_at != c->fast) {
        return LEP_E_STATE;
    }
    memcpy(out, SPARE_SAMPLE(c), sizeof(*out));
    return LEP_OK;
#endif
}

TINY uint32_t now(const lep_client *c)
{
    return c->io.now_ms(c->io.user);
}

/* The transaction or recovery is over; returns rc, its outcome. */
static int finish(lep_client *c, int rc)
{
    c->phase = PH_NONE;
    return rc;
}

/* A transaction (or a recovery's stop) waits for its answer. */
static bool waiting(const lep_client *c)
{
    return (uint8_t)(c->phase - PH_PLAIN) < PH_DRAIN_SYNC - PH_PLAIN;
}

/* Write the pending command (again) and restart the attempt's clock. */
static int write_pending(lep_client *c)
{
    uint8_t frame[2u * LEP_LEN_FILTER_SET_CMD + 5u]; /* the longest command, every byte stuffed */
    size_t n;
    int rc;
    c->fast = (uint16_t)FAST_LOOK_NEXT; /* a deadline is armed */
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

/* Begin sending code (a new transaction or the next step of a recovery); the
 * filter code stays as it is (lep_command_encode reads it only for a filter set). */
SHARED int begin(lep_client *c, unsigned code, unsigned phase)
{
    c->msg_len = 0; /* (already 0 when a step begins the next part of a recovery) */
    c->cmd.code = (uint8_t)code;
    c->tries = 0;
    c->phase = (uint8_t)phase;
    return write_pending(c);
}

int lep_client_send(lep_client *c, const lep_command *cmd)
{
    if (c == NULL || cmd == NULL) {
        return LEP_E_ARG;
    }
    c->cmd.filter = cmd->filter;
    return begin(c, cmd->code, PH_PLAIN);
}

int lep_client_recover(lep_client *c, uint16_t quiet_ms)
{
    if (c == NULL) {
        return LEP_E_ARG;
    }
    c->quiet_ms = quiet_ms;                      /* (0: the default, see quiet_of) */
    c->state = (uint8_t)(c->state & ~ST_STREAM); /* a stream's data is stale from here on */
    return begin(c, LEP_CMD_STOP, PH_STOP_SYNC);
}

/* A recovery's stop is over (answered, refused or never got through): the
 * drain begins. False when no recovery's stop was pending. */
static bool stop_over(lep_client *c)
{
    if (c->phase != PH_STOP_SYNC && c->phase != PH_STOP_START) {
        return false;
    }
    c->phase = (uint8_t)(c->phase + 2u); /* (streaming is already off) */
    c->t_start = now(c);
    c->t_aux = c->t_start;
    return true;
}

/* The attempt is over with rc (LEP_STEP_RESPONSE: it ended well, streaming
 * follows the command; else its error). A recovery's stop goes on to its
 * drain instead (answered, refused or never got through: LEP_STEP_NONE). */
SHARED int settle(lep_client *c, int rc)
{
    if (stop_over(c)) {
        return LEP_STEP_NONE;
    }
    if (rc == LEP_E_TIMEOUT) {
        c->count[N_TIMEOUTS]++;
    }
    if (rc == LEP_STEP_RESPONSE) {
        if (c->cmd.code == LEP_CMD_START) {
            if (c->phase == PH_RESTARTED) {
                c->count[N_RECOVERIES]++;
            }
            c->state = (uint8_t)(c->state | ST_STREAM | ST_FRESH);
        } else if (c->cmd.code == LEP_CMD_STOP) {
            c->state = (uint8_t)(c->state & ~ST_STREAM);
        }
    }
    return finish(c, rc);
}

/* The answer to the pending command arrived: kept is its result code, result
 * what it means here (the same, or LEP_RESULT_STATE for data of a stream a
 * resent start began, whose first copy was executed). */
SHARED int on_answer(lep_client *c, uint8_t kept, unsigned result)
{
    c->last_result = kept;
    if (result == LEP_RESULT_STATE &&
        (c->cmd.code == LEP_CMD_START || c->cmd.code == LEP_CMD_STOP) &&
        c->phase <= PH_RESTARTED) { /* (not a recovery's stop: any answer to it will do) */
        if (c->tries > 0u) {
            c->count[N_RESENT_CONFIRMED]++; /* an earlier copy was executed */
            result = LEP_RESULT_OK;
        } else if (c->cmd.code == LEP_CMD_START && c->phase == PH_PLAIN &&
                   (c->state & ST_STREAM) == 0u) {
            /* A stream we did not start (a stale one) already runs. */
            return begin(c, LEP_CMD_STOP, PH_STOP_START); /* LEP_OK is LEP_STEP_NONE */
        }
    }
    return settle(c, result == LEP_RESULT_OK ? LEP_STEP_RESPONSE : LEP_E_SENSOR);
}

/* Handle one good frame; returns an outcome, or LEP_STEP_NONE to go on. */
HOT int on_message(lep_client *c, const lep_frame_event *ev)
{
    lep_response r;
    int rc = lep_response_decode(ev->msg, ev->len, &r);
    bool mine;
    if (rc != LEP_OK && rc != LEP_E_SENSOR) {
        c->count[N_INVALID]++;
        return LEP_STEP_NONE;
    }
#if !defined(__OPTIMIZE_SIZE__)
    memcpy(SPARE_SAMPLE(c), &r.u.sample, sizeof(r.u.sample));
#endif
    if (r.stream && (c->state & ST_STREAM) != 0u) {
        if (c->cmd.code == LEP_CMD_STOP && waiting(c)) {
            return LEP_STEP_NONE; /* our data still in flight before the stop answer */
        }
        c->count[N_SAMPLES]++;
        c->state = (uint8_t)(c->state | ST_FRESH);
        return LEP_STEP_SAMPLE;
    }
    mine = waiting(c) && r.code == c->cmd.code; /* (a data message's code is the start's) */
    if (mine && (!r.stream || c->tries > 0u)) {
        /* Our answer; or data of a stream we are starting: the first copy of
         * our resent start was executed, as if a copy were refused with 0x04
         * (the data's result is 0, which is kept). */
        return on_answer(c, r.result, r.result | (r.stream ? LEP_RESULT_STATE : 0u));
    }
    c->count[N_UNEXPECTED]++; /* e.g. a stream we did not start (a stale one), a late answer */
    return LEP_STEP_NONE;
}

/* The attempt failed, after a NAK (which is N_RETRIES) or a timeout (which is
 * N_RESENT_TIMEOUT): send again (counted in count[which]), or give up with
 * LEP_E_NAK or LEP_E_TIMEOUT. */
SHARED int attempt_failed(lep_client *c, unsigned which)
{
    if (!waiting(c)) {
        return LEP_STEP_NONE; /* (a NAK or a deadline of no attempt) */
    }
    if (c->tries < c->max_retries) {
        c->tries++;
        c->count[which]++;
        return write_pending(c);
    }
    /* (a stop of a recovery that never got through does not end it) */
    return settle(c, which == N_RETRIES ? LEP_E_NAK : LEP_E_TIMEOUT);
}

HOT int on_event(lep_client *c, const lep_frame_event *ev)
{
    if (ev->type == LEP_FRAME_MESSAGE) {
        return on_message(c, ev);
    }
    if (ev->type == LEP_FRAME_NAK) {
        return attempt_failed(c, N_RETRIES);
    }
    if (ev->error == LEP_E_LENGTH) {
        c->count[N_INVALID]++; /* an empty frame */
    }
    return LEP_STEP_NONE;
}

/* What is left at t of span begun at t0 (0 once it has passed); NEVER when
 * span is 0 (the timer is not armed). */
SHARED uint32_t left_of(uint32_t t, uint32_t t0, uint32_t span)
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

/* The drain's quiet time: quiet_ms, where 0 (what lep_client_init leaves) is
 * the default. */
TINY uint32_t quiet_of(const lep_client *c)
{
    return c->quiet_ms != 0u ? c->quiet_ms : LEP_CLIENT_DEFAULT_QUIET_MS;
}

/* The drain's limit: LEP_CLIENT_DRAIN_TIMEOUTS timeouts plus the quiet time. */
static uint32_t drain_limit(const lep_client *c, uint32_t quiet)
{
    uint32_t timeout = c->timeout_ms;
    return (timeout < DRAIN_TIMEOUT_CAP ? timeout : DRAIN_TIMEOUT_CAP) * LEP_CLIENT_DRAIN_TIMEOUTS +
           quiet;
}

/* The deadlines at the clock's time, fed saying bytes came in. Two timers:
 * the attempt's (the answer's timeout, or a drain's quiet time; from t_start)
 * and the other (a drain's limit, or the stream watchdog; from t_aux). A
 * drain's are armed throughout (quiet_ms and timeout_ms are never 0) and it
 * runs with streaming off; otherwise the attempt's is armed while a
 * transaction waits, the watchdog while streaming with watchdog_ms not 0. */
static int check_clock(lep_client *c, bool fed, bool watch)
{
    uint32_t t = now(c);
    if (c->phase >= PH_DRAIN_SYNC) {
        uint32_t quiet = quiet_of(c);
        if (fed) {
            c->t_start = t; /* not quiet yet */
        }
        if (expired(t, c->t_aux, drain_limit(c, quiet))) {
            return finish(c, LEP_E_NO_SYNC);
        }
        if (expired(t, c->t_start, quiet)) {
            return begin(c, DRAIN_NEXT_CODE(c->phase), c->phase - 4u);
        }
        return LEP_STEP_NONE;
    }
    if ((c->state & ST_FRESH) != 0u) {
        /* The watchdog's time runs from here. (Without streaming t_aux is not
         * read here; a start that succeeds sets ST_FRESH again.) */
        c->state = (uint8_t)(c->state & ~ST_FRESH);
        c->t_aux = t;
    }
    if (expired(t, c->t_start, c->timeout_ms)) { /* (attempt_failed: if one waits) */
        int rc = attempt_failed(c, N_RESENT_TIMEOUT);
        if (rc != LEP_STEP_NONE) {
            return rc;
        }
    }
    if (watch && expired(t, c->t_aux, c->watchdog_ms)) {
        c->t_aux = t;
        c->count[N_STALLS]++;
        return LEP_E_STALLED;
    }
    return LEP_STEP_NONE;
}

/* After the input (len bytes) is consumed without an outcome: watch the
 * clock, on single-byte steps only when c->fast has come round to 0 (every
 * CHECK_EVERY steps, every step during a recovery), and only while a deadline
 * is armed (otherwise c->fast just goes on counting). */
SHARED int step_clock(lep_client *c, size_t len)
{
    bool watch;
    if (len == 1u && c->fast != 0u) {
        return LEP_STEP_NONE;
    }
    watch = (c->state & ST_STREAM) != 0u && c->watchdog_ms != 0u; /* the watchdog */
    if (c->phase == PH_NONE && !watch) {
        return LEP_STEP_NONE; /* no deadline to watch */
    }
    /* FAST_CHECKED (~31) when at most a plain transaction waits, else
     * FAST_LOOK_NEXT (~0): no branch, no literal */
    c->fast = (uint16_t) ~((c->phase <= PH_PLAIN) * (CHECK_EVERY - 1u));
    return check_clock(c, len > 0u, watch); /* (nothing there changes watch) */
}

/* Handle the decoder's event ev (LEP_FRAME_NONE: nothing): an outcome, or
 * LEP_STEP_NONE to go on. */
HOT int take(lep_client *c, const lep_frame_event *ev)
{
    int rc;
    if (ev->type == LEP_FRAME_NONE) {
        return LEP_STEP_NONE;
    }
    rc = on_event(c, ev);
    if (rc == LEP_STEP_NONE) {
        return rc;
    }
    if (c->fast == 0u) {
        c->fast = (uint16_t)FAST_LOOK_NEXT; /* the clock was due: look on the next step */
    }
    if (rc > 0) { /* a response or a sample: keep its message (feed delivers it at dec.buf) */
        c->msg_len = (uint8_t)ev->len;
        c->msg_at = c->fast;
        if (ev->len == LEP_LEN_SAMPLE && ev->msg[LEP_LEN_SAMPLE - 1u] != 0u) {
            c->count[N_RESERVED]++; /* a sample's last reserved byte (unspecified) */
        }
    }
    return rc;
}

/* lep_client_step for any input but a single byte (at -Os: any input). Out
 * of line when optimising for speed, so the one-byte path saves no registers. */
#if defined(__GNUC__) && !defined(__OPTIMIZE_SIZE__)
__attribute__((noinline))
#endif
static int
step_input(lep_client *c, const uint8_t *data, size_t len, size_t *consumed)
{
    size_t pos = 0;
    c->msg_len = 0;
    while (pos < len) {
        lep_frame_event ev;
        int rc;
#if defined(__OPTIMIZE_SIZE__) /* a byte at a time: the firmware links no feed loop */
        (void)lep_frame_decoder_feed_byte(&c->dec, data[pos], &ev);
        pos++;
#else
        pos += lep_frame_decoder_feed(&c->dec, data + pos, len - pos, &ev);
#endif
        rc = take(c, &ev);
        if (rc != LEP_STEP_NONE) {
            *consumed = pos;
            return rc;
        }
    }
    *consumed = len;
    return step_clock(c, len);
}

int(lep_client_step)(lep_client *c, const uint8_t *data, size_t len, size_t *consumed)
{
    if (c == NULL || consumed == NULL || (data == NULL && len > 0)) {
        return LEP_E_ARG;
    }
#if defined(__OPTIMIZE_SIZE__)
    if (len == 1u) {
        c->fast++; /* counted like lep_client_step_byte */
    }
#else
    if (len == 1u) { /* the same, without the loop */
        *consumed = 1;
        return lep_client_step_byte(c, data[0], NULL);
    }
#endif
    return step_input(c, data, len, consumed);
}

/* (lep_client_step_byte counted the step in c->fast.) */
int lep_client_step_byte_slow(lep_client *c, uint8_t b, lep_sample *out)
{
    int rc;
#if defined(__OPTIMIZE_SIZE__)
    size_t used;
    rc = step_input(c, &b, 1, &used);
#else /* step_input for one byte, without its loop */
    lep_frame_event ev;
    c->msg_len = 0;
    if (c->fast == 0u && lep_frame_decoder_push1(&c->dec, b)) {
        return step_clock(c, 1); /* only the clock was due (the inline path left b alone) */
    }
    (void)lep_frame_decoder_feed(&c->dec, &b, 1, &ev);
    rc = take(c, &ev);
    if (rc == LEP_STEP_NONE) {
        return step_clock(c, 1);
    }
#endif
    if (rc == LEP_STEP_SAMPLE) {
        (void)lep_client_get_sample(c, out); /* (nothing when out is NULL) */
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
    if (c->phase >= PH_DRAIN_SYNC) {
        span = quiet_of(c);
        other = drain_limit(c, span);
    } else {
        if (c->phase == PH_NONE) {
            span = 0;
        }
        if ((c->state & ST_STREAM) == 0u) {
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
        rc = lep_client_step(c, rx->buf + rx->pos, (size_t)(rx->len - rx->pos), &used);
        rx->pos = (uint16_t)(rx->pos + used);
    }
    if (rc == LEP_STEP_NONE) { /* (all of it was consumed) */
        rc = lep_client_step(c, NULL, 0, &used);
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
                c->count[N_SAMPLES]--; /* not delivered: skipped while waiting for another answer */
                c->count[N_UNEXPECTED]++;
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
        c->count[N_TIMEOUTS]++;
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
SHARED int complete(lep_client *c, int rc, void *out, size_t size)
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
SHARED int transact(lep_client *c, const lep_command *cmd, void *out, size_t size)
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
SHARED int query(lep_client *c, uint8_t code, uint8_t filter, void *out, size_t size)
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
    if (c != NULL && out != NULL && (c->state & ST_STREAM) != 0u) {
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
