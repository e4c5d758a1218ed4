/* Host session, the processing chain (session_chain.h): overload episodes,
 * tare (averaged in raw counts), the host low-pass (2nd-order Butterworth),
 * payload compensation and limits (session_chain_load.c), decimation, rotation and
 * moment-point shift, and the end of a run (duration or count). Its rows and
 * events go into the sink it is given. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <string.h>

#include "leptrino/error.h"
#include "session_chain.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define LOWPASS_NAME "2nd-order Butterworth (bilinear, prewarped)"

/* ---- low-pass ---- */

void lep_priv_lowpass_design(session_lowpass *lp, double cutoff_hz, double fs)
{
    double k, k2, norm, tau;
    memset(lp, 0, sizeof *lp);
    if (cutoff_hz <= 0.0 || fs <= 0.0)
        return;
    /* Bilinear transform of the analog Butterworth prototype, with the
     * cut-off pre-warped so that the -3 dB point is exactly cutoff_hz. */
    k = tan(M_PI * cutoff_hz / fs);
    k2 = k * k;
    norm = 1.0 / (1.0 + sqrt(2.0) * k + k2);
    lp->cutoff_hz = cutoff_hz;
    lp->b0 = k2 * norm;
    lp->b1 = 2.0 * lp->b0;
    lp->b2 = lp->b0;
    lp->a1 = 2.0 * (k2 - 1.0) * norm;
    lp->a2 = (1.0 - sqrt(2.0) * k + k2) * norm;
    /* Group delay at 0 Hz in samples: sum(i b_i)/sum(b_i) - sum(i a_i)/sum(a_i)
     * (a_0 = 1); the numerator's part is 1 for b = b0 (1, 2, 1). */
    tau = 1.0 - (lp->a1 + 2.0 * lp->a2) / (1.0 + lp->a1 + lp->a2);
    lp->delay_s = tau / fs;
    lp->settle_n = (uint32_t)ceil(fs / cutoff_hz);
}

/* Filter raw counts x into y (direct form II transposed). The first sample
 * after a (re)start sets the state to the steady state for it, so there is no
 * start-up transient from zero. */
static bool lowpass_run(session_lowpass *lp, const int16_t raw[LEP_AXES], double y[LEP_AXES])
{
    int k;
    if (!lp->primed) {
        for (k = 0; k < LEP_AXES; k++) {
            double x = (double)raw[k];
            lp->z2[k] = (lp->b2 - lp->a2) * x;
            lp->z1[k] = (lp->b1 - lp->a1) * x + lp->z2[k];
        }
        lp->primed = true;
        lp->settle = lp->settle_n;
    }
    for (k = 0; k < LEP_AXES; k++) {
        double x = (double)raw[k];
        double out = lp->b0 * x + lp->z1[k];
        lp->z1[k] = lp->b1 * x - lp->a1 * out + lp->z2[k];
        lp->z2[k] = lp->b2 * x - lp->a2 * out;
        y[k] = out;
    }
    if (lp->settle > 0) {
        lp->settle--;
        return true;
    }
    return false;
}

int lep_priv_chain_set_lowpass(session_chain *ch, double cutoff_hz, double fs)
{
    if (!isfinite(cutoff_hz) || cutoff_hz < 0.0 || cutoff_hz > 0.45 * fs)
        return LEP_E_VALUE;
    lep_priv_lowpass_design(&ch->lp, cutoff_hz, fs);
    return LEP_OK;
}

void lep_priv_chain_restart_filter(session_chain *ch)
{
    ch->lp.primed = false;
}

void lep_priv_chain_hole(session_chain *ch)
{
    ch->lp.settle = ch->lp.settle_n; /* the filter's output after a hole is a transient */
}

/* ---- rotation ---- */

