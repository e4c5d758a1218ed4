/* Private: what the virtual sensor measures (models, waveform, replay). */
#ifndef LEPTRINO_SIM_SIGNAL_H
#define LEPTRINO_SIM_SIGNAL_H

#include <stddef.h>
#include <stdint.h>

#include "leptrino/message.h"
#include "leptrino/sim.h"
#include "struct_api.h"

/* splitmix64: a small seedable generator (no rand(), no global state). */
uint64_t lep_priv_splitmix64(uint64_t *state);
/* Uniform in [0, 1). */
double lep_priv_uniform(uint64_t *state);
/* sin(x) to about 1e-9 (the library needs no libm). */
double lep_priv_sine(double x);

typedef struct lep_sim_signal {
    lep_rated rated;
    double rate_hz;
    double amplitude, noise;
    int constant;
    uint64_t seed;
    double freq[LEP_AXES], phase[LEP_AXES];
    uint64_t overload_every_n, overload_duration_n; /* in samples (0: no episodes) */
    double payload_counts[LEP_AXES];                /* the payload's gravity wrench, in counts */
    lep_sample *replay;     /* rows of the replay file (status -1 = derive), or NULL */
    int16_t *replay_status; /* per row: status given in the file, or -1 */
    size_t replay_rows;
} lep_sim_signal;

/* Set up from the options (loads the replay file). On failure returns a
 * LEP_E_* code with a one-line message in err. */
int lep_priv_signal_init(lep_sim_signal *g, const lep_sim_options *o, const lep_rated *rated,
                         char *err, size_t errlen);
void lep_priv_signal_free(lep_sim_signal *g);

/* sim_replay.c: read a replay file into g->replay (rows of raw counts and
 * the status each gives, or -1). LEP_E_NOT_FOUND/LEP_E_IO/LEP_E_VALUE with a
 * message naming the file and line. On failure g may hold rows already
 * read: lep_priv_signal_free releases them. */
int lep_priv_replay_load(lep_sim_signal *g, const char *file, char *err, size_t errlen);

/* What the sensor measures at index n of the sample clock (t = n / rate_hz),
 * in counts before the ADC's limit (an overload may exceed it): a pure
 * function of the options, the seed and n. Returns the status byte given by a
 * replay file for that row, or -1 (derive it). */
int lep_priv_signal_counts(const lep_sim_signal *g, uint64_t n, double counts[LEP_AXES]);

/* Counts to a sample: rounded and saturated at +/-32000, status bit 2 where
 * any axis exceeds rated (+/-10000), or the given status (>= 0) plus that
 * bit. reserved is left 0. */
void lep_priv_signal_finish(const double counts[LEP_AXES], int given_status, lep_sample *out);

/* The ADC's limit: counts clipped to +/-32000. */
double lep_priv_signal_clip(double counts);

#endif
