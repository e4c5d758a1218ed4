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

/* Write stream samples into caller arrays from index 0 until cap are
 * written or the monotonic clock (lep_monotonic_seconds) passes until_s
 * (ignored when <= 0); *n gets how many (in every case). Arrays: t[cap]
 * (needed) the host arrival time, lep_monotonic_seconds(); si[cap*6] N, N m
 * (needs rated[6]); raw[cap*6] counts; status[cap]; seq[cap] the two
 * reserved bytes; all but t may be NULL. Blocks; waits are clipped to the
 * time left before until_s. Each sample is stamped with the time the read
 * that delivered it returned. The client must be streaming
 * (lep_client_start). Returns LEP_OK (full, or until_s reached),
 * LEP_E_TIMEOUT when no sample came for timeout_ms (< 0: wait forever),
 * LEP_E_ARG (NULL c, n or t, si without rated), LEP_E_STATE (not
 * streaming), or the client's error (LEP_E_DISCONNECTED, ...); nothing
 * already read is lost. */
LEP_API int lep_record_fill(lep_client *c, const double rated[6], size_t cap, size_t *n, double *t,
                            double *si, int16_t *raw, uint8_t *status, uint16_t *seq,
                            double until_s, int timeout_ms);

#ifdef __cplusplus
}
#endif

#endif
