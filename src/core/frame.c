/* Frame codec: DLE stuffing, BCC, and the push decoder (spec 2.2-2.3).
 *
 * The decoder is a state machine written as labelled code, one label per
 * state, so each byte costs a compare and a jump to the next state's code
 * instead of a dispatch. Inside a frame it copies a machine word at a time while
 * the word holds no DLE (a SWAR test) and folds the word into the BCC; at a chunk
 * end it copies byte by byte. It is plain C over memcpy, so it gives the same
 * result on any byte order and word size, and it stops only at a state
 * boundary, which is what makes any chunking give the same events. */
#include "leptrino/frame.h"

#include <stddef.h>
#include <string.h>

#include "leptrino/error.h"

/* The first five are frame.h's LEP_FRAME_ST_*_: lep_frame_decoder_push1 there
 * is the inline copy of feed_byte's transitions that raise no event and count
 * nothing (the client's one-byte path; the client tests hold it to the same
 * events at every chunking). */
enum {
    S_IDLE = LEP_FRAME_ST_IDLE_,         /* between frames: hunting for DLE STX */
    S_IDLE_DLE = LEP_FRAME_ST_IDLE_DLE_, /* between frames, after a DLE */
    S_MSG = LEP_FRAME_ST_BODY_,          /* inside a frame */
    S_MSG_DLE = LEP_FRAME_ST_BODY_DLE_,  /* inside a frame, after a DLE */
    S_BCC = LEP_FRAME_ST_BCC_,           /* after DLE ETX: the next byte is the BCC */
    S_SKIP,     /* inside a rejected (over-long) frame: track escapes to its end */
    S_SKIP_DLE, /* same, after a DLE */
    S_SKIP_BCC, /* same, the BCC byte */
    S_BCC_DLE   /* between frames, after a frame whose BCC was 0x10: that byte may
                    also have been the DLE of a following DLE STX / DLE NAK */
};

/* The word-at-a-time machine (decode below) is built unless the build
 * optimises for size or defines LEPTRINO_FRAME_SMALL: then the one-byte machine
 * is lep_frame_decoder_feed_byte, and feed and feed_all are loops over it (a
 * firmware fed byte by byte links no loop of the decoder's), for about a fifth
 * of the flash and several times the instructions per byte. The tests run both
 * builds. */
#if !defined(LEPTRINO_FRAME_SMALL) && !defined(__OPTIMIZE_SIZE__)
#define FRAME_FAST 1
#endif

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

void lep_frame_decoder_init(lep_frame_decoder *d)
{
    if (d != NULL) {
        memset(d, 0, sizeof(*d)); /* S_IDLE is 0 */
    }
}

/* Busy in every state but S_IDLE, S_IDLE_DLE and S_BCC_DLE (between frames). */
#define BUSY_STATES                                                                            \
    ((1u << S_MSG) | (1u << S_MSG_DLE) | (1u << S_BCC) | (1u << S_SKIP) | (1u << S_SKIP_DLE) | \
     (1u << S_SKIP_BCC))

bool lep_frame_decoder_busy(const lep_frame_decoder *d)
{
    return d != NULL && ((BUSY_STATES >> d->state) & 1u) != 0;
}

#ifdef FRAME_FAST
/* A machine word of bytes for the fast path: size_t is the register width on
 * the targets we know (8 bytes on x86-64, 4 on a Cortex-M0+). */
typedef size_t word_t;
#define W_SIZE sizeof(word_t)
#define W_ONES ((word_t)-1 / 0xFFu) /* 0x0101...01 */
#define W_HIGH (W_ONES * 0x80u)     /* 0x8080...80 */
#define W_DLES (W_ONES * LEP_DLE)   /* 0x1010...10 */

/* Non-zero when some byte of w is 0x10 (a zero byte of w ^ 0x1010...: the
 * high bit of a byte of w ^ 0x10 is that of w). On a little-endian machine
 * its lowest set bit is exact: it marks the first such byte in memory order. */
static word_t has_dle(word_t w)
{
    return ((w ^ W_DLES) - W_ONES) & ~w & W_HIGH;
}

