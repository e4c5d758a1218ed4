/* The virtual sensor's digital filter: the FIR low-pass a filter code selects
 * (in effect after a power cycle), applied to what the sensor measures. */
#include <string.h>

#include "sim_filter.h"

#define PI 3.141592653589793

double lep_priv_fir_cutoff_hz(uint8_t code)
{
    static const double hz[4] = { 0.0, 10.0, 100.0, 200.0 };
    return code < 4u ? hz[code] : 0.0;
}

static double cosine(double x)
{
    return lep_priv_sine(x + PI / 2.0);
}

void lep_priv_fir_design(lep_sim_fir *f, uint8_t code, double rate_hz)
{
    double fc = lep_priv_fir_cutoff_hz(code), sum = 0.0, wc;
    size_t j, n, half;
    memset(f, 0, sizeof *f);
    f->taps = 1;
    f->h[0] = 1.0;
    if (fc <= 0.0 || fc >= rate_hz / 2.0)
        return;                          /* off, or nothing to cut below the Nyquist frequency */
    half = (size_t)(rate_hz / fc + 0.5); /* 2 * rate / fc + 1 taps */
    if (half > (LEP_SIM_FIR_MAX_TAPS - 1u) / 2u)
        half = (LEP_SIM_FIR_MAX_TAPS - 1u) / 2u;
    n = 2u * half + 1u;
    wc = 2.0 * PI * fc / rate_hz; /* cut-off in radians per sample */
    for (j = 0; j < n; j++) {
        double m = (double)j - (double)half;
        double w = 0.42 - 0.5 * cosine(2.0 * PI * (double)j / (double)(n - 1u)) +
                   0.08 * cosine(4.0 * PI * (double)j / (double)(n - 1u));
        double sinc = m == 0.0 ? wc / PI : lep_priv_sine(wc * m) / (PI * m);
        f->h[j] = w * sinc;
        sum += f->h[j];
    }
    for (j = 0; j < n; j++)
        f->h[j] /= sum; /* exactly unity gain at 0 Hz: a constant load passes unchanged */
    f->taps = n;
}

/* Input m of the filter: the signal clipped at the ADC's limit. */
static int input(const lep_sim_signal *g, uint64_t m, double x[LEP_AXES])
{
    int i, status = lep_priv_signal_counts(g, m, x);
    for (i = 0; i < LEP_AXES; i++)
        x[i] = lep_priv_signal_clip(x[i]);
    return status;
}

void lep_priv_fir_sample(const lep_sim_fir *f, const lep_sim_signal *g, uint64_t n, lep_sample *out)
{
    double y[LEP_AXES] = { 0 }, x[LEP_AXES];
    int status = input(g, n, x), i;
    size_t j;
    if (f->taps == 1) {
        lep_priv_signal_finish(x, status, out);
        return;
    }
    for (j = 0; j < f->taps; j++) {
        if (j > 0)
            (void)input(g, n >= j ? n - j : 0u, x);
        for (i = 0; i < LEP_AXES; i++)
            y[i] += f->h[j] * x[i];
    }
    lep_priv_signal_finish(y, status, out);
}

void lep_priv_fir_next(lep_sim_fir_state *st, const lep_sim_fir *f, const lep_sim_signal *g,
                       uint64_t n, lep_sample *out)
{
    double y[LEP_AXES] = { 0 }, x[LEP_AXES];
    int status, i;
    size_t j, p;
    if (f->taps == 1) {
        lep_priv_fir_sample(f, g, n, out);
        return;
    }
    if (!st->primed || n != st->next_n) {
        /* fill the ring with inputs n - taps + 1 .. n - 1 */
        for (j = f->taps - 1u; j > 0; j--) {
            p = f->taps - 1u - j;
            (void)input(g, n >= j ? n - j : 0u, st->x[p]);
        }
        st->pos = f->taps - 2u;
        st->primed = true;
    }
    status = input(g, n, x);
    st->pos = st->pos + 1u == f->taps ? 0u : st->pos + 1u;
    memcpy(st->x[st->pos], x, sizeof x);
    st->next_n = n + 1u;
    /* the same order of terms as lep_priv_fir_sample: bit for bit equal */
    p = st->pos;
    for (j = 0; j < f->taps; j++) {
        for (i = 0; i < LEP_AXES; i++)
            y[i] += f->h[j] * st->x[p][i];
        p = p == 0 ? f->taps - 1u : p - 1u;
    }
    lep_priv_signal_finish(y, status, out);
}