void lep_rotation_from_rpy(double roll, double pitch, double yaw, double r[9])
{
    double cr = cos(roll), sr = sin(roll);
    double cp = cos(pitch), sp = sin(pitch);
    double cy = cos(yaw), sy = sin(yaw);
    if (r == NULL)
        return;
    r[0] = cy * cp;
    r[1] = cy * sp * sr - sy * cr;
    r[2] = cy * sp * cr + sy * sr;
    r[3] = sy * cp;
    r[4] = sy * sp * sr + cy * cr;
    r[5] = sy * sp * cr - cy * sr;
    r[6] = -sp;
    r[7] = cp * sr;
    r[8] = cp * cr;
}

int lep_priv_chain_set_rotation(session_chain *ch, const double rotation[9],
                                const double shift_m[3])
{
    static const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    static const double zero[3] = { 0, 0, 0 };
    const double *r = rotation != NULL ? rotation : identity;
    const double *p = shift_m != NULL ? shift_m : zero;
    int i, j, k;
    for (i = 0; i < 9; i++)
        if (!isfinite(r[i]))
            return LEP_E_VALUE;
    for (i = 0; i < 3; i++)
        if (!isfinite(p[i]))
            return LEP_E_VALUE;
    /* Orthonormal (a rotation, or one with a mirrored axis): R R^T = I. */
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            double d = 0.0;
            for (k = 0; k < 3; k++)
                d += r[i * 3 + k] * r[j * 3 + k];
            if (fabs(d - (i == j ? 1.0 : 0.0)) > 1e-6)
                return LEP_E_VALUE;
        }
    }
    memcpy(ch->rot, r, sizeof ch->rot);
    memcpy(ch->shift, p, sizeof ch->shift);
    return LEP_OK;
}

/* f' = R f, m' = R m - r x f' (the moment about the point r). */
static void rotate(const session_chain *pr, double v[LEP_AXES])
{
    const double *r = pr->rot, *p = pr->shift;
    double f[3], m[3];
    int i;
    for (i = 0; i < 3; i++) {
        f[i] = r[i * 3] * v[0] + r[i * 3 + 1] * v[1] + r[i * 3 + 2] * v[2];
        m[i] = r[i * 3] * v[3] + r[i * 3 + 1] * v[4] + r[i * 3 + 2] * v[5];
    }
    v[0] = f[0];
    v[1] = f[1];
    v[2] = f[2];
    v[3] = m[0] - (p[1] * f[2] - p[2] * f[1]);
    v[4] = m[1] - (p[2] * f[0] - p[0] * f[2]);
    v[5] = m[2] - (p[0] * f[1] - p[1] * f[0]);
}

/* ---- the run ---- */

void lep_priv_chain_init(session_chain *ch, const lep_session_options *o,
                         const session_chain_config *cfg)
{
    memset(ch, 0, sizeof *ch);
    ch->cfg = *cfg;
    memcpy(ch->rot, o->rotation, sizeof ch->rot);
    memcpy(ch->shift, o->shift_m, sizeof ch->shift);
    ch->decimate = o->decimate;
    lep_priv_load_init(&ch->load, o);
}

/* ---- tare ---- */

static void begin_tare(session_chain *ch, unsigned n, double duration_s, bool hold)
{
    ch->taring = true;
    ch->tare_hold = hold;
    ch->tare_n_goal = n;
    ch->tare_duration = duration_s;
    ch->tare_until = 0.0;
    ch->tare_n = 0;
    memset(ch->tare_sum, 0, sizeof ch->tare_sum);
}

void lep_priv_chain_start(session_chain *ch)
{
    if (ch->cfg.tare_samples > 0)
        begin_tare(ch, ch->cfg.tare_samples, 0.0, true);
    ch->lp.primed = false;
    lep_priv_load_start(&ch->load);
    ch->dec_phase = 0;
    ch->carry_flags = 0;
    ch->overloaded = false;
    ch->ended = false;
    ch->first_delivered_t = 0.0;
}

void lep_priv_chain_stop(session_chain *ch)
{
    ch->taring = false;
    ch->tare_hold = false;
}

bool lep_priv_chain_ended(const session_chain *ch)
{
    return ch->ended;
}