/* Index of the first DLE in the word at p, given has_dle() of it (non-zero). */
#if defined(__GNUC__) && defined(__BYTE_ORDER__) && defined(__ORDER_LITTLE_ENDIAN__) && \
    (defined(__x86_64__) || defined(__i386__) || defined(__aarch64__))
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define FIRST_DLE(m, p) ((size_t)__builtin_ctzll((unsigned long long)(m)) / 8u)
#endif
#endif
#ifndef FIRST_DLE
static size_t first_dle(const uint8_t *p)
{
    size_t k = 0;
    while (p[k] != LEP_DLE) {
        k++;
    }
    return k;
}
#define FIRST_DLE(m, p) first_dle(p)
#endif

/* The first k bytes of a word (k < W_SIZE), in memory order on any machine. */
static word_t first_bytes(word_t w, size_t k)
{
    /* Eight 0xFF then zeros: W_SIZE bytes from keep + 8 - k are k 0xFF bytes
     * then zeros, for any word of up to 8 bytes (4 on a 32-bit target). */
    static const uint8_t keep[16] = { 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF };
    word_t m;
    memcpy(&m, keep + (8u - k), W_SIZE);
    return w & m;
}

/* XOR of the bytes of a word. */
static uint8_t fold(word_t acc)
{
    size_t shift;
    for (shift = W_SIZE * 4u; shift >= 8u; shift /= 2u) {
        acc ^= acc >> shift;
    }
    return (uint8_t)acc;
}

#endif /* FRAME_FAST */

/* Wrong arguments (kept out of the decoding path). */
static size_t feed_bad_call(const lep_frame_decoder *d, size_t len, lep_frame_event *ev)
{
    if (ev != NULL) {
        const bool nothing_to_read = d != NULL && len == 0; /* only data was NULL */
        ev->type = nothing_to_read ? LEP_FRAME_NONE : LEP_FRAME_ERROR;
        ev->error = nothing_to_read ? LEP_OK : LEP_E_ARG;
        ev->msg = NULL;
        ev->len = 0;
    }
    return 0;
}

/* What a byte completes: the event types, then the errors as their negated
 * codes (they index k_counter below, so they must run 0..6). */
enum {
    K_NONE = LEP_FRAME_NONE,
    K_MESSAGE = LEP_FRAME_MESSAGE,
    K_NAK = LEP_FRAME_NAK,
    K_TOO_LONG = -LEP_E_TOO_LONG,
    K_BCC = -LEP_E_BCC,
    K_ESCAPE = -LEP_E_ESCAPE,
    K_LENGTH = -LEP_E_LENGTH
};
typedef char k_kinds_run_0_to_6
    [(K_NAK == 2 && K_TOO_LONG == 3 && K_BCC == 4 && K_ESCAPE == 5 && K_LENGTH == 6) ? 1 : -1];
#define STAT_(field) ((uint8_t)offsetof(lep_frame_stats, field))
/* The counter each adds one to (an empty frame's is bytes_discarded: the one
 * is its BCC byte, the rest of the frame is counted before). */
static const uint8_t k_counter[] = {
    STAT_(bytes_discarded), STAT_(messages),      STAT_(naks),           STAT_(overruns),
    STAT_(bcc_errors),      STAT_(escape_errors), STAT_(bytes_discarded)
};

/* Add n to the counter at offset off (an offsetof of one of its uint32_t
 * members) of d's stats. */
static void count(lep_frame_decoder *d, size_t off, size_t n)
{
    uint32_t *c = (uint32_t *)(void *)((unsigned char *)&d->stats + off);
    *c += (uint32_t)n;
}

/* In the word-at-a-time build, feed_byte takes the usual bytes inline and
 * calls step for the others (on one line with the name, so that both builds
 * place the functions on the same lines for the coverage report). */
#if defined(FRAME_FAST) && defined(__GNUC__) && defined(__OPTIMIZE__)
#define STEP_ATTR __attribute__((noinline))
#define FEED_BYTE_ATTR __attribute__((always_inline)) inline
#else
#define STEP_ATTR
#define FEED_BYTE_ATTR
#endif

