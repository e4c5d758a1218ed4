/* Sensor side of the protocol: decode commands, keep the sensor's protocol
 * state, encode answers. Used by the virtual sensor and by firmware or
 * gateways that present themselves as a Leptrino sensor.
 *
 * Behaviour (the spec's choices and leptrino's where it is silent):
 *  - bad BCC: answer DLE NAK; other rejected frames: no answer;
 *  - short/long message or wrong Length: result 0x01; unknown code: 0x02;
 *    filter code > 3 or a reserved byte not at its fixed value: 0x03;
 *  - state error 0x04: start while already streaming, filter set while
 *    streaming; stop while idle is accepted (0x00) so recovery is idempotent;
 *    queries and the handshake sample are answered in every state;
 *  - a filter set takes effect at the next lep_device_power_cycle().
 * Not thread-safe; caller-allocated; no allocation.
 * NULL arguments as leptrino.h says. */
#ifndef LEPTRINO_DEVICE_H
#define LEPTRINO_DEVICE_H

#include <stddef.h>
#include <stdint.h>

#include "config.h"
#include "export.h"
#include "frame.h"
#include "message.h"

#ifdef __cplusplus
extern "C" {
#endif

enum lep_device_event_type {
    LEP_DEVICE_NONE = 0,    /* input consumed, nothing to answer */
    LEP_DEVICE_COMMAND = 1, /* a command was processed; out holds its answer */
    LEP_DEVICE_NAK = 2,     /* a command with a bad BCC; out holds DLE NAK */
    LEP_DEVICE_REJECTED = 3 /* a frame that cannot be answered (bad escape, too long, no code) */
};

typedef struct lep_device_event {
    int type;       /* enum lep_device_event_type */
    uint8_t code;   /* LEP_DEVICE_COMMAND: command code received */
    uint8_t result; /* LEP_DEVICE_COMMAND: result code answered */
    uint8_t filter; /* LEP_DEVICE_COMMAND with a filter set: the code requested */
} lep_device_event;

/* Device context. Caller-allocated; its fields are private.
 * Evolution rule: the layout is public only so that C and firmware can
 * allocate it statically. Other languages allocate lep_device_sizeof() bytes
 * (aligned for a uint32_t and a float) and never read its fields; the fields
 * may change between minor versions while the version is 0.x. */
typedef struct lep_device {
    uint8_t filter_active;
    uint8_t filter_pending;
    uint8_t streaming; /* 1: continuous output is on */
    lep_frame_decoder dec;
    lep_product_info info;
    lep_rated rated;
    lep_sample sample;
} lep_device;

#if LEP_HAVE_DEVICE

/* sizeof(lep_device), for callers that allocate it as bytes. */
LEP_API size_t lep_device_sizeof(void);

/* Reset d with its identity, ratings and active filter code (copied).
 * LEP_E_ARG for NULL; LEP_E_VALUE for a filter code > 3, invalid ratings, or
 * an identity field longer than its place in the product-info answer. */
LEP_API int lep_device_init(lep_device *d, const lep_product_info *info, const lep_rated *rated,
                            uint8_t filter);

/* Feed bytes received from the host; consumes up to and including the byte
 * that completes a frame and returns the count (at least 1 when len > 0;
 * 0 with ev->type LEP_DEVICE_NONE for a NULL argument). On LEP_DEVICE_COMMAND and
 * LEP_DEVICE_NAK the frame to send back is in out[0..*out_len) (cap of
 * LEP_MAX_FRAME always suffices); otherwise *out_len is 0. If cap is too
 * small the answer is dropped and *out_len is 0. */
LEP_API size_t lep_device_feed(lep_device *d, const uint8_t *in, size_t len, lep_device_event *ev,
                               uint8_t *out, size_t cap, size_t *out_len);

/* The sample answered to a handshake query (0x30) from now on. */
LEP_API void lep_device_set_sample(lep_device *d, const lep_sample *s);

/* Frame one continuous-output data message (0x32) for s into out.
 * Errors as lep_response_frame. */
LEP_API int lep_device_stream_frame(const lep_sample *s, uint8_t *out, size_t cap, size_t *len);

/* 1 while continuous output is on (else 0): the application then sends
 * lep_device_stream_frame() at its output rate. */
LEP_API int lep_device_streaming(const lep_device *d);

/* Filter code in effect, and the one that takes effect at power-cycle. */
LEP_API uint8_t lep_device_filter(const lep_device *d);
LEP_API uint8_t lep_device_filter_pending(const lep_device *d);

/* Simulate switching the sensor off and on: streaming stops, the pending
 * filter becomes active, and any partial input is forgotten. */
LEP_API void lep_device_power_cycle(lep_device *d);

#endif /* LEP_HAVE_DEVICE */

#ifdef __cplusplus
}
#endif

#endif
