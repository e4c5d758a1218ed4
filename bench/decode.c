/* Codec measurements of leptrino-bench. Each region is a separate, never
 * inlined function, so callgrind can count exactly its instructions
 * (valgrind --toggle-collect=region_*) while the stream is built outside it. */
#include <string.h>

#include "bench.h"
#include "leptrino/leptrino.h"

#if defined(__GNUC__)
#define NOINLINE __attribute__((noinline))
#else
#define NOINLINE
#endif

const char *bench_region_name(int which)
{
    static const char *const names[REGION_COUNT] = { "leptrino",    "leptrino_feed",
                                                     "plain",       "plain_loop",
                                                     "client_step", "client_step_call" };
    return which >= 0 && which < REGION_COUNT ? names[which] : "?";
}

/* The handler of lep_frame_decoder_feed_all: messages handed on (third byte
 * summed so nothing is optimised away). */
static void on_event(void *user, const lep_frame_event *ev)
{
    if (ev->type == LEP_FRAME_MESSAGE) {
        *(uint32_t *)user += ev->msg[2];
    }
}

/* lep_frame_decoder_feed_all as a host reads it: one call per chunk. */
NOINLINE static size_t region_leptrino(const uint8_t *in, size_t len, size_t chunk, uint32_t *sink)
{
    lep_frame_decoder d;
    size_t off = 0;
    lep_frame_decoder_init(&d);
    while (off < len) {
        size_t n = len - off < chunk ? len - off : chunk;
        (void)lep_frame_decoder_feed_all(&d, in + off, n, on_event, sink);
        off += n;
    }
    return d.stats.messages;
}

/* lep_frame_decoder_feed as a host reads it: one chunk per read, every event
 * drained, messages handed on (third byte summed so nothing is optimised away). */
NOINLINE static size_t region_feed(const uint8_t *in, size_t len, size_t chunk, uint32_t *sink)
{
    lep_frame_decoder d;
    size_t off = 0;
    lep_frame_decoder_init(&d);
    while (off < len) {
        const uint8_t *p = in + off;
        size_t n = len - off < chunk ? len - off : chunk;
        off += n;
        while (n > 0) {
            lep_frame_event ev;
            size_t used = lep_frame_decoder_feed(&d, p, n, &ev);
            p += used;
            n -= used;
            if (ev.type == LEP_FRAME_MESSAGE) {
                *sink += ev.msg[2];
            }
        }
    }
    return d.stats.messages;
}

/* The baseline on the same chunks: its parse function called per byte. */
NOINLINE static size_t region_plain(const uint8_t *in, size_t len, size_t chunk, uint32_t *sink)
{
    plain_decoder d;
    size_t off = 0;
    size_t msgs = 0;
    plain_init(&d);
    while (off < len) {
        size_t n = len - off < chunk ? len - off : chunk;
        size_t i;
        for (i = 0; i < n; i++) {
            if (plain_step(&d, in[off + i])) {
                *sink += d.buf[2];
                msgs++;
            }
        }
        off += n;
    }
    return msgs;
}

/* The same machine with the loop inside its file (state in registers). */
NOINLINE static size_t region_plain_loop(const uint8_t *in, size_t len, size_t chunk,
                                         uint32_t *sink)
{
    plain_decoder d;
    size_t off = 0;
    size_t msgs = 0;
    plain_init(&d);
    while (off < len) {
        size_t n = len - off < chunk ? len - off : chunk;
        msgs += plain_feed(&d, in + off, n, sink);
        off += n;
    }
    return msgs;
}

static int no_write(void *user, const uint8_t *data, size_t len)
{
    (void)user;
    (void)data;
    (void)len;
    return 0;
}

static uint32_t zero_clock(void *user)
{
    (void)user;
    return 0;
}

/* One outcome of lep_client_step: a sample is read out (counted in *samples). */
static void take_outcome(lep_client *c, int rc, size_t *samples, uint32_t *sink)
{
    if (rc == LEP_STEP_SAMPLE) {
        lep_sample smp;
        if (lep_client_get_sample(c, &smp) == LEP_OK)
            *sink += (uint32_t)(uint16_t)smp.raw[0];
        (*samples)++;
    }
}

/* The client's step API fed chunk bytes per call, already streaming; every
 * outcome drained. One byte at a time is lep_client_step_byte, as an MCU's
 * ISR ring consumer calls it (the same outcomes as lep_client_step). */