static void tare_event(const session_chain *ch, session_sink *sk, double t, uint64_t sample)
{
    lep_session_event ev;
    lep_priv_event_init(&ev, LEP_EV_TARE, sample, t);
    memcpy(ev.tare, ch->tare, sizeof ev.tare);
    lep_priv_sink_event(sk, &ev);
}

/* The new offset applies from row number `sample` on. With a payload set,
 * the offset is the bias alone: the mean less the payload's expected wrench
 * at the gravity in force. */
static void tare_finish(session_chain *ch, session_sink *sk, double t, uint64_t sample)
{
    double payload[LEP_AXES];
    int k;
    lep_priv_load_counts(&ch->load, &ch->cfg.rated, payload);
    for (k = 0; k < LEP_AXES; k++)
        ch->tare[k] = ch->tare_sum[k] / (double)ch->tare_n - payload[k];
    ch->tared = true;
    ch->taring = false;
    ch->tare_hold = false;
    tare_event(ch, sk, t, sample);
}

void lep_priv_chain_tare(session_chain *ch, unsigned n, double duration_s)
{
    begin_tare(ch, n, n > 0 ? 0.0 : duration_s, false);
}

void lep_priv_chain_set_tare(session_chain *ch, session_sink *sk, const double offset[LEP_AXES],
                             double t, uint64_t sample)
{
    ch->taring = false;
    ch->tare_hold = false;
    ch->tared = offset != NULL;
    if (offset != NULL)
        memcpy(ch->tare, offset, sizeof ch->tare);
    else
        memset(ch->tare, 0, sizeof ch->tare);
    tare_event(ch, sk, t, sample);
}

bool lep_priv_chain_tared(const session_chain *ch, double offset[LEP_AXES])
{
    if (offset != NULL)
        memcpy(offset, ch->tare, sizeof ch->tare);
    return ch->tared;
}

bool lep_priv_chain_taring(const session_chain *ch)
{
    return ch->taring;
}

void lep_priv_chain_meta(const session_chain *ch, lep_session_meta *out)
{
    out->lowpass_hz = ch->lp.cutoff_hz;
    if (ch->lp.cutoff_hz > 0.0) {
        size_t n = sizeof LOWPASS_NAME < sizeof out->lowpass_name ? sizeof LOWPASS_NAME
                                                                  : sizeof out->lowpass_name;
        memcpy(out->lowpass_name, LOWPASS_NAME, n);
        out->lowpass_name[sizeof out->lowpass_name - 1u] = '\0';
        out->lowpass_delay_s = ch->lp.delay_s;
    }
    out->decimate = ch->decimate;
    memcpy(out->rotation, ch->rot, sizeof out->rotation);
    memcpy(out->shift_m, ch->shift, sizeof out->shift_m);
    out->tared = ch->tared;
    memcpy(out->tare, ch->tare, sizeof out->tare);
    lep_priv_load_meta(&ch->load, out);
}

/* ---- one sample ---- */

static void overload(session_chain *ch, session_sink *sk, const lep_sample *smp, double t,
                     uint8_t *flags)
{
    uint8_t axes = lep_sample_saturated(smp, ch->cfg.saturation);
    bool over = (smp->status & LEP_STATUS_OVERLOAD) != 0u || axes != 0u;
    lep_session_event ev;
    if (over)
        *flags |= LEP_SF_OVERLOAD;
    if (over == ch->overloaded)
        return;
    ch->overloaded = over;
    lep_priv_event_init(&ev, over ? LEP_EV_OVERLOAD_BEGIN : LEP_EV_OVERLOAD_END,
                        lep_priv_sink_processed(sk), t);
    ev.axes = axes;
    ev.status = smp->status;
    lep_priv_sink_event(sk, &ev); /* counts an overload begun */
}

/* zeroed, si (tare after the filter: exact, as the filter's gain at 0 Hz is
 * 1; the payload's gravity wrench removed), rotated and shifted; the
 * sample's own fields. */
