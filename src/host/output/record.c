/* Batch recording of a running stream into caller-owned arrays (record.h). */
#define _POSIX_C_SOURCE 200809L

#include "leptrino/record.h"

#include <float.h>

#include "leptrino/error.h"
#include "leptrino/serial.h"
#include "struct_api.h"

/* Samples taken from the client per lep_client_next_samples call. */
#define LEP_RECORD_CHUNK 64u

static void record_store(lep_record_batch *b, const lep_rated *rated, const lep_sample *s, double t)
{
    size_t i = b->n;
    size_t k;

    b->t[i] = t;
    if (b->si != NULL) {
        lep_sample_to_si(s, rated, &b->si[i * LEP_AXES]);
    }
    if (b->raw != NULL) {
        for (k = 0; k < LEP_AXES; k++) {
            b->raw[i * LEP_AXES + k] = s->raw[k];
        }
    }
    if (b->status != NULL) {
        b->status[i] = s->status;
    }
    if (b->seq != NULL) {
        b->seq[i] = s->reserved;
    }
    b->n = i + 1u;
}

int lep_record_fill_batch(lep_client *c, const lep_rated *rated, lep_record_batch *b,
                          double until_s, int timeout_ms)
{
    lep_sample chunk[LEP_RECORD_CHUNK];

    if (c == NULL || b == NULL || b->t == NULL || b->n > b->cap ||
        (b->si != NULL && rated == NULL)) {
        return LEP_E_ARG;
    }
    if (!lep_client_streaming(c)) {
        return LEP_E_STATE;
    }
    while (b->n < b->cap) {
        size_t room = b->cap - b->n;
        size_t got = 0;
        size_t i;
        int wait = timeout_ms;
        int clipped = 0;
        int rc;
        double now;

        if (until_s > 0.0) {
            double left_ms;
            now = lep_monotonic_seconds();
            if (now >= until_s) {
                return LEP_OK;
            }
            /* Wait no longer than the time left (rounded up, so the next
             * check sees the deadline passed). */
            left_ms = (until_s - now) * 1000.0 + 1.0;
            if (wait < 0 || left_ms < (double)wait) {
                wait = left_ms < 2147483647.0 ? (int)left_ms : 2147483647;
                clipped = 1;
            }
        }
        if (room > LEP_RECORD_CHUNK) {
            room = LEP_RECORD_CHUNK;
        }
        rc = lep_client_next_samples(c, chunk, room, &got, wait);
        now = lep_monotonic_seconds();
        if (got > room) {
            got = room;
        }
        for (i = 0; i < got; i++) {
            record_store(b, rated, &chunk[i], now);
        }
        if (rc == LEP_E_TIMEOUT && got == 0 && clipped) {
            continue; /* the deadline, not the sensor, ended this wait */
        }
        if (rc < 0) {
            return rc;
        }
    }
    return LEP_OK;
}

int lep_record_fill(lep_client *c, const double rated[6], size_t cap, size_t *n, double *t,
                    double *si, int16_t *raw, uint8_t *status, uint16_t *seq, double until_s,
                    int timeout_ms)
{
    lep_record_batch b;
    lep_rated r;
    int k, rc;
    if (n != NULL)
        *n = 0;
    if (n == NULL)
        return LEP_E_ARG;
    if (rated != NULL) {
        for (k = 0; k < LEP_AXES; k++) {
            if (!(rated[k] > 0.0 && rated[k] <= FLT_MAX)) /* also NaN */
                return LEP_E_ARG;
            r.axis[k] = (float)rated[k];
        }
    }
    b.cap = cap;
    b.n = 0;
    b.t = t;
    b.si = si;
    b.raw = raw;
    b.status = status;
    b.seq = seq;
    rc = lep_record_fill_batch(c, rated != NULL ? &r : NULL, &b, until_s, timeout_ms);
    *n = b.n;
    return rc;
}