/* One byte (the path of a caller fed byte by byte, e.g. from an ISR ring
 * buffer): a switch on the state, and every outcome ends in one place that
 * counts the discarded bytes, makes the event and counts it, and stores the
 * next state. In the word-at-a-time build, feed_byte below takes the usual
 * bytes inline and comes here for the others. */
STEP_ATTR static size_t step(lep_frame_decoder *d, uint8_t b, lep_frame_event *ev)
{
    const unsigned st = d->state;
    size_t disc = (size_t)d->len + d->raw; /* wire bytes of the frame so far */
    unsigned kind = K_NONE;
    unsigned next = S_IDLE;
    switch (st) {
    case S_MSG:
        if (b == LEP_DLE) {
            next = S_MSG_DLE;
            disc = 0;
            break;
        }
    append: /* a message byte */
        if (d->len < LEP_MAX_MESSAGE) {
            d->buf[d->len++] = b;
            d->bcc ^= b;
            next = S_MSG;
            disc = 0;
            break;
        }
        kind = K_TOO_LONG; /* the 129th message byte */
        disc++;
        next = S_SKIP;
        break;
    case S_BCC: /* disc is the frame without this byte */
        if (b == (uint8_t)(d->bcc ^ LEP_ETX)) {
            kind = K_LENGTH; /* (its counter counts this byte) */
            if (d->len != 0) {
                kind = K_MESSAGE;
                disc = 0;
                if (b == LEP_DLE) {
                    next = S_BCC_DLE;
                }
            }
            break;
        }
        kind = K_BCC;
        if (b == LEP_DLE) { /* this DLE may open the next frame */
            next = S_IDLE_DLE;
        } else {
            disc++;
        }
        break;
    case S_MSG_DLE:
        if (b == LEP_ETX) {
            d->raw = (uint16_t)(d->raw + 2u);
            next = S_BCC;
            disc = 0;
            break;
        }
        if (b == LEP_DLE) { /* stuffed */
            d->raw++;
            disc++;
            goto append;
        }
        if (b == LEP_STX || b == LEP_NAK) { /* the partial frame is dropped */
            count(d, b == LEP_STX ? STAT_(restarts) : STAT_(escape_errors), 1);
            count(d, STAT_(bytes_discarded), disc);
            goto after_dle;
        }
        kind = K_ESCAPE;
        disc += 2u;
        break;
    case S_IDLE_DLE:
    case S_BCC_DLE:
    case S_SKIP_DLE:
        if (b == LEP_STX || b == LEP_NAK) {
        after_dle:
            disc = 0;
            if (b == LEP_NAK) {
                kind = K_NAK;
                break;
            }
            /* a frame begins; after a 0x10 BCC its DLE was counted with that frame */
            d->raw = st == S_BCC_DLE ? 1u : 2u;
            d->len = 0;
            d->bcc = 0;
            next = S_MSG;
            break;
        }
        if (st == S_SKIP_DLE) {
            disc = 2;
            if (b == LEP_ETX) {
                next = S_SKIP_BCC;
            } else if (b == LEP_DLE) {
                next = S_SKIP;
            }
            break;
        }
        /* between frames: the DLE before is discarded unless counted already */
        disc = st == S_IDLE_DLE ? 1u : 0u;
        goto between;
    default: /* S_IDLE, S_SKIP, S_SKIP_BCC */
        disc = 0;
        if (st == S_SKIP) {
            next = S_SKIP;
            if (b == LEP_DLE) {
                next = S_SKIP_DLE;
                break;
            }
            disc = 1;
            break;
        }
    between:
        if (b == LEP_DLE) {
            next = S_IDLE_DLE; /* this one may start a frame */
        } else {
            disc++;
        }
        break;
    }
    d->state = (uint8_t)next;
    count(d, STAT_(bytes_discarded), disc);
    ev->type = kind < K_TOO_LONG ? (int)kind : LEP_FRAME_ERROR;
    if (kind != K_NONE) {
        count(d, k_counter[kind], 1);
        ev->error = kind < K_TOO_LONG ? LEP_OK : -(int)kind;
        ev->msg = NULL;
        ev->len = 0;
        if (kind == K_MESSAGE) {
            ev->msg = d->buf;
            ev->len = d->len;
        }
    }
    return 1;
}

