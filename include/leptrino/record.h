/* Batch recording of a running stream (OS layer: host timestamps).
 *
 * Fills caller-owned arrays straight from the client, one call per batch, so
 * that language bindings do no per-sample work. */
#ifndef LEPTRINO_RECORD_H
#define LEPTRINO_RECORD_H

#include <stddef.h>
#include <stdint.h>

#include "client.h"
#include "export.h"
#include "message.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Destination arrays; any pointer but t may be NULL to skip that column. */
typedef struct lep_record_batch {
    size_t cap;      /* capacity in samples */
    size_t n;        /* samples filled so far; the call appends from here */
    double *t;       /* [cap] host arrival time, lep_monotonic_seconds() */
    double *si;      /* [cap * 6] N, N m (needs rated) */
    int16_t *raw;    /* [cap * 6] counts */
    uint8_t *status; /* [cap] status bits */
    uint16_t *seq;   /* [cap] the two reserved bytes (sequence number of leptrino-sim) */
} lep_record_batch;

/* Append stream samples to b until it is full or the monotonic clock
 * (lep_monotonic_seconds) passes until_s (ignored when <= 0). Blocks; waits
 * are clipped to the time left before until_s. Each sample is stamped with the
 * time the read that delivered it returned. The client must be streaming
 * (lep_client_start). Returns LEP_OK (full, or until_s reached), LEP_E_TIMEOUT
 * when no sample came for timeout_ms (< 0: wait forever), LEP_E_ARG (NULL c,
 * b or b->t, n > cap, si without rated), LEP_E_STATE (not streaming), or the
 * client's error (LEP_E_DISCONNECTED, ...); b->n counts what was filled in
 * every case, and nothing already read is lost. */
LEP_API int lep_record_fill(lep_client *c, const lep_rated *rated, lep_record_batch *b,
                            double until_s, int timeout_ms);

#ifdef __cplusplus
}
#endif

#endif
