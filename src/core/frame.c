/* Frame codec: DLE stuffing, BCC, and the push decoder (spec 2.2-2.3).
 *
 * How this file is organised, top to bottom:
 *  1. the encoder side: lep_bcc, lep_frame_size, lep_frame_encode;
 *  2. the decoder's states (enum state), and the small steps that several
 *     transitions share (begin a frame, drop it, take a message byte, hunt
 *     for the next frame);
 *  3. take_byte(), THE decoder: one switch on the state taking one byte, with
 *     its counters; nothing else decides a transition. It returns what the
 *     byte completed, and make_event() turns that into the event;
 *  4. run(), the loop that feeds take_byte a chunk of input up to the first
 *     event. In the body state it copies the run of plain message bytes that
 *     follows in one go (copy_body_run: what take_byte would do with each);
 *  5. the public entry points, each a call of run(): lep_frame_decoder_feed
 *     (up to the first event), _feed_byte (one byte), _feed_all (run again
 *     after each event, handing it to a handler).
 *
 * Every byte on the wire is accounted for: it ends up in a delivered message
 * or NAK, or it is added to stats.bytes_discarded. Bytes of a frame still in
 * progress are counted when the frame ends (d->len message bytes plus d->raw
 * other wire bytes: DLE STX, stuffing DLEs, DLE ETX). Since run() stops only
 * between two bytes and keeps everything in *d, any chunking of the same input
 * gives the same events and counters. The rules where the spec is silent are
 * listed with the shared vectors in test/vectors/README.md. */
#include "leptrino/frame.h"

#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "leptrino/error.h"

uint8_t lep_bcc(const uint8_t *msg, size_t len)
{
    uint8_t bcc = LEP_ETX;
    size_t i;
    if (msg == NULL) {
        return bcc;
    }
    for (i = 0; i < len; i++) {
        bcc ^= msg[i];
    }
    return bcc;
}

size_t lep_frame_size(const uint8_t *msg, size_t len)
{
    size_t n = 5u + len;
    size_t i;
    if (msg == NULL) {
        return 0;
    }
    for (i = 0; i < len; i++) {
        if (msg[i] == LEP_DLE) {
            n++;
        }
    }
    return n;
}

int lep_frame_encode(const uint8_t *msg, size_t len, uint8_t *out, size_t cap, size_t *out_len)
{
    uint8_t bcc = LEP_ETX;
    size_t n;
    size_t i;
    if (msg == NULL || out == NULL || out_len == NULL || len == 0) {
        return LEP_E_ARG;
    }
    *out_len = 0;
    if (len > LEP_MAX_MESSAGE) {
        return LEP_E_TOO_LONG;
    }
    n = lep_frame_size(msg, len);
    if (n > cap) {
        return LEP_E_BUFFER;
    }
    *out_len = n;
    *out++ = LEP_DLE;
    *out++ = LEP_STX;
    for (i = 0; i < len; i++) {
        bcc ^= msg[i];
        *out++ = msg[i];
        if (msg[i] == LEP_DLE) {
            *out++ = LEP_DLE;
        }
    }
    out[0] = LEP_DLE;
    out[1] = LEP_ETX;
    out[2] = bcc; /* never stuffed, even when it is 0x10 */
    return LEP_OK;
}

/* ---- The decoder ---- */

/* The decoder's states (lep_frame_decoder.state). The first three are between
 * frames, the others inside one (lep_frame_decoder_busy). */
enum state {
    S_IDLE = 0, /* hunting for DLE STX (what lep_frame_decoder_init sets) */
    S_IDLE_DLE, /* hunting, after a DLE: STX opens a frame, NAK is a NAK */
    S_BCC_DLE,  /* a message just ended with a BCC of 0x10: that byte may also have
                   been the DLE of a DLE STX or DLE NAK that follows */
    S_BODY,     /* inside a frame, after DLE STX: message bytes */
    S_BODY_DLE, /* inside a frame, after a DLE */
    S_BCC,      /* after DLE ETX: this byte is the BCC */
    S_SKIP,     /* inside a rejected (over-long) frame: follow its stuffing to its end */
    S_SKIP_DLE, /* the same, after a DLE */
    S_SKIP_BCC  /* the same, the BCC byte after its DLE ETX */
};

void lep_frame_decoder_init(lep_frame_decoder *d)
{
    if (d != NULL) {
        memset(d, 0, sizeof(*d)); /* S_IDLE, empty, counters zero */
    }
}

size_t lep_frame_decoder_sizeof(void)
{
    return sizeof(lep_frame_decoder);
}

int lep_frame_decoder_busy(const lep_frame_decoder *d)
{
    return d != NULL && d->state >= S_BODY;
}

void lep_frame_decoder_get_stats(const lep_frame_decoder *d, lep_frame_stats *out)
{
    if (d != NULL && out != NULL) {
        *out = d->stats;
    }
}

