/* Frame codec: DLE stuffing, BCC, and the push decoder (spec 2.2-2.3). */
#include "leptrino/frame.h"

#include <string.h>

#include "leptrino/error.h"

enum {
    S_IDLE = 0,  /* between frames: hunting for DLE STX */
    S_IDLE_DLE,  /* between frames, after a DLE */
    S_MSG,       /* inside a frame */
    S_MSG_DLE,   /* inside a frame, after a DLE */
    S_BCC,       /* after DLE ETX: the next byte is the BCC */
    S_SKIP,      /* inside a rejected (over-long) frame: track escapes to its end */
    S_SKIP_DLE,  /* same, after a DLE */
    S_SKIP_BCC,  /* same, the BCC byte */
    S_BCC_DLE    /* between frames, after a frame whose BCC was 0x10: that byte may
                    also have been the DLE of a following DLE STX / DLE NAK */
};

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
    size_t n = 0;
    size_t i;
    if (msg == NULL || out == NULL || out_len == NULL || len == 0) {
        return LEP_E_ARG;
    }
    *out_len = 0;
    if (len > LEP_MAX_MESSAGE) {
        return LEP_E_TOO_LONG;
    }
    if (lep_frame_size(msg, len) > cap) {
        return LEP_E_BUFFER;
    }
    out[n++] = LEP_DLE;
    out[n++] = LEP_STX;
    for (i = 0; i < len; i++) {
        out[n++] = msg[i];
        if (msg[i] == LEP_DLE) {
            out[n++] = LEP_DLE;
        }
    }
    out[n++] = LEP_DLE;
    out[n++] = LEP_ETX;
    out[n++] = lep_bcc(msg, len); /* never stuffed, even when it is 0x10 */
    *out_len = n;
    return LEP_OK;
}

void lep_frame_decoder_init(lep_frame_decoder *d)
{
    if (d != NULL) {
        memset(d, 0, sizeof(*d));
        d->state = S_IDLE;
    }
}

bool lep_frame_decoder_busy(const lep_frame_decoder *d)
{
    return d != NULL && d->state != S_IDLE && d->state != S_IDLE_DLE && d->state != S_BCC_DLE;
}

static void begin_frame(lep_frame_decoder *d)
{
    d->state = S_MSG;
    d->len = 0;
    d->bcc = 0;
    d->raw = 2; /* DLE STX */
}

static void reject(lep_frame_decoder *d, lep_frame_event *ev, int error, uint8_t next_state)
{
    ev->type = LEP_FRAME_ERROR;
    ev->error = error;
    d->stats.bytes_discarded += d->raw;
    d->raw = 0;
    d->state = next_state;
    switch (error) {
    case LEP_E_BCC: d->stats.bcc_errors++; break;
    case LEP_E_ESCAPE: d->stats.escape_errors++; break;
    default: d->stats.overruns++; break;
    }
}

/* Append one message byte; false (and the frame rejected) past 128 bytes. */
static bool append(lep_frame_decoder *d, lep_frame_event *ev, uint8_t b)
{
    if (d->len >= LEP_MAX_MESSAGE) {
        reject(d, ev, LEP_E_TOO_LONG, S_SKIP);
        return false;
    }
    d->buf[d->len++] = b;
    d->bcc ^= b;
    return true;
}

/* A DLE NAK completed: deliver it and hunt for the next frame. */
static bool nak(lep_frame_decoder *d, lep_frame_event *ev)
{
    d->state = S_IDLE;
    d->raw = 0;
    d->stats.naks++;
    ev->type = LEP_FRAME_NAK;
    return true;
}

