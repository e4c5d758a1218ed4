/* Frame codec (spec 2.3): DLE STX | stuffed message | DLE ETX | BCC.
 *
 * Sans-I/O: pure functions and a push decoder. No allocation, no clock, no
 * blocking; NULL arguments as leptrino.h says.
 * The decoder gives identical events for any chunking of the same input.
 * Its rules where the spec is silent (restart at DLE STX, NAK inside a frame,
 * over-long frames, resync after a lost BCC byte) are listed with the shared
 * vectors in test/vectors/README.md. In short, a lost BCC never costs the next
 * frame: a DLE where the BCC should be (and the BCC is not 0x10) rejects the
 * frame and may itself start the next one. */
#ifndef LEPTRINO_FRAME_H
#define LEPTRINO_FRAME_H

#include <stddef.h>
#include <stdint.h>

#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Constants are enumerators, not macros, so that an FFI reading the
 * declarations sees them; each is an int. */

/* Control bytes of the framing (spec 2.3). */
enum lep_control_byte { LEP_DLE = 0x10, LEP_STX = 0x02, LEP_ETX = 0x03, LEP_NAK = 0x15 };

/* Size limits, in bytes. */
enum lep_frame_limit {
    LEP_MAX_MESSAGE = 128,                  /* longest unstuffed message (Length .. end of Data) */
    LEP_MAX_FRAME = 2 * LEP_MAX_MESSAGE + 5 /* longest frame (all stuffed, + 5 control bytes) */
};

/* BCC of an unstuffed message: XOR of its bytes and ETX (NULL: that of no
 * bytes, ETX). */
LEP_API uint8_t lep_bcc(const uint8_t *msg, size_t len);

/* Encode msg[0..len) as a frame into out[0..cap); *out_len receives its size.
 * Errors: LEP_E_ARG (NULL, len 0), LEP_E_TOO_LONG (len > 128),
 * LEP_E_BUFFER (cap too small; out is then unspecified). */
LEP_API int lep_frame_encode(const uint8_t *msg, size_t len, uint8_t *out, size_t cap,
                             size_t *out_len);

/* Size the frame of msg will take on the wire (0 if msg is NULL). */
LEP_API size_t lep_frame_size(const uint8_t *msg, size_t len);

enum lep_frame_event_type {
    LEP_FRAME_NONE = 0,    /* all input consumed, no event */
    LEP_FRAME_MESSAGE = 1, /* a complete message with a correct BCC */
    LEP_FRAME_NAK = 2,     /* DLE NAK (inside a frame it also drops the partial frame, counted
                              as an escape error, so a NAK is never lost) */
    LEP_FRAME_ERROR = 3    /* a frame was rejected: see error */
};

typedef struct lep_frame_event {
    int type;  /* enum lep_frame_event_type */
    int error; /* with LEP_FRAME_ERROR: LEP_E_BCC, LEP_E_ESCAPE, LEP_E_TOO_LONG,
                           LEP_E_LENGTH for an empty frame (counted in bytes_discarded only),
                           or LEP_E_ARG for a bad argument to lep_frame_decoder_feed or
                           lep_frame_decoder_feed_byte */
    const uint8_t
        *msg;   /* with LEP_FRAME_MESSAGE: the unstuffed message, valid until the next feed */
    size_t len; /* its length (1..128) */
} lep_frame_event;

/* Decoder counters; they only grow (wrap at 2^32). */
typedef struct lep_frame_stats {
    uint32_t messages;        /* messages delivered */
    uint32_t naks;            /* DLE NAK seen */
    uint32_t bcc_errors;      /* frames rejected for a BCC mismatch */
    uint32_t escape_errors;   /* frames rejected for an illegal byte after DLE */
    uint32_t overruns;        /* frames rejected for exceeding 128 bytes */
    uint32_t restarts;        /* partial frames abandoned at a new DLE STX */
    uint32_t bytes_discarded; /* wire bytes not part of a delivered message or NAK */
} lep_frame_stats;