FEED_BYTE_ATTR static size_t feed_byte(lep_frame_decoder *d, uint8_t b, lep_frame_event *ev)
{
#ifdef FRAME_FAST
    /* The usual bytes: a message byte, a DLE, a stuffed DLE, the BCC, DLE STX,
     * a byte between frames. */
    ev->type = LEP_FRAME_NONE;
    if (d->state == S_MSG) {
        if (b == LEP_DLE) {
            d->state = S_MSG_DLE;
            return 1;
        }
        if (d->len < LEP_MAX_MESSAGE) {
            d->buf[d->len++] = b;
            d->bcc ^= b;
            return 1;
        }
    } else if (d->state == S_MSG_DLE && b == LEP_DLE && d->len < LEP_MAX_MESSAGE) {
        d->buf[d->len++] = b;
        d->bcc ^= b;
        d->raw++;
        d->state = S_MSG;
        return 1;
    } else if (d->state == S_IDLE) { /* hunting for DLE STX */
        if (b == LEP_DLE) {
            d->state = S_IDLE_DLE;
        } else {
            d->stats.bytes_discarded++;
        }
        return 1;
    } else if (d->state == S_IDLE_DLE && b == LEP_STX) { /* a frame begins */
        d->raw = 2;
        d->len = 0;
        d->bcc = 0;
        d->state = S_MSG;
        return 1;
    } else if (d->state == S_BCC && b == (uint8_t)(d->bcc ^ LEP_ETX) && d->len != 0) {
        d->stats.messages++; /* a correct BCC: the message */
        ev->type = LEP_FRAME_MESSAGE;
        ev->error = LEP_OK;
        ev->msg = d->buf;
        ev->len = d->len;
        d->state = b == LEP_DLE ? S_BCC_DLE : S_IDLE;
        return 1;
    }
#endif
    return step(d, b, ev);
}

#ifdef FRAME_FAST
/* Count a rejected frame of `wire` wire bytes and make it the event: what
 * step's common end does for an error, as direct stores (through k_counter it
 * costs the 1 % corrupted stream 0.02 instructions/byte). */
static void reject(lep_frame_decoder *d, lep_frame_event *ev, int error, size_t wire)
{
    d->stats.bytes_discarded += (uint32_t)wire;
    if (error == LEP_E_BCC) {
        d->stats.bcc_errors++;
    } else if (error == LEP_E_ESCAPE) {
        d->stats.escape_errors++;
    } else if (error == LEP_E_TOO_LONG) {
        d->stats.overruns++;
    }
    ev->type = LEP_FRAME_ERROR;
    ev->error = error;
    ev->msg = NULL;
    ev->len = 0;
}

#endif

#ifdef FRAME_FAST
/* The decoder runs on local copies of its state and writes them back when it
 * returns. n is the message length so far, acc the XOR of its bytes (any byte
 * lanes; folded to d->bcc between calls), x the frame's wire bytes that are not
 * message bytes (DLE STX, stuffing DLEs, DLE ETX): the frame has n + x wire
 * bytes so far (d->raw between calls). Each label below is a state; a state
 * that runs out of input stores its number and returns. With no handler it
 * returns at the first event (lep_frame_decoder_feed); with one it hands each
 * event over and goes on in the next state (lep_frame_decoder_feed_all). */