static void fill_row(const session_chain *ch, const lep_sample *smp, const double y[LEP_AXES],
                     const double off[LEP_AXES], session_row *row)
{
    int k;
    memcpy(row->raw, smp->raw, sizeof row->raw);
    for (k = 0; k < LEP_AXES; k++) {
        row->zeroed[k] = (double)smp->raw[k] - off[k];
        row->si[k] = (y[k] - off[k]) * (double)ch->cfg.rated.axis[k] / (double)LEP_RAW_FULL_SCALE;
    }
    lep_priv_load_compensate(&ch->load, row->si);
    rotate(ch, row->si);
    row->status = smp->status;
    row->seq = smp->reserved;
}

void lep_priv_chain_one(const session_chain *ch, const lep_sample *smp, double t, double t_utc,
                        session_row *row)
{
    double y[LEP_AXES];
    int k;
    for (k = 0; k < LEP_AXES; k++)
        y[k] = (double)smp->raw[k];
    fill_row(ch, smp, y, ch->tare, row);
    row->t_mono = t;
    row->t_utc = t_utc;
    row->arrived = t;
    row->flags = (smp->status & LEP_STATUS_OVERLOAD) != 0u ||
                         lep_sample_saturated(smp, ch->cfg.saturation) != 0u
                     ? LEP_SF_OVERLOAD
                     : 0u;
}

void lep_priv_chain_sample(session_chain *ch, session_sink *sk, const lep_sample *smp, double t,
                           double t_utc, double arrived, uint8_t flags)
{
    double y[LEP_AXES], off[LEP_AXES];
    int k;
    uint32_t phase;
    uint64_t processed = lep_priv_sink_processed(sk);
    session_row row;

    if (ch->ended)
        return;
    overload(ch, sk, smp, t, &flags);
    if (ch->lp.cutoff_hz > 0.0) {
        if (lowpass_run(&ch->lp, smp->raw, y))
            flags |= LEP_SF_SETTLING;
    } else {
        for (k = 0; k < LEP_AXES; k++)
            y[k] = (double)smp->raw[k];
    }
    memcpy(off, ch->tare, sizeof off); /* a sample averaged by a tare keeps the old offset */
    if (ch->taring) {
        bool by_time = ch->tare_n_goal == 0;
        if (by_time && ch->tare_n == 0)
            ch->tare_until = t + ch->tare_duration;
        if (by_time && t >= ch->tare_until && ch->tare_n > 0) {
            tare_finish(ch, sk, t, processed); /* this sample comes after the averaging time */
            memcpy(off, ch->tare, sizeof off);
        } else {
            bool hold = ch->tare_hold;
            for (k = 0; k < LEP_AXES; k++)
                ch->tare_sum[k] += (double)smp->raw[k];
            ch->tare_n++;
            flags |= LEP_SF_TARING;
            if (!by_time && ch->tare_n >= ch->tare_n_goal)
                tare_finish(ch, sk, t, processed + (hold || ch->dec_phase != 0u ? 0u : 1u));
            if (hold) {
                ch->carry_flags |= flags & LEP_SF_GAP;
                return;
            }
        }
    }
    phase = ch->dec_phase;
    ch->dec_phase = ch->decimate > 1u ? (phase + 1u) % ch->decimate : 0u;
    if (phase != 0u) {
        ch->carry_flags |= flags & LEP_SF_GAP;
        return;
    }
    if (ch->cfg.duration_s > 0.0 && processed > 0 &&
        t - ch->first_delivered_t >= ch->cfg.duration_s) {
        ch->ended = true;
        return;
    }
    flags |= ch->carry_flags;
    ch->carry_flags = 0;
    row.t_mono = t;
    row.t_utc = t_utc;
    row.arrived = arrived;
    fill_row(ch, smp, y, off, &row);
    row.flags = flags | lep_priv_load_limits(&ch->load, sk, row.si, t, processed);
    if (processed == 0)
        ch->first_delivered_t = t;
    lep_priv_sink_row(sk, &row); /* row number `processed` */
    if (ch->cfg.count > 0 && processed + 1u >= ch->cfg.count)
        ch->ended = true;
}