NOINLINE static size_t region_client_step(lep_client *c, const uint8_t *in, size_t len,
                                          size_t chunk, uint32_t *sink)
{
    size_t off = 0;
    size_t samples = 0;
    if (chunk == 1) { /* the loop of an ISR ring's consumer: pop a byte, step, act on the outcome */
        for (off = 0; off < len; off++) {
            lep_sample smp;
            if (lep_client_step_byte(c, in[off], &smp) == LEP_STEP_SAMPLE) {
                *sink += (uint32_t)(uint16_t)smp.raw[0];
                samples++;
            }
        }
        return samples;
    }
    while (off < len) {
        const uint8_t *p = in + off;
        size_t n = len - off < chunk ? len - off : chunk;
        off += n;
        while (n > 0) {
            size_t used = 0;
            take_outcome(c, lep_client_step(c, p, n, &used), &samples, sink);
            p += used;
            n -= used;
            if (used == 0) {
                return samples;
            }
        }
    }
    return samples;
}

/* The documented general API fed one byte per call, already streaming: an
 * ISR ring's consumer pops a byte b, calls lep_client_step(c, &b, 1, &used)
 * and on LEP_STEP_SAMPLE reads the sample with lep_client_get_sample. */
NOINLINE static size_t region_client_step_call(lep_client *c, const uint8_t *in, size_t len,
                                               uint32_t *sink)
{
    size_t off;
    size_t samples = 0;
    for (off = 0; off < len; off++) {
        uint8_t b = in[off];
        size_t used;
        if (lep_client_step(c, &b, 1, &used) == LEP_STEP_SAMPLE) {
            lep_sample smp;
            if (lep_client_get_sample(c, &smp) == LEP_OK) {
                *sink += (uint32_t)(uint16_t)smp.raw[0];
                samples++;
            }
        }
    }
    return samples;
}

/* A client that has started streaming (its start answered), fed s through
 * the step region `which` in chunks of chunk bytes. */
static size_t client_step_run(int which, const bench_bytes *s, size_t chunk, uint32_t *sink)
{
    static lep_client c;
    lep_io io;
    lep_command start = { LEP_CMD_START, 0 };
    lep_response ack;
    uint8_t msg[8];
    uint8_t wire[32];
    size_t mlen = 0;
    size_t wlen = 0;
    size_t used = 0;
    memset(&io, 0, sizeof(io));
    io.write = no_write;
    io.now_ms = zero_clock;
    memset(&ack, 0, sizeof(ack));
    ack.code = LEP_CMD_START;
    if (lep_client_init(&c, &io) != LEP_OK || lep_client_send(&c, &start) != LEP_OK ||
        lep_response_encode(&ack, msg, sizeof(msg), &mlen) != LEP_OK ||
        lep_frame_encode(msg, mlen, wire, sizeof(wire), &wlen) != LEP_OK ||
        lep_client_step(&c, wire, wlen, &used) != LEP_STEP_RESPONSE || !lep_client_streaming(&c)) {
        return 0;
    }
    if (which == REGION_CLIENT_STEP_CALL) {
        return region_client_step_call(&c, s->data, s->len, sink);
    }
    return region_client_step(&c, s->data, s->len, chunk, sink);
}

size_t bench_region_run(int which, const bench_bytes *s, size_t chunk, uint32_t *sink)
{
    switch (which) {
    case REGION_LEPTRINO:
        return region_leptrino(s->data, s->len, chunk, sink);
    case REGION_FEED:
        return region_feed(s->data, s->len, chunk, sink);
    case REGION_PLAIN:
        return region_plain(s->data, s->len, chunk, sink);
    case REGION_PLAIN_LOOP:
        return region_plain_loop(s->data, s->len, chunk, sink);
    default:
        return client_step_run(which, s, chunk, sink);
    }
}

double bench_encode_msgs_per_s(int runs, size_t frames, int whole_sample)
{
    double rate[16];
    int r;
    volatile uint32_t sink = 0;
    if (runs > 16) {
        runs = 16;
    }
    for (r = 0; r < runs; r++) {
        double t0 = bench_now_s();
        size_t i;
        for (i = 0; i < frames; i++) {
            uint8_t out[LEP_MAX_FRAME];
            size_t n = 0;
            if (whole_sample) {
                lep_sample smp;
                memset(&smp, 0, sizeof(smp));
                smp.raw[0] = (int16_t)i;
                smp.reserved = (uint16_t)i;
                (void)lep_device_stream_frame(&smp, out, sizeof(out), &n);
            } else {
                uint8_t msg[20] = { 20, 0xFF, 0x32, 0x00 };
                msg[4] = (uint8_t)i;
                msg[5] = (uint8_t)(i >> 8);
                (void)lep_frame_encode(msg, sizeof(msg), out, sizeof(out), &n);
            }
            sink += out[n - 1u];
        }
        rate[r] = (double)frames / (bench_now_s() - t0);
    }
    (void)sink;
    return bench_median(rate, (size_t)runs);
}