#if defined(__GNUC__) && defined(__OPTIMIZE__) && !defined(__OPTIMIZE_SIZE__)
__attribute__((always_inline)) inline /* a copy per entry point, not at -O0/-Os */
#endif
    static size_t
    decode(lep_frame_decoder *d, const uint8_t *data, size_t len, lep_frame_event *ev,
           lep_frame_handler on_event, void *user)
{
    const uint8_t *p;
    const uint8_t *end;
    uint8_t *buf;
    size_t n;
    size_t x;
    size_t wire = 0;
    word_t acc;
    int error;
    unsigned st;
    uint8_t b;
    p = data;
    end = data + len;
    buf = d->buf;
    st = d->state;
    if (st == S_IDLE) {
        goto idle; /* the usual state at a call: the last call ended a frame */
    }
    n = d->len;
    x = d->raw;
    acc = d->bcc;
    switch (st) {
    case S_MSG:
        goto msg;
    case S_MSG_DLE:
        goto msg_dle;
    case S_BCC:
        goto bcc;
    case S_IDLE_DLE:
        goto idle_dle;
    case S_BCC_DLE:
        goto bcc_dle;
    case S_SKIP:
        goto skip;
    case S_SKIP_DLE:
        goto skip_dle;
    default:
        goto skip_bcc;
    }

idle : { /* between frames: hunting for DLE STX */
    const uint8_t *q = p;
    if (end - p >= 2 && p[0] == LEP_DLE && p[1] == LEP_STX) {
        p += 2; /* the usual case, taken in one step */
        x = 2;
        goto begin;
    }
    while (q < end && *q != LEP_DLE) {
        q++;
    }
    d->stats.bytes_discarded += (uint32_t)(q - p);
    if (q == end) {
        p = q;
        st = S_IDLE;
        goto suspend_between;
    }
    p = q + 1;
}
idle_dle: /* between frames, after a DLE */
    if (p == end) {
        st = S_IDLE_DLE;
        goto suspend_between;
    }
    b = *p++;
    if (b == LEP_STX) {
        x = 2;
        goto begin;
    }
    if (b == LEP_NAK) {
        goto nak;
    }
    if (b == LEP_DLE) {
        d->stats.bytes_discarded++; /* the earlier DLE; this one may start a frame */
        goto idle_dle;
    }
    d->stats.bytes_discarded += 2u;
    goto idle;

begin:
    n = 0;
    acc = 0;
msg : /* inside a frame */
{
    /* Whole words while they hold no DLE and fit in the input and in buf. */
    uint8_t *dst = buf + n;
    uint8_t *const dst_last = buf + (LEP_MAX_MESSAGE - W_SIZE);
    while ((size_t)(end - p) >= W_SIZE && dst <= dst_last) {
        word_t w;
        word_t m;
        memcpy(&w, p, W_SIZE);
        memcpy(dst, &w, W_SIZE);
        m = has_dle(w);
        if (m != 0) {
            size_t k = FIRST_DLE(m, p);
            acc ^= first_bytes(w, k);
            n = (size_t)(dst - buf) + k;
            p += k + 1u; /* the DLE */
            goto msg_dle;
        }
        acc ^= w;
        p += W_SIZE;
        dst += W_SIZE;
    }
    n = (size_t)(dst - buf);
}
    { /* Byte by byte: the end of the input is near, or of the buffer. */
        const uint8_t *stop =
            (size_t)(end - p) < LEP_MAX_MESSAGE - n ? end : p + (LEP_MAX_MESSAGE - n);
        while (p < stop && *p != LEP_DLE) {
            buf[n++] = *p;
            acc ^= *p++;
        }
        if (p == end) {
            st = S_MSG;
            goto suspend;
        }
        if (*p++ != LEP_DLE) {
            /* The 129th message byte. */
            error = LEP_E_TOO_LONG;
            wire = n + x + 1u;
            st = S_SKIP;
            goto fail;
        }
    }
msg_dle: /* inside a frame, after a DLE */
    if (p == end) {
        st = S_MSG_DLE;
        goto suspend;
    }
    b = *p++;
    if (b == LEP_ETX) {
        x += 2u;
        goto bcc;
    }
    if (b == LEP_DLE) {
        if (n == LEP_MAX_MESSAGE) {
            error = LEP_E_TOO_LONG;
            wire = n + x + 2u;
            st = S_SKIP;
            goto fail;
        }
        buf[n++] = LEP_DLE;
        acc ^= LEP_DLE;
        x++;
        /* Runs of stuffed DLEs (payloads full of 0x10) pair by pair. */
        while ((size_t)(end - p) >= 2u && p[0] == LEP_DLE && p[1] == LEP_DLE &&
               n < LEP_MAX_MESSAGE) {
            buf[n++] = LEP_DLE;
            acc ^= LEP_DLE;
            x++;
            p += 2;
        }
        goto msg;
    }
    if (b == LEP_STX) {
        /* A new frame starts inside this one: drop the partial frame. */
        d->stats.bytes_discarded += (uint32_t)(n + x);
        d->stats.restarts++;
        x = 2;
        goto begin;
    }
    if (b == LEP_NAK) {
        /* The sensor NAKs while a frame of its is broken off: drop the
         * partial frame (an escape error) but never lose the NAK. */
        d->stats.bytes_discarded += (uint32_t)(n + x);
        d->stats.escape_errors++;
        goto nak;
    }
    error = LEP_E_ESCAPE;
    wire = n + x + 2u;
    st = S_IDLE;
    goto fail;

bcc: /* after DLE ETX: this byte is the BCC */
    if (p == end) {
        st = S_BCC;
        goto suspend;
    }
    b = *p++;
    if (b == (uint8_t)(fold(acc) ^ LEP_ETX)) {
        if (n == 0) {
            /* DLE STX DLE ETX BCC: no Length byte, nothing to deliver. */
            error = LEP_E_LENGTH;
            wire = x + 1u;
            st = S_IDLE;
            goto fail;
        }
        d->stats.messages++;
        ev->type = LEP_FRAME_MESSAGE;
        ev->error = LEP_OK;
        ev->msg = buf;
        ev->len = n;
        /* A BCC of 0x10 may also be the DLE of what follows: the true BCC
         * was lost and happened to be 0x10, or the next frame's DLE was. */
        if (on_event == NULL) {
            d->state = b == LEP_DLE ? S_BCC_DLE : S_IDLE;
            return (size_t)(p - data);
        }
        on_event(user, ev);
        if (b == LEP_DLE) {
            goto bcc_dle;
        }
        goto idle;
    }
    error = LEP_E_BCC;
    wire = n + x + 1u;
    st = S_IDLE;
    if (b == LEP_DLE) {
        /* The BCC byte was lost (or hit): this DLE may open the next frame,
         * so it is not counted with this one. */
        wire--;
        st = S_IDLE_DLE;
    }
    goto fail;

bcc_dle: /* between frames; the last frame's 0x10 BCC may have been a DLE */
    if (p == end) {
        st = S_BCC_DLE;
        goto suspend_between;
    }
    b = *p++;
    if (b == LEP_STX) {
        x = 1; /* its DLE was counted with the frame before */
        goto begin;
    }
    if (b == LEP_NAK) {
        goto nak;
    }
    if (b == LEP_DLE) {
        goto idle_dle;
    }
    d->stats.bytes_discarded++;
    goto idle;

skip: /* inside a rejected (over-long) frame: follow its stuffing to its end */
    while (p < end && *p != LEP_DLE) {
        p++;
        d->stats.bytes_discarded++;
    }
    if (p == end) {
        st = S_SKIP;
        goto suspend_between;
    }
    p++;
skip_dle:
    if (p == end) {
        st = S_SKIP_DLE;
        goto suspend_between;
    }
    b = *p++;
    if (b == LEP_STX) {
        x = 2;
        goto begin;
    }
    if (b == LEP_NAK) {
        goto nak;
    }
    d->stats.bytes_discarded += 2u;
    if (b == LEP_DLE) {
        goto skip;
    }
    if (b != LEP_ETX) {
        goto idle;
    }
skip_bcc: /* the BCC of a rejected frame; a DLE may be it or the next frame's DLE */
    if (p == end) {
        st = S_SKIP_BCC;
        goto suspend_between;
    }
    if (*p++ == LEP_DLE) {
        goto idle_dle;
    }
    d->stats.bytes_discarded++;
    goto idle;

suspend_between: /* all input consumed between frames, no event */
    d->state = (uint8_t)st;
    ev->type = LEP_FRAME_NONE;
    return len;

suspend: /* all input consumed inside a frame, no event */
    d->state = (uint8_t)st;
    d->len = (uint16_t)n;
    d->raw = (uint16_t)x;
    d->bcc = fold(acc);
    ev->type = LEP_FRAME_NONE;
    return len;

nak: /* DLE NAK completed: deliver it and hunt for the next frame */
    d->stats.naks++;
    ev->type = LEP_FRAME_NAK;
    ev->error = LEP_OK;
    ev->msg = NULL;
    ev->len = 0;
    if (on_event == NULL) {
        d->state = S_IDLE;
        return (size_t)(p - data);
    }
    on_event(user, ev);
    goto idle;

fail: /* a frame rejected: wire is its count of wire bytes */
    reject(d, ev, error, wire);
    if (on_event == NULL) {
        d->state = (uint8_t)st;
        return (size_t)(p - data);
    }
    on_event(user, ev);
    if (st == S_SKIP) {
        goto skip;
    }
    if (st == S_IDLE_DLE) {
        goto idle_dle;
    }
    goto idle;
}