/* The wire bytes of the frame in progress: its message bytes so far and the
 * others (DLE STX, stuffing, DLE ETX). */
static uint32_t frame_wire(const lep_frame_decoder *d)
{
    return (uint32_t)d->len + d->raw;
}

/* DLE STX: a frame begins. `raw` is its DLE STX's share of the wire bytes (1
 * when its DLE was counted already, as a message's 0x10 BCC). */
static void begin_frame(lep_frame_decoder *d, uint16_t raw)
{
    d->len = 0;
    d->bcc = 0;
    d->raw = raw;
    d->state = S_BODY;
}

/* The frame in progress is dropped: its wire bytes so far, and `more` after
 * them, are counted as discarded. */
static void drop_frame(lep_frame_decoder *d, uint32_t more)
{
    d->stats.bytes_discarded += frame_wire(d) + more;
}

/* A message byte b (plain or stuffed) in the body state: appended, or the
 * 129th one, which rejects the frame (its bytes so far and b are discarded). */
static int message_byte(lep_frame_decoder *d, uint8_t b)
{
    if (d->len == LEP_MAX_MESSAGE) { /* follow the frame to its end */
        d->stats.overruns++;
        drop_frame(d, 1u);
        d->state = S_SKIP;
        return LEP_E_TOO_LONG;
    }
    d->buf[d->len++] = b;
    d->bcc ^= b;
    return LEP_FRAME_NONE;
}

/* Between frames: a DLE may start a frame, any other byte is discarded. */
static int hunt(lep_frame_decoder *d, uint8_t b)
{
    d->state = S_IDLE_DLE;
    if (b != LEP_DLE) {
        d->stats.bytes_discarded++;
        d->state = S_IDLE;
    }
    return LEP_FRAME_NONE;
}

/* Take the one byte b: the transition of the current state, with its
 * counters. Returns what b completes: LEP_FRAME_NONE (nothing),
 * LEP_FRAME_MESSAGE, LEP_FRAME_NAK, or the LEP_E_* error of a rejected frame
 * (its wire bytes are counted as discarded here). */
static int take_byte(lep_frame_decoder *d, uint8_t b)
{
    switch ((enum state)d->state) {
    case S_BODY:
        if (b == LEP_DLE) {
            d->state = S_BODY_DLE;
            return LEP_FRAME_NONE;
        }
        return message_byte(d, b);

    case S_BODY_DLE:
        if (b == LEP_ETX) { /* the message is complete: its BCC follows */
            d->raw = (uint16_t)(d->raw + 2u);
            d->state = S_BCC;
        } else if (b == LEP_DLE) { /* a stuffed 0x10: the first DLE was stuffing */
            d->raw++;
            d->state = S_BODY;
            return message_byte(d, b);
        } else if (b == LEP_STX) { /* a new frame: the partial one is abandoned */
            d->stats.restarts++;
            drop_frame(d, 0u);
            begin_frame(d, 2u);
        } else if (b == LEP_NAK) {
            /* The sensor NAKs while a frame of its is broken off: drop the
             * partial frame (an escape error, no event of its own) but never
             * lose the NAK. */
            d->stats.escape_errors++;
            drop_frame(d, 0u);
            d->stats.naks++;
            d->state = S_IDLE;
            return LEP_FRAME_NAK;
        } else { /* DLE and an illegal byte: hunt again from the next byte */
            d->stats.escape_errors++;
            drop_frame(d, 2u);
            d->state = S_IDLE;
            return LEP_E_ESCAPE;
        }
        return LEP_FRAME_NONE;

    case S_BCC: /* every BCC byte completes an event */
        d->state = S_IDLE;
        if (b == (uint8_t)(d->bcc ^ LEP_ETX) && d->len != 0u) {
            d->stats.messages++;
            if (b == LEP_DLE) { /* (a BCC of 0x10 may also be the next DLE) */
                d->state = S_BCC_DLE;
            }
            return LEP_FRAME_MESSAGE;
        }
        drop_frame(d, 1u);
        if (d->len == 0u && b == LEP_ETX) { /* DLE STX DLE ETX BCC: nothing to deliver */
            return LEP_E_LENGTH;            /* (counted as discarded bytes only) */
        }
        d->stats.bcc_errors++;
        if (b == LEP_DLE) {
            /* The BCC byte was lost (or hit): this DLE may open the next
             * frame, so it is not counted with this one. */
            d->stats.bytes_discarded--;
            d->state = S_IDLE_DLE;
        }
        return LEP_E_BCC;

    case S_IDLE:
        return hunt(d, b);

    case S_IDLE_DLE:
    case S_BCC_DLE:
    case S_SKIP_DLE:
        if (b == LEP_STX) {
            /* a frame begins; after a 0x10 BCC its DLE was counted with the message */
            begin_frame(d, d->state == S_BCC_DLE ? 1u : 2u);
            return LEP_FRAME_NONE;
        }
        if (b == LEP_NAK) {
            d->stats.naks++;
            d->state = S_IDLE;
            return LEP_FRAME_NAK;
        }
        if (d->state == S_SKIP_DLE) { /* inside a rejected frame: its DLE and b */
            d->stats.bytes_discarded += 2u;
            d->state = b == LEP_ETX ? S_SKIP_BCC : b == LEP_DLE ? S_SKIP : S_IDLE;
            return LEP_FRAME_NONE;
        }
        if (d->state == S_IDLE_DLE) { /* (a message's 0x10 BCC was counted with it) */
            d->stats.bytes_discarded++;
        }
        return hunt(d, b);

    case S_SKIP:
        if (b == LEP_DLE) {
            d->state = S_SKIP_DLE;
        } else {
            d->stats.bytes_discarded++;
        }
        return LEP_FRAME_NONE;

    default: /* S_SKIP_BCC: a DLE here may be the BCC or the next frame's DLE */
        return hunt(d, b);
    }
}

