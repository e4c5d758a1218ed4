/* What the virtual sensor measures: seedable waveform, replay, overloads. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "leptrino/payload.h"
#include "struct_api.h"
#include "sim_signal.h"

#define TWO_PI 6.283185307179586
/* An overload episode pushes one axis to 4x rated: beyond 3.2x it saturates. */
#define OVERLOAD_LEVEL 4.0

uint64_t lep_priv_splitmix64(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

double lep_priv_uniform(uint64_t *state)
{
    return (double)(lep_priv_splitmix64(state) >> 11) * (1.0 / 9007199254740992.0);
}

int lep_priv_signal_init(lep_sim_signal *g, const lep_sim_options *o, const lep_rated *rated,
                         char *err, size_t errlen)
{
    static const double base_hz[LEP_AXES] = { 0.5, 0.7, 1.1, 1.3, 1.7, 1.9 };
    uint64_t st;
    int i;
    memset(g, 0, sizeof *g);
    g->rated = *rated;
    g->rate_hz = o->rate_hz;
    g->amplitude = o->amplitude;
    g->noise = o->noise;
    g->constant = o->constant;
    g->seed = o->seed;
    /* Episodes in whole samples of the sample clock, so that each is as long
     * as every other (0.05 s at 1.2 kHz: 60 samples, never 59 or 61). */
    if (o->overload_every_s > 0 && o->overload_duration_s > 0) {
        g->overload_every_n = (uint64_t)(o->overload_every_s * o->rate_hz + 0.5);
        g->overload_duration_n = (uint64_t)(o->overload_duration_s * o->rate_hz + 0.5);
        if (g->overload_duration_n == 0)
            g->overload_duration_n = 1;
        if (g->overload_duration_n >= g->overload_every_n) /* under two samples apart */
            g->overload_every_n = g->overload_duration_n = 0;
    }
    {
        /* what the tool weighs at this orientation, through the rated values */
        lep_payload p;
        double w[LEP_AXES];
        p.mass_kg = o->payload[0];
        memcpy(p.com_m, &o->payload[1], sizeof p.com_m);
        if (lep_payload_wrench_p(&p, o->gravity, w) != LEP_OK) {
            lep_priv_set_err(err, errlen, "payload or gravity: not finite, or a negative mass");
            return LEP_E_ARG; /* lep_sim_options_check refuses it first */
        }
        for (i = 0; i < LEP_AXES; i++)
            g->payload_counts[i] = w[i] / (double)rated->axis[i] * LEP_RAW_FULL_SCALE;
    }
    st = o->seed;
    for (i = 0; i < LEP_AXES; i++) {
        g->freq[i] = base_hz[i] * (0.9 + 0.2 * lep_priv_uniform(&st));
        g->phase[i] = TWO_PI * lep_priv_uniform(&st);
    }
    if (o->replay_csv[0] != '\0') {
        int rc = lep_priv_replay_load(g, o->replay_csv, err, errlen);
        if (rc != LEP_OK) {
            lep_priv_signal_free(g);
            return rc;
        }
    }
    return LEP_OK;
}

void lep_priv_signal_free(lep_sim_signal *g)
{
    free(g->replay);
    free(g->replay_status);
    g->replay = NULL;
    g->replay_status = NULL;
    g->replay_rows = 0;
}

/* Small math of our own so the library needs no libm. */
static double floor_pos(double x) /* x >= 0, < 2^62 */
{
    return (double)(uint64_t)x;
}

static double abs_d(double x)
{
    return x < 0 ? -x : x;
}

/* sin(x) to ~1e-9 after reduction to [-pi/2, pi/2]. */
double lep_priv_sine(double x)
{
    double k, r, r2;
    const double pi = TWO_PI / 2.0;
    k = x >= 0 ? floor_pos(x / TWO_PI) : -floor_pos(-x / TWO_PI) - 1.0;
    r = x - k * TWO_PI; /* [0, 2pi) */
    if (r > pi)
        r -= TWO_PI; /* (-pi, pi] */
    if (r > pi / 2)
        r = pi - r;
    else if (r < -pi / 2)
        r = -pi - r;
    r2 = r * r;
    return r * (1.0 -
                r2 / 6.0 *
                    (1.0 -
                     r2 / 20.0 *
                         (1.0 - r2 / 42.0 *
                                    (1.0 - r2 / 72.0 * (1.0 - r2 / 110.0 * (1.0 - r2 / 156.0))))));
}

static int16_t saturate(double counts)
{
    if (counts > LEP_SATURATION_V113)
        return LEP_SATURATION_V113;
    if (counts < -LEP_SATURATION_V113)
        return -LEP_SATURATION_V113;
    return (int16_t)(counts >= 0 ? (int)(counts + 0.5) : -(int)(-counts + 0.5));
}

int lep_priv_signal_counts(const lep_sim_signal *g, uint64_t n, double counts[LEP_AXES])
{
    double t = (double)n / g->rate_hz;
    int i, given_status = -1;
    if (g->replay != NULL) {
        size_t row = (size_t)(n % g->replay_rows);
        for (i = 0; i < LEP_AXES; i++)
            counts[i] = g->replay[row].raw[i];
        given_status = g->replay_status[row];
    } else {
        for (i = 0; i < LEP_AXES; i++) {
            double v;
            if (g->constant) {
                v = g->amplitude;
            } else {
                uint64_t st = g->seed ^ (n * 0xD1B54A32D192ED03u) ^ ((uint64_t)i << 56);
                v = g->amplitude * lep_priv_sine(TWO_PI * g->freq[i] * t + g->phase[i]) +
                    g->noise * (2.0 * lep_priv_uniform(&st) - 1.0);
            }
            counts[i] = v * LEP_RAW_FULL_SCALE + g->payload_counts[i];
        }
    }
    if (g->overload_every_n > 0 && n >= g->overload_every_n &&
        n % g->overload_every_n < g->overload_duration_n) {
        uint64_t episode = n / g->overload_every_n; /* 1, 2, ... */
        int axis = (int)((episode - 1u) % LEP_AXES);
        double sign = (episode & 1u) ? 1.0 : -1.0;
        counts[axis] = sign * OVERLOAD_LEVEL * LEP_RAW_FULL_SCALE;
    }
    return given_status;
}

void lep_priv_signal_finish(const double counts[LEP_AXES], int given_status, lep_sample *out)
{
    int i, over = 0;
    memset(out, 0, sizeof *out);
    for (i = 0; i < LEP_AXES; i++) {
        if (abs_d(counts[i]) > LEP_RAW_FULL_SCALE)
            over = 1;
        out->raw[i] = saturate(counts[i]);
    }
    if (given_status >= 0)
        out->status = (uint8_t)given_status;
    else
        out->status = over ? (uint8_t)LEP_STATUS_OVERLOAD : 0u;
    if (given_status >= 0 && over)
        out->status |= LEP_STATUS_OVERLOAD;
}

double lep_priv_signal_clip(double counts)
{
    if (counts > LEP_SATURATION_V113)
        return LEP_SATURATION_V113;
    if (counts < -LEP_SATURATION_V113)
        return -LEP_SATURATION_V113;
    return counts;
}
