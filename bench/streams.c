/* The three streams of leptrino-bench, built deterministically from a seed:
 *  - realistic: continuous-output data messages (0x32) of a 6-axis waveform
 *    (a slow sine per axis, a little noise, a load offset), with the virtual
 *    sensor's sequence number in the reserved bytes, so 0x10 bytes appear in
 *    their natural share (low bytes of counts, sequence numbers);
 *  - all 0x10: every payload byte 0x10 (the worst case of stuffing);
 *  - 1 % corrupted: the realistic stream with 1 % of its bytes replaced by
 *    another value (frames then fail their BCC, lose sync, restart). */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "leptrino/leptrino.h"

static uint32_t xorshift(uint32_t *s)
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *s = x;
    return x;
}

const char *bench_stream_name(int which)
{
    static const char *const names[STREAM_COUNT] = { "realistic", "all_0x10", "corrupt_1pct" };
    return which >= 0 && which < STREAM_COUNT ? names[which] : "?";
}

int bench_stream_make(int which, size_t frames, bench_bytes *out)
{
    size_t cap = frames * (2u * 20u + 5u);
    size_t i;
    uint32_t rng = 0x1234567u;
    memset(out, 0, sizeof(*out));
    out->data = malloc(cap);
    if (out->data == NULL) {
        return -1;
    }
    for (i = 0; i < frames; i++) {
        uint8_t msg[20];
        size_t n = 0;
        size_t j;
        if (which == STREAM_ALL_DLE) {
            memset(msg, LEP_DLE, sizeof(msg));
            msg[0] = 20;
            msg[1] = 0xFF;
            msg[2] = 0x32;
            msg[3] = 0x00;
        } else {
            /* 1.2 kHz samples: sines of 0.5..3 Hz, +-3000 counts around an
             * offset, +-40 counts of noise; the sequence number as the sim sends. */
            lep_sample s;
            lep_response r;
            double t = (double)i / 1200.0;
            unsigned a;
            memset(&s, 0, sizeof(s));
            for (a = 0; a < LEP_AXES; a++) {
                double v = 500.0 * (double)a - 1200.0 +
                           3000.0 * sin(2.0 * 3.14159265358979 * (0.5 + 0.5 * a) * t);
                v += (double)(xorshift(&rng) % 81u) - 40.0;
                s.raw[a] = (int16_t)lround(v);
            }
            s.reserved = (uint16_t)(i & 0xFFFFu);
            memset(&r, 0, sizeof(r));
            r.code = LEP_CMD_START;
            r.stream = true;
            r.u.sample = s;
            if (lep_response_encode(&r, msg, sizeof(msg), &n) != LEP_OK || n != sizeof(msg)) {
                free(out->data);
                out->data = NULL;
                return -1;
            }
        }
        for (j = 0; j < sizeof(msg); j++) {
            out->payload_dle += msg[j] == LEP_DLE;
        }
        out->payload += sizeof(msg);
        if (lep_frame_encode(msg, sizeof(msg), out->data + out->len, cap - out->len, &n) !=
            LEP_OK) {
            free(out->data);
            out->data = NULL;
            return -1;
        }
        out->len += n;
    }
    out->frames = frames;
    if (which == STREAM_CORRUPT) {
        for (i = 0; i < out->len; i++) {
            if (xorshift(&rng) % 100u == 0u) {
                out->data[i] ^= (uint8_t)(1u + xorshift(&rng) % 255u);
                out->corrupted++;
            }
        }
    }
    return 0;
}
