/* What the virtual sensor measures: seedable waveform, replay, overloads. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
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

/* Parse one CSV line of 6 or 7 integers. Returns 1 for a row, 0 for a line
 * to skip (blank, comment, header), -1 for a malformed line. */
static int parse_row(const char *line, lep_sample *row, int16_t *status)
{
    const char *p = line;
    long v[7];
    int count = 0;
    while (*p == ' ' || *p == '\t')
        p++;
    if (*p == '\0' || *p == '\n' || *p == '\r' || *p == '#')
        return 0;
    if (isalpha((unsigned char)*p))
        return 0; /* a header line */
    for (;;) {
        char *end;
        if (count == 7)
            return -1;
        errno = 0;
        v[count] = strtol(p, &end, 10);
        if (end == p || errno != 0)
            return -1;
        count++;
        p = end;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == ',' || *p == ';') {
            p++;
            continue;
        }
        if (*p == '\0' || *p == '\n' || *p == '\r')
            break;
        return -1;
    }
    if (count < 6)
        return -1;
    memset(row, 0, sizeof *row);
    {
        int i;
        for (i = 0; i < LEP_AXES; i++) {
            if (v[i] < -32768 || v[i] > 32767)
                return -1;
            row->raw[i] = (int16_t)v[i];
        }
    }
    if (count == 7) {
        if (v[6] < 0 || v[6] > 255)
            return -1;
        *status = (int16_t)v[6];
    } else {
        *status = -1;
    }
    return 1;
}

static int load_replay(lep_sim_signal *g, const char *file, char *err, size_t errlen)
{
    char line[512];
    size_t cap = 0, lineno = 0;
    FILE *f = fopen(file, "r");
    if (f == NULL) {
        lep_priv_set_err(err, errlen, "%s: cannot open replay file: %s", file, strerror(errno));
        return errno == ENOENT ? LEP_E_NOT_FOUND : LEP_E_IO;
    }
    while (fgets(line, sizeof line, f) != NULL) {
        lep_sample row;
        int16_t status;
        int r;
        lineno++;
        r = parse_row(line, &row, &status);
        if (r == 0)
            continue;
        if (r < 0) {
            lep_priv_set_err(err, errlen,
                    "%s:%zu: expected 6 or 7 integers fx,fy,fz,mx,my,mz[,status] (int16, status 0..255)",
                    file, lineno);
            fclose(f);
            return LEP_E_VALUE;
        }
        if (g->replay_rows == cap) {
            size_t ncap = cap ? cap * 2 : 256;
            lep_sample *nr = realloc(g->replay, ncap * sizeof *nr);
            int16_t *ns;
            if (nr == NULL) {
                fclose(f);
                lep_priv_set_err(err, errlen, "%s: out of memory", file);
                return LEP_E_IO;
            }
            g->replay = nr;
            ns = realloc(g->replay_status, ncap * sizeof *ns);
            if (ns == NULL) {
                fclose(f);
                lep_priv_set_err(err, errlen, "%s: out of memory", file);
                return LEP_E_IO;
            }
            g->replay_status = ns;
            cap = ncap;
        }
        g->replay[g->replay_rows] = row;
        g->replay_status[g->replay_rows] = status;
        g->replay_rows++;
    }
    fclose(f);
    if (g->replay_rows == 0) {
        lep_priv_set_err(err, errlen, "%s: no samples in replay file", file);
        return LEP_E_VALUE;
    }
    return LEP_OK;
}

int lep_priv_signal_init(lep_sim_signal *g, const lep_sim_options *o, const lep_rated *rated,
                         char *err, size_t errlen)
{
    static const double base_hz[LEP_AXES] = {0.5, 0.7, 1.1, 1.3, 1.7, 1.9};
    uint64_t st;
    int i;
    memset(g, 0, sizeof *g);
    g->rated = *rated;
    g->rate_hz = o->rate_hz;
    g->amplitude = o->amplitude;
    g->noise = o->noise;
    g->constant = o->constant;
    g->seed = o->seed;
    g->overload_every_s = o->overload_every_s;
    g->overload_duration_s = o->overload_duration_s;
    st = o->seed;
    for (i = 0; i < LEP_AXES; i++) {
        g->freq[i] = base_hz[i] * (0.9 + 0.2 * lep_priv_uniform(&st));
        g->phase[i] = TWO_PI * lep_priv_uniform(&st);
    }
    if (o->replay_csv[0] != '\0') {
        int rc = load_replay(g, o->replay_csv, err, errlen);
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
static double sine(double x)
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
    return r * (1.0 - r2 / 6.0 * (1.0 - r2 / 20.0 * (1.0 - r2 / 42.0 * (1.0 - r2 / 72.0 *
                (1.0 - r2 / 110.0 * (1.0 - r2 / 156.0))))));
}

static int16_t saturate(double counts)
{
    if (counts > LEP_SATURATION_V113)
        return LEP_SATURATION_V113;
    if (counts < -LEP_SATURATION_V113)
        return -LEP_SATURATION_V113;
    return (int16_t)(counts >= 0 ? (int)(counts + 0.5) : -(int)(-counts + 0.5));
}

void lep_priv_signal_sample(const lep_sim_signal *g, uint64_t n, lep_sample *out)
{
    double t = (double)n / g->rate_hz;
    double counts[LEP_AXES];
    int i, given_status = -1, over = 0;
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
                v = g->amplitude * sine(TWO_PI * g->freq[i] * t + g->phase[i]) +
                    g->noise * (2.0 * lep_priv_uniform(&st) - 1.0);
            }
            counts[i] = v * LEP_RAW_FULL_SCALE;
        }
    }
    if (g->overload_every_s > 0 && g->overload_duration_s > 0 && t >= g->overload_every_s) {
        double k = floor_pos(t / g->overload_every_s);
        if (t - k * g->overload_every_s < g->overload_duration_s) {
            uint64_t episode = (uint64_t)k; /* 1, 2, ... */
            int axis = (int)((episode - 1u) % LEP_AXES);
            double sign = (episode & 1u) ? 1.0 : -1.0;
            counts[axis] = sign * OVERLOAD_LEVEL * LEP_RAW_FULL_SCALE;
        }
    }
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