/* Advance by one byte; true when it completed an event. */
static bool step(lep_frame_decoder *d, uint8_t b, lep_frame_event *ev)
{
    switch (d->state) {
    case S_IDLE:
        if (b == LEP_DLE) {
            d->state = S_IDLE_DLE;
        } else {
            d->stats.bytes_discarded++;
        }
        return false;
    case S_IDLE_DLE:
        if (b == LEP_STX) {
            begin_frame(d);
        } else if (b == LEP_NAK) {
            return nak(d, ev);
        } else if (b == LEP_DLE) {
            d->stats.bytes_discarded++; /* the earlier DLE; this one may still start a frame */
        } else {
            d->stats.bytes_discarded += 2;
            d->state = S_IDLE;
        }
        return false;
    case S_MSG:
        d->raw++;
        if (b == LEP_DLE) {
            d->state = S_MSG_DLE;
            return false;
        }
        return !append(d, ev, b);
    case S_MSG_DLE:
        d->raw++;
        if (b == LEP_DLE) {
            d->state = S_MSG;
            return !append(d, ev, b);
        }
        if (b == LEP_ETX) {
            d->state = S_BCC;
            return false;
        }
        if (b == LEP_STX) {
            /* A new frame starts inside this one: drop the partial frame. */
            d->stats.bytes_discarded += (uint32_t)(d->raw - 2u);
            d->stats.restarts++;
            begin_frame(d);
            return false;
        }
        if (b == LEP_NAK) {
            /* The sensor NAKs while a frame of its is broken off: drop the
             * partial frame (an escape error) but never lose the NAK. */
            d->stats.bytes_discarded += (uint32_t)(d->raw - 2u);
            d->stats.escape_errors++;
            return nak(d, ev);
        }
        reject(d, ev, LEP_E_ESCAPE, S_IDLE);
        return true;
    case S_BCC: {
        uint8_t want = (uint8_t)(d->bcc ^ LEP_ETX);
        if (b == LEP_DLE && want != LEP_DLE) {
            /* The BCC byte was lost (or hit): this DLE may open the next frame,
             * so it is not counted with this one. */
            reject(d, ev, LEP_E_BCC, S_IDLE_DLE);
            return true;
        }
        d->raw++;
        if (b != want) {
            reject(d, ev, LEP_E_BCC, S_IDLE);
            return true;
        }
        if (d->len == 0) {
            /* DLE STX DLE ETX BCC: no Length byte, nothing to deliver. */
            ev->type = LEP_FRAME_ERROR;
            ev->error = LEP_E_LENGTH;
            d->stats.bytes_discarded += d->raw;
            d->raw = 0;
            d->state = S_IDLE;
            return true;
        }
        /* A BCC of 0x10 may also be the DLE of what follows: the true BCC was
         * lost and happened to be 0x10, or the next frame's DLE was lost. */
        d->state = b == LEP_DLE ? S_BCC_DLE : S_IDLE;
        d->raw = 0;
        d->stats.messages++;
        ev->type = LEP_FRAME_MESSAGE;
        ev->msg = d->buf;
        ev->len = d->len;
        return true;
    }
    case S_BCC_DLE:
        if (b == LEP_DLE) {
            d->state = S_IDLE_DLE;
        } else if (b == LEP_STX) {
            begin_frame(d);
            d->raw = 1; /* its DLE was counted with the frame before */
        } else if (b == LEP_NAK) {
            return nak(d, ev);
        } else {
            d->stats.bytes_discarded++;
            d->state = S_IDLE;
        }
        return false;
    case S_SKIP:
        if (b == LEP_DLE) {
            d->state = S_SKIP_DLE;
        } else {
            d->stats.bytes_discarded++;
        }
        return false;
    case S_SKIP_DLE:
        if (b == LEP_STX) {
            begin_frame(d);
        } else if (b == LEP_NAK) {
            return nak(d, ev);
        } else {
            d->stats.bytes_discarded += 2;
            d->state = b == LEP_ETX ? S_SKIP_BCC : (b == LEP_DLE ? S_SKIP : S_IDLE);
        }
        return false;
    default: /* S_SKIP_BCC: a DLE may be the BCC or the next frame's DLE (BCC lost) */
        if (b == LEP_DLE) {
            d->state = S_IDLE_DLE;
        } else {
            d->stats.bytes_discarded++;
            d->state = S_IDLE;
        }
        return false;
    }
}

size_t lep_frame_decoder_feed(lep_frame_decoder *d, const uint8_t *data, size_t len,
                              lep_frame_event *ev)
{
    size_t i;
    if (ev == NULL) {
        return 0;
    }
    if (d == NULL || (data == NULL && len > 0)) {
        ev->type = LEP_FRAME_ERROR;
        ev->error = LEP_E_ARG;
        ev->msg = NULL;
        ev->len = 0;
        return 0;
    }
    ev->type = LEP_FRAME_NONE;
    ev->error = LEP_OK;
    ev->msg = NULL;
    ev->len = 0;
    for (i = 0; i < len; i++) {
        if (step(d, data[i], ev)) {
            return i + 1;
        }
    }
    return len;
}