/* decode() specialised for each entry point (the handler a constant), kept
 * out of line so the one-byte path stays a small function. */
#if defined(__GNUC__)
#define LEP_NOINLINE __attribute__((noinline))
#else
#define LEP_NOINLINE
#endif
LEP_NOINLINE static size_t decode_one_event(lep_frame_decoder *d, const uint8_t *data, size_t len,
                                            lep_frame_event *ev)
{
    return decode(d, data, len, ev, NULL, NULL);
}

LEP_NOINLINE static int decode_all(lep_frame_decoder *d, const uint8_t *data, size_t len,
                                   lep_frame_handler on_event, void *user)
{
    lep_frame_event ev;
    (void)decode(d, data, len, &ev, on_event, user);
    return LEP_OK;
}

/* One byte through feed_all: its event, if any, to the handler. */
static int feed_all_byte(lep_frame_decoder *d, uint8_t b, lep_frame_handler on_event, void *user)
{
    lep_frame_event ev;
    (void)feed_byte(d, b, &ev);
    if (ev.type != LEP_FRAME_NONE) {
        on_event(user, &ev);
    }
    return LEP_OK;
}

#endif /* FRAME_FAST */

int lep_frame_decoder_feed_byte(lep_frame_decoder *d, uint8_t b, lep_frame_event *ev)
{
    if (ev == NULL || d == NULL) {
        (void)feed_bad_call(d, 1, ev);
        return LEP_E_ARG;
    }
    (void)feed_byte(d, b, ev);
    return LEP_OK;
}

