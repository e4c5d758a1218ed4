/* Sensor side: answer commands and keep the protocol state of a sensor.
 *
 * Structures are copied with memcpy where that is smaller than an assignment
 * on Thumb-1 at -Os (the size budgets of docs/embedded.md). */
#include "leptrino/device.h"

#include <stdbool.h>
#include <string.h>

#include "leptrino/error.h"

#if LEP_HAVE_DEVICE

/* Whether r, with src (size bytes) as its data, can be encoded. */
static bool encodable(lep_response *r, uint8_t code, const void *src, size_t size)
{
    uint8_t msg[LEP_LEN_PRODUCT_INFO_RATE];
    size_t n;
    r->code = code;
    memcpy(&r->u, src, size);
    return lep_response_encode(r, msg, sizeof(msg), &n) == LEP_OK;
}

/* True when the answers to 0x2A and 0x2B can be encoded from info and rated
 * (the encoder reads only the member of u that the code selects). */
static bool identity_ok(const lep_product_info *info, const lep_rated *rated)
{
    lep_response r;
    r.result = LEP_RESULT_OK;
    r.stream = false;
    return encodable(&r, LEP_CMD_RATED, rated, sizeof(*rated)) &&
           encodable(&r, LEP_CMD_PRODUCT_INFO, info, sizeof(*info));
}

size_t lep_device_sizeof(void)
{
    return sizeof(lep_device);
}

int lep_device_init(lep_device *d, const lep_product_info *info, const lep_rated *rated,
                    uint8_t filter)
{
    if (d == NULL || info == NULL || rated == NULL) {
        return LEP_E_ARG;
    }
    if (filter > LEP_FILTER_MAX || !identity_ok(info, rated)) {
        return LEP_E_VALUE;
    }
    memset(d, 0, sizeof(*d));
    lep_frame_decoder_init(&d->dec);
    memcpy(&d->info, info, sizeof(*info));
    memcpy(&d->rated, rated, sizeof(*rated));
    d->filter_active = filter;
    d->filter_pending = filter;
    return LEP_OK;
}

void lep_device_set_sample(lep_device *d, const lep_sample *s)
{
    if (d != NULL && s != NULL) {
        d->sample = *s;
    }
}

int lep_device_streaming(const lep_device *d)
{
    return d != NULL && d->streaming != 0u;
}

uint8_t lep_device_filter(const lep_device *d)
{
    return d == NULL ? 0u : d->filter_active;
}

uint8_t lep_device_filter_pending(const lep_device *d)
{
    return d == NULL ? 0u : d->filter_pending;
}

void lep_device_power_cycle(lep_device *d)
{
    if (d != NULL) {
        lep_frame_stats stats;
        memcpy(&stats, &d->dec.stats, sizeof(stats));
        lep_frame_decoder_init(&d->dec);
        memcpy(&d->dec.stats, &stats, sizeof(stats));
        d->streaming = false;
        d->filter_active = d->filter_pending;
    }
}

int lep_device_stream_frame(const lep_sample *s, uint8_t *out, size_t cap, size_t *len)
{
    lep_response r;
    if (s == NULL) {
        return LEP_E_ARG;
    }
    r.code = LEP_CMD_START;
    r.result = LEP_RESULT_OK;
    r.stream = true;
    r.u.sample = *s;
    return lep_response_frame(&r, out, cap, len);
}

typedef char lep_device_offsets_fit[(offsetof(lep_device, sample) < 256u) ? 1 : -1];

/* The queries, answered with a copy of a member of lep_device. */
static const struct query {
    uint8_t code;
    uint8_t size;
    uint8_t at; /* offset in lep_device (the last member starts below 256) */
} k_queries[] = { { LEP_CMD_PRODUCT_INFO, sizeof(lep_product_info), offsetof(lep_device, info) },
                  { LEP_CMD_RATED, sizeof(lep_rated), offsetof(lep_device, rated) },
                  { LEP_CMD_FILTER_GET, 1, offsetof(lep_device, filter_active) },
                  { LEP_CMD_SAMPLE, sizeof(lep_sample), offsetof(lep_device, sample) } };

/* Apply a valid command to the state and fill r.u with its answer (a
 * refusal sets ev->result). */
static void apply(lep_device *d, const lep_command *cmd, lep_device_event *ev, lep_response *r)
{
    const struct query *q;
    for (q = k_queries; q != k_queries + sizeof(k_queries) / sizeof(k_queries[0]); q++) {
        if (cmd->code == q->code) {
            memcpy(&r->u, (const uint8_t *)d + q->at, q->size);
            return;
        }
    }
    if (cmd->code == LEP_CMD_STOP) {
        d->streaming = false;
    } else if (d->streaming) { /* start, filter set: refused while streaming */
        ev->result = LEP_RESULT_STATE;
    } else if (cmd->code == LEP_CMD_START) {
        d->streaming = true;
    } else {
        d->filter_pending = cmd->filter;
    }
}

static void answer(lep_device *d, const uint8_t *msg, size_t len, lep_device_event *ev,
                   uint8_t *out, size_t cap, size_t *out_len)
{
    lep_command cmd;
    lep_response r;
    int rc = lep_command_decode(msg, len, &cmd, &ev->result);
    if (len < 3u) {
        ev->type = LEP_DEVICE_REJECTED; /* no command code to answer to */
        ev->result = 0;
        return;
    }
    ev->type = LEP_DEVICE_COMMAND;
    ev->code = cmd.code;
    ev->filter = cmd.filter;
    if (rc == LEP_OK) {
        apply(d, &cmd, ev, &r);
    }
    r.code = cmd.code; /* apply() filled the member of r.u that the code selects */
    r.result = ev->result;
    r.stream = false;
    /* a cap too small drops the answer: lep_response_frame leaves *out_len 0 */
    (void)lep_response_frame(&r, out, cap, out_len);
}

size_t lep_device_feed(lep_device *d, const uint8_t *in, size_t len, lep_device_event *ev,
                       uint8_t *out, size_t cap, size_t *out_len)
{
    lep_frame_event fev;
    size_t n;
    if (out_len != NULL) {
        *out_len = 0;
    }
    if (ev == NULL) {
        return 0;
    }
    ev->type = LEP_DEVICE_NONE;
    ev->code = 0;
    ev->result = 0;
    ev->filter = 0;
    if (d == NULL || out == NULL || out_len == NULL || (in == NULL && len > 0)) {
        return 0;
    }
    n = lep_frame_decoder_feed(&d->dec, in, len, &fev);
    if (fev.type == LEP_FRAME_MESSAGE) {
        answer(d, fev.msg, fev.len, ev, out, cap, out_len);
    } else if (fev.type == LEP_FRAME_ERROR && fev.error == LEP_E_BCC) {
        ev->type = LEP_DEVICE_NAK;
        if (cap >= 2u) {
            out[0] = LEP_DLE;
            out[1] = LEP_NAK;
            *out_len = 2;
        }
    } else if (fev.type == LEP_FRAME_ERROR) {
        ev->type = LEP_DEVICE_REJECTED;
    }
    return n;
}

#else
/* LEP_CONFIG_NO_DEVICE: nothing here (ISO C wants a declaration in every file). */
typedef int lep_device_left_out;
#endif
