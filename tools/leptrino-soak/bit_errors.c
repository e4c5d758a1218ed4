/* leptrino-soak --bit-errors N: how often a frame with two flipped bits passes
 * the 8-bit XOR BCC, and then the message checks, as a different message. A
 * protocol limit, measured: random valid frames (stream data with random
 * counts, product info, rated values), two distinct random bits flipped
 * anywhere in the frame (stuffing, DLE/STX/ETX and BCC included), fed to the
 * frame decoder followed by a clean frame; a message that comes out different
 * from both and decodes is an undetected error. */
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "leptrino/leptrino.h"
#include "soak.h"

typedef struct tally {
    uint64_t trials, bcc_passed, accepted;
} tally;

static uint64_t mix(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

/* A random valid message of kind 0 (stream data), 1 (product info), 2 (rated). */
static size_t make_message(int kind, uint64_t *rng, uint8_t *msg, size_t cap)
{
    lep_response r;
    size_t len = 0;
    int i;
    memset(&r, 0, sizeof r);
    if (kind == 0) {
        r.code = LEP_CMD_START;
        r.stream = true;
        for (i = 0; i < LEP_AXES; i++)
            r.u.sample.raw[i] = (int16_t)((int)(mix(rng) % 64001u) - 32000);
        r.u.sample.status = (uint8_t)(mix(rng) & 0x07u); /* the defined bits */
        r.u.sample.reserved = (uint16_t)mix(rng);        /* a sequence number */
    } else if (kind == 1) {
        r.code = LEP_CMD_PRODUCT_INFO;
        memcpy(r.u.info.model, "PFS055YA501U6", 14);
        snprintf(r.u.info.serial, sizeof r.u.info.serial, "%08u",
                 (unsigned)(mix(rng) % 100000000u));
        memcpy(r.u.info.firmware, "1.13", 5);
    } else {
        r.code = LEP_CMD_RATED;
        for (i = 0; i < LEP_AXES; i++)
            r.u.rated.axis[i] = (float)(1 + mix(rng) % 2000u);
    }
    if (lep_response_encode(&r, msg, cap, &len) != LEP_OK)
        return 0;
    return len;
}

/* Feed data to d; count messages that differ from want[0..want_len) and that
 * the message codec accepts. *frames_ok counts those that passed the BCC. */
static void feed(lep_frame_decoder *d, const uint8_t *data, size_t n, const uint8_t *want,
                 size_t want_len, uint64_t *frames_ok, uint64_t *accepted)
{
    while (n > 0) {
        lep_frame_event ev;
        lep_response r;
        size_t used = lep_frame_decoder_feed(d, data, n, &ev);
        data += used;
        n -= used;
        if (ev.type != LEP_FRAME_MESSAGE)
            continue;
        if (ev.len == want_len && memcmp(ev.msg, want, want_len) == 0)
            continue; /* the message as sent */
        (*frames_ok)++;
        if (lep_response_decode(ev.msg, ev.len, &r) == LEP_OK)
            (*accepted)++;
    }
}

static void trial(int kind, uint64_t *rng, tally *t)
{
    uint8_t msg[LEP_MAX_MESSAGE], frame[LEP_MAX_FRAME], bad[LEP_MAX_FRAME];
    size_t len = make_message(kind, rng, msg, sizeof msg), flen = 0, nbits, b1, b2;
    lep_frame_decoder d;
    if (len == 0 || lep_frame_encode(msg, len, frame, sizeof frame, &flen) != LEP_OK)
        return;
    nbits = flen * 8u;
    b1 = (size_t)(mix(rng) % nbits);
    do
        b2 = (size_t)(mix(rng) % nbits);
    while (b2 == b1);
    memcpy(bad, frame, flen);
    bad[b1 / 8u] ^= (uint8_t)(1u << (b1 % 8u));
    bad[b2 / 8u] ^= (uint8_t)(1u << (b2 % 8u));
    lep_frame_decoder_init(&d);
    feed(&d, bad, flen, msg, len, &t->bcc_passed, &t->accepted);
    feed(&d, frame, flen, msg, len, &t->bcc_passed, &t->accepted); /* the next frame */
    t->trials++;
}

static void print_tally(const char *name, const tally *t, int comma)
{
    printf("\"%s\":{\"trials\":%llu,\"passed_bcc\":%llu,\"accepted\":%llu,"
           "\"passed_bcc_rate\":%.6f,\"accepted_rate\":%.6f}%s",
           name, (unsigned long long)t->trials, (unsigned long long)t->bcc_passed,
           (unsigned long long)t->accepted,
           t->trials ? (double)t->bcc_passed / (double)t->trials : 0.0,
           t->trials ? (double)t->accepted / (double)t->trials : 0.0, comma ? "," : "");
}

int soak_bit_errors(uint64_t trials, uint64_t seed)
{
    static const char *const names[3] = { "stream_data", "product_info", "rated" };
    tally t[3];
    uint64_t rng = seed ^ 0xB17E55u, i;
    int k;
    memset(t, 0, sizeof t);
    for (i = 0; i < trials; i++)
        for (k = 0; k < 3; k++)
            trial(k, &rng, &t[k]);
    printf("{\"two_bit_errors\":{\"seed\":%llu,", (unsigned long long)seed);
    for (k = 0; k < 3; k++)
        print_tally(names[k], &t[k], k < 2);
    printf("}}\n");
    return 0;
}
