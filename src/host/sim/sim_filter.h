/* Private: the sensor's digital filter (an FIR low-pass per filter code),
 * applied to what the virtual sensor measures. */
#ifndef LEPTRINO_SIM_FILTER_H
#define LEPTRINO_SIM_FILTER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/message.h"
#include "sim_signal.h"

/* Longest filter: 2 * rate / cut-off + 1 taps, at most this many. */
#define LEP_SIM_FIR_MAX_TAPS 255u

/* The coefficients of one filter code at one sample rate (read-only once made). */
typedef struct lep_sim_fir {
    size_t taps; /* odd; 1 is pass-through */
    double h[LEP_SIM_FIR_MAX_TAPS];
} lep_sim_fir;

/* The last inputs, for computing a stream's samples in order cheaply. */
typedef struct lep_sim_fir_state {
    double x[LEP_SIM_FIR_MAX_TAPS][LEP_AXES]; /* ring of inputs, clipped counts */
    size_t pos;                               /* slot of input next_n - 1 */
    uint64_t next_n;                          /* the input index the ring expects next */
    bool primed;
} lep_sim_fir_state;

/* Cut-off of a filter code per spec v1.13: 0 off, 1: 10 Hz, 2: 100 Hz, 3: 200 Hz. */
double lep_priv_fir_cutoff_hz(uint8_t code);

/* Design the filter of a code (0..3) at rate_hz: a Blackman-windowed sinc,
 * linear phase, unity gain at 0 Hz. */
void lep_priv_fir_design(lep_sim_fir *f, uint8_t code, double rate_hz);

/* Sample n of the filtered signal, computed from the signal alone: a pure
 * function of (g, f, n). Inputs before index 0 are taken as input 0 (the
 * load held before the clock started). */
void lep_priv_fir_sample(const lep_sim_fir *f, const lep_sim_signal *g, uint64_t n,
                         lep_sample *out);

/* The same sample, bit for bit, using and updating st: one new input per
 * call when n follows the previous call's n, else st is refilled. */
void lep_priv_fir_next(lep_sim_fir_state *st, const lep_sim_fir *f, const lep_sim_signal *g,
                       uint64_t n, lep_sample *out);

#endif