size_t lep_frame_decoder_feed(lep_frame_decoder *d, const uint8_t *data, size_t len,
                              lep_frame_event *ev)
{
#ifndef FRAME_FAST
    const uint8_t *p = data;
#endif
    if (ev == NULL || d == NULL || data == NULL) {
        return feed_bad_call(d, len, ev);
    }
#ifdef FRAME_FAST
    if (len == 1) {
        return feed_byte(d, data[0], ev);
    }
    return decode_one_event(d, data, len, ev);
#else
    ev->type = LEP_FRAME_NONE;
    while (p < data + len) { /* the one machine, a byte at a time */
        (void)lep_frame_decoder_feed_byte(d, *p++, ev);
        if (ev->type != LEP_FRAME_NONE) {
            break;
        }
    }
    return (size_t)(p - data);
#endif
}

int lep_frame_decoder_feed_all(lep_frame_decoder *d, const uint8_t *data, size_t len,
                               lep_frame_handler on_event, void *user)
{
#ifndef FRAME_FAST
    lep_frame_event ev;
#endif
    if (d == NULL || on_event == NULL || (data == NULL && len > 0)) {
        return LEP_E_ARG;
    }
#ifdef FRAME_FAST
    if (len > 1) {
        return decode_all(d, data, len, on_event, user);
    }
    if (len == 1) {
        return feed_all_byte(d, data[0], on_event, user);
    }
#else
    while (len > 0) { /* the one machine, a byte at a time */
        (void)lep_frame_decoder_feed_byte(d, *data++, &ev);
        len--;
        if (ev.type != LEP_FRAME_NONE) {
            on_event(user, &ev);
        }
    }
#endif
    return LEP_OK;
}
