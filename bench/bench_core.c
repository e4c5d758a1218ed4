/* Core benchmark: decoder and codec throughput, context sizes. Prints figures;
 * asserts nothing about speed (machines are shared). Median of 7 runs. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "leptrino/leptrino.h"

#define FRAMES 200000u
#define RUNS 7

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a;
    double y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, size_t n)
{
    qsort(v, n, sizeof(*v), cmp_double);
    return v[n / 2];
}

int main(void)
{
    size_t cap = FRAMES * 40u;
    uint8_t *wire = malloc(cap);
    size_t len = 0;
    unsigned i;
    int run;
    double decode[RUNS];
    double decode1[RUNS];
    double encode[RUNS];
    volatile uint32_t sink = 0;
    if (wire == NULL) {
        return 1;
    }
    /* A stream of data messages with varied values (some contain 0x10 bytes). */
    for (i = 0; i < FRAMES; i++) {
        lep_sample s;
        size_t n;
        unsigned a;
        memset(&s, 0, sizeof(s));
        for (a = 0; a < LEP_AXES; a++) {
            s.raw[a] = (int16_t)((int)((i * 37u + a * 4111u) % 20001u) - 10000);
        }
        s.reserved = (uint16_t)i;
        if (lep_device_stream_frame(&s, wire + len, cap - len, &n) != LEP_OK) {
            return 1;
        }
        len += n;
    }
    for (run = 0; run < RUNS; run++) {
        lep_frame_decoder d;
        lep_frame_event ev;
        lep_response r;
        size_t pos = 0;
        double t0 = now_s();
        lep_frame_decoder_init(&d);
        while (pos < len) {
            pos += lep_frame_decoder_feed(&d, wire + pos, len - pos, &ev);
            if (ev.type == LEP_FRAME_MESSAGE && lep_response_decode(ev.msg, ev.len, &r) == LEP_OK) {
                sink += (uint32_t)r.u.sample.raw[0];
            }
        }
        decode[run] = now_s() - t0;
        if (d.stats.messages != FRAMES) {
            fprintf(stderr, "bench: decoded %u of %u\n", (unsigned)d.stats.messages, FRAMES);
            return 1;
        }
        /* The same, fed one byte at a time (an ISR-fed MCU). */
        t0 = now_s();
        lep_frame_decoder_init(&d);
        for (pos = 0; pos < len; pos++) {
            (void)lep_frame_decoder_feed(&d, wire + pos, 1, &ev);
        }
        decode1[run] = now_s() - t0;
        t0 = now_s();
        for (i = 0; i < FRAMES; i++) {
            lep_sample s;
            uint8_t out[64];
            size_t n;
            memset(&s, 0, sizeof(s));
            s.raw[0] = (int16_t)i;
            (void)lep_device_stream_frame(&s, out, sizeof(out), &n);
            sink += out[n - 1];
        }
        encode[run] = now_s() - t0;
    }
    printf("stream of %u data frames, %zu bytes (%.1f bytes/frame)\n", FRAMES, len, (double)len / FRAMES);
    printf("decode+validate, whole buffer : %6.1f ns/frame  %7.1f MB/s  (%.0fx the 1.2 kHz line rate)\n",
           median(decode, RUNS) * 1e9 / FRAMES, (double)len / median(decode, RUNS) / 1e6,
           FRAMES / median(decode, RUNS) / 1200.0);
    printf("decode, one byte per call     : %6.1f ns/frame  %7.1f MB/s\n",
           median(decode1, RUNS) * 1e9 / FRAMES, (double)len / median(decode1, RUNS) / 1e6);
    printf("encode data frame             : %6.1f ns/frame\n", median(encode, RUNS) * 1e9 / FRAMES);
    printf("sizeof: lep_client %zu, lep_device %zu, lep_frame_decoder %zu, lep_response %zu bytes\n",
           sizeof(lep_client), sizeof(lep_device), sizeof(lep_frame_decoder), sizeof(lep_response));
    (void)sink;
    free(wire);
    return 0;
}