/* The event of what take_byte returned (not LEP_FRAME_NONE). */
static void make_event(const lep_frame_decoder *d, int what, lep_frame_event *ev)
{
    const bool message = what == LEP_FRAME_MESSAGE;
    ev->type = what < 0 ? LEP_FRAME_ERROR : what;
    ev->error = what < 0 ? what : LEP_OK;
    ev->msg = message ? d->buf : NULL;
    ev->len = message ? d->len : 0u;
}

/* In the body state, plain message bytes (not a DLE, with room in the buffer)
 * change nothing but the message: copy the run of them at p in one loop,
 * exactly what take_byte would do with each, up to a DLE, the end of the input
 * or a full buffer. Returns where the run stopped. */
static const uint8_t *copy_body_run(lep_frame_decoder *d, const uint8_t *p, const uint8_t *end)
{
    size_t n = d->len;
    uint8_t bcc = d->bcc;
    while (p < end && *p != LEP_DLE && n < LEP_MAX_MESSAGE) {
        bcc ^= *p;
        d->buf[n++] = *p++;
    }
    d->len = (uint16_t)n;
    d->bcc = bcc;
    return p;
}

/* The decoder over the bytes p[0..end): stops after the byte that completes
 * an event, or at the end of the input (ev->type LEP_FRAME_NONE). Returns
 * where it stopped. */
static const uint8_t *run(lep_frame_decoder *d, const uint8_t *p, const uint8_t *end,
                          lep_frame_event *ev)
{
    ev->type = LEP_FRAME_NONE;
    while (p < end) {
        const int what = take_byte(d, *p++);
        if (what != LEP_FRAME_NONE) {
            make_event(d, what, ev);
            break;
        }
        if (d->state == S_BODY && p < end && *p != LEP_DLE) {
            p = copy_body_run(d, p, end);
        }
    }
    return p;
}

/* A call with a NULL decoder, event or data: ev (when not NULL) says why. */
static void bad_call(const lep_frame_decoder *d, size_t len, lep_frame_event *ev)
{
    if (ev != NULL) {
        const bool nothing_to_read = d != NULL && len == 0; /* only data was NULL */
        ev->type = nothing_to_read ? LEP_FRAME_NONE : LEP_FRAME_ERROR;
        ev->error = nothing_to_read ? LEP_OK : LEP_E_ARG;
        ev->msg = NULL;
        ev->len = 0;
    }
}

size_t lep_frame_decoder_feed(lep_frame_decoder *d, const uint8_t *data, size_t len,
                              lep_frame_event *ev)
{
    if (d == NULL || data == NULL || ev == NULL) {
        bad_call(d, len, ev);
        return 0;
    }
    return (size_t)(run(d, data, data + len, ev) - data);
}

int lep_frame_decoder_feed_byte(lep_frame_decoder *d, uint8_t b, lep_frame_event *ev)
{
    if (d == NULL || ev == NULL) {
        bad_call(d, 1u, ev);
        return LEP_E_ARG;
    }
    (void)run(d, &b, &b + 1, ev);
    return LEP_OK;
}

int lep_frame_decoder_feed_all(lep_frame_decoder *d, const uint8_t *data, size_t len,
                               lep_frame_handler on_event, void *user)
{
    lep_frame_event ev;
    if (d == NULL || on_event == NULL || (data == NULL && len > 0)) {
        return LEP_E_ARG;
    }
    while (len > 0) {
        const uint8_t *next = run(d, data, data + len, &ev);
        len -= (size_t)(next - data);
        data = next;
        if (ev.type != LEP_FRAME_NONE) {
            on_event(user, &ev);
        }
    }
    return LEP_OK;
}