/* Push decoder. Caller-allocated (static memory is fine); its fields are
 * private: read the counters with lep_frame_decoder_get_stats. One decoder must
 * not be fed from two contexts at once; distinct decoders are independent.
 * Evolution rule: the layout is public only so that C and firmware can
 * allocate it statically. Other languages allocate lep_frame_decoder_sizeof()
 * bytes (aligned for a uint32_t) and never read its fields; the fields may
 * change between minor versions while the version is 0.x. */
typedef struct lep_frame_decoder {
    uint8_t state;
    uint8_t bcc;
    uint16_t len;
    uint16_t raw;
    lep_frame_stats stats;
    uint8_t buf[LEP_MAX_MESSAGE];
} lep_frame_decoder;

/* sizeof(lep_frame_decoder), for callers that allocate it as bytes. */
LEP_API size_t lep_frame_decoder_sizeof(void);

/* Reset the decoder to hunt for DLE STX and zero its counters. */
LEP_API void lep_frame_decoder_init(lep_frame_decoder *d);

/* Consume bytes of data[0..len) up to and including the first one that
 * completes an event, and return how many were consumed (at least 1 when
 * len > 0). Call again with the rest. ev->type is LEP_FRAME_NONE when all
 * input was consumed without an event (the other fields of ev are set only
 * with the event types that use them). Allocates nothing, keeps no pointer to
 * data; ev->msg points into d.
 *
 * Bad arguments: when d or ev is NULL, or data is NULL with len > 0, nothing
 * is consumed, 0 is returned and ev (when not NULL) is an LEP_FRAME_ERROR event
 * with error LEP_E_ARG; d is left unchanged. So 0 with len > 0 means "stop":
 * a caller looping on the return value never spins. data may be NULL when
 * len is 0 (returns 0 with LEP_FRAME_NONE). */
LEP_API size_t lep_frame_decoder_feed(lep_frame_decoder *d, const uint8_t *data, size_t len,
                                      lep_frame_event *ev);

/* Feed the one byte b: exactly lep_frame_decoder_feed(d, &b, 1, ev) (the same
 * event in ev, the same counters), for a caller fed a byte at a time (e.g. from
 * an ISR ring buffer). ev->type is LEP_FRAME_NONE when b completes no event.
 * Returns LEP_OK, or LEP_E_ARG when d or ev is NULL: then b is not consumed,
 * d is unchanged and ev (when not NULL) is an LEP_FRAME_ERROR event with error
 * LEP_E_ARG. */
LEP_API int lep_frame_decoder_feed_byte(lep_frame_decoder *d, uint8_t b, lep_frame_event *ev);

/* Called by lep_frame_decoder_feed_all for each event, in input order. ev and
 * ev->msg are valid only during the call. The handler must not feed the same
 * decoder (it may feed others). */
typedef void (*lep_frame_handler)(void *user, const lep_frame_event *ev);

/* Consume all of data[0..len), calling on_event(user, ev) for every event it
 * completes. Gives exactly the events and counters of lep_frame_decoder_feed
 * on the same input, for any chunking and mixed with it. Allocates nothing.
 * Returns LEP_OK, or LEP_E_ARG (d or on_event NULL, or data NULL with len > 0:
 * nothing consumed, d unchanged). */
LEP_API int lep_frame_decoder_feed_all(lep_frame_decoder *d, const uint8_t *data, size_t len,
                                       lep_frame_handler on_event, void *user);

/* 1 when the decoder is inside a frame (between DLE STX and its BCC), else 0. */
LEP_API int lep_frame_decoder_busy(const lep_frame_decoder *d);

/* Copy the decoder's counters into *out. */
LEP_API void lep_frame_decoder_get_stats(const lep_frame_decoder *d, lep_frame_stats *out);

#ifdef __cplusplus
}
#endif

#endif
