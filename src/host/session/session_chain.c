/* Host session, the processing of each sample: overload episodes, tare
 * (averaged in raw counts), the host low-pass (2nd-order Butterworth),
 * payload compensation and limits (session_load.c), decimation, rotation and
 * moment-point shift, and the end of a run (duration or count). */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <string.h>

#include "leptrino/error.h"
#include "session_priv.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

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

void lep_priv_lowpass_restart(session_lowpass *lp)
{
    lp->primed = false;
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

int lep_session_set_lowpass(lep_session *s, double cutoff_hz)
{
    if (s == NULL)
        return LEP_E_ARG;
    if (!isfinite(cutoff_hz) || cutoff_hz < 0.0 || cutoff_hz > 0.45 * s->nominal_hz)
        return LEP_E_VALUE;
    pthread_mutex_lock(&s->mu);
    lep_priv_lowpass_design(&s->proc.lp, cutoff_hz, s->nominal_hz);
    pthread_mutex_unlock(&s->mu);
    return LEP_OK;
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

int lep_session_set_rotation(lep_session *s, const double rotation[9], const double shift_m[3])
{
    static const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    static const double zero[3] = { 0, 0, 0 };
    const double *r = rotation != NULL ? rotation : identity;
    const double *p = shift_m != NULL ? shift_m : zero;
    int i, j, k;
    if (s == NULL)
        return LEP_E_ARG;
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
    pthread_mutex_lock(&s->mu);
    memcpy(s->proc.rot, r, sizeof s->proc.rot);
    memcpy(s->proc.shift, p, sizeof s->proc.shift);
    pthread_mutex_unlock(&s->mu);
    return LEP_OK;
}

/* f' = R f, m' = R m - r x f' (the moment about the point r). */
static void rotate(const session_proc *pr, double v[LEP_AXES])
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

/* ---- tare ---- */

static void begin_tare(lep_session *s, unsigned n, double duration_s, bool hold)
{
    s->proc.taring = true;
    s->proc.tare_hold = hold;
    s->proc.tare_n_goal = n;
    s->proc.tare_duration = duration_s;
    s->proc.tare_until = 0.0;
    s->proc.tare_n = 0;
    memset(s->proc.tare_sum, 0, sizeof s->proc.tare_sum);
}

void lep_priv_proc_start(lep_session *s)
{
    session_proc *p = &s->proc;
    if (s->opt.tare_samples > 0)
        begin_tare(s, s->opt.tare_samples, 0.0, true);
    lep_priv_lowpass_restart(&p->lp);
    lep_priv_load_start(&s->load);
    p->dec_phase = 0;
    p->carry_flags = 0;
    p->overloaded = false;
    p->ended = false;
    p->first_delivered_t = 0.0;
}

void lep_priv_proc_stop(session_proc *p)
{
    p->taring = false;
    p->tare_hold = false;
}

static void tare_event(lep_session *s, double t, uint64_t sample)
{
    lep_session_event ev;
    lep_priv_event_init(&ev, LEP_EV_TARE, sample, t);
    memcpy(ev.tare, s->proc.tare, sizeof ev.tare);
    lep_priv_sink_event(&s->sink, &ev);
}

/* The new offset applies from delivered sample number `sample` on. With a
 * payload set, the offset is the bias alone: the mean less the payload's
 * expected wrench at the gravity in force. */
static void tare_finish(lep_session *s, double t, uint64_t sample)
{
    double payload[LEP_AXES];
    int k;
    lep_priv_load_counts(&s->load, &s->rated, payload);
    for (k = 0; k < LEP_AXES; k++)
        s->proc.tare[k] = s->proc.tare_sum[k] / (double)s->proc.tare_n - payload[k];
    s->proc.tared = true;
    s->proc.taring = false;
    s->proc.tare_hold = false;
    tare_event(s, t, sample);
}

int lep_session_tare(lep_session *s, int samples, double duration_s)
{
    if (s == NULL || samples < 0 || !isfinite(duration_s) || duration_s < 0.0 ||
        (samples == 0 && duration_s <= 0.0))
        return LEP_E_ARG;
    pthread_mutex_lock(&s->mu);
    begin_tare(s, (unsigned)samples, samples > 0 ? 0.0 : duration_s, false);
    pthread_mutex_unlock(&s->mu);
    return LEP_OK;
}

int lep_session_untare(lep_session *s)
{
    if (s == NULL)
        return LEP_E_ARG;
    pthread_mutex_lock(&s->mu);
    s->proc.taring = false;
    s->proc.tare_hold = false;
    s->proc.tared = false;
    memset(s->proc.tare, 0, sizeof s->proc.tare);
    tare_event(s, lep_monotonic_seconds(), lep_priv_sink_processed(&s->sink));
    pthread_mutex_unlock(&s->mu);
    return LEP_OK;
}

int lep_session_set_tare(lep_session *s, const double offset[LEP_AXES])
{
    int k;
    if (s == NULL || offset == NULL)
        return LEP_E_ARG;
    for (k = 0; k < LEP_AXES; k++)
        if (!isfinite(offset[k]))
            return LEP_E_ARG;
    pthread_mutex_lock(&s->mu);
    s->proc.taring = false;
    s->proc.tare_hold = false;
    s->proc.tared = true;
    memcpy(s->proc.tare, offset, sizeof s->proc.tare);
    tare_event(s, lep_monotonic_seconds(), lep_priv_sink_processed(&s->sink));
    pthread_mutex_unlock(&s->mu);
    return LEP_OK;
}

int lep_session_get_tare(lep_session *s, double offset[LEP_AXES])
{
    bool tared;
    if (s == NULL) {
        if (offset != NULL)
            memset(offset, 0, sizeof(double) * LEP_AXES);
        return LEP_E_ARG;
    }
    pthread_mutex_lock(&s->mu);
    if (offset != NULL)
        memcpy(offset, s->proc.tare, sizeof s->proc.tare);
    tared = s->proc.tared;
    pthread_mutex_unlock(&s->mu);
    return tared ? 1 : 0;
}

int lep_session_taring(lep_session *s)
{
    bool taring;
    if (s == NULL)
        return 0;
    pthread_mutex_lock(&s->mu);
    taring = s->proc.taring;
    pthread_mutex_unlock(&s->mu);
    return taring ? 1 : 0;
}

/* ---- one sample ---- */

static void overload(lep_session *s, const lep_sample *smp, double t, uint8_t *flags)
{
    uint8_t axes = lep_sample_saturated(smp, s->saturation);
    bool over = (smp->status & LEP_STATUS_OVERLOAD) != 0u || axes != 0u;
    lep_session_event ev;
    if (over)
        *flags |= LEP_SF_OVERLOAD;
    if (over == s->proc.overloaded)
        return;
    s->proc.overloaded = over;
    lep_priv_event_init(&ev, over ? LEP_EV_OVERLOAD_BEGIN : LEP_EV_OVERLOAD_END,
                        lep_priv_sink_processed(&s->sink), t);
    ev.axes = axes;
    ev.status = smp->status;
    lep_priv_sink_event(&s->sink, &ev); /* counts an overload begun */
}

/* zeroed, si (tare after the filter: exact, as the filter's gain at 0 Hz is
 * 1; the payload's gravity wrench removed), rotated and shifted; the
 * sample's own fields. */
static void fill_row(const lep_session *s, const lep_sample *smp, const double y[LEP_AXES],
                     const double off[LEP_AXES], session_row *row)
{
    int k;
    memcpy(row->raw, smp->raw, sizeof row->raw);
    for (k = 0; k < LEP_AXES; k++) {
        row->zeroed[k] = (double)smp->raw[k] - off[k];
        row->si[k] = (y[k] - off[k]) * (double)s->rated.axis[k] / (double)LEP_RAW_FULL_SCALE;
    }
    lep_priv_load_compensate(&s->load, row->si);
    rotate(&s->proc, row->si);
    row->status = smp->status;
    row->seq = smp->reserved;
}

void lep_priv_proc_one(const lep_session *s, const lep_sample *smp, double t, double t_utc,
                       session_row *row)
{
    double y[LEP_AXES];
    int k;
    for (k = 0; k < LEP_AXES; k++)
        y[k] = (double)smp->raw[k];
    fill_row(s, smp, y, s->proc.tare, row);
    row->t_mono = t;
    row->t_utc = t_utc;
    row->flags =
        (smp->status & LEP_STATUS_OVERLOAD) != 0u || lep_sample_saturated(smp, s->saturation) != 0u
            ? LEP_SF_OVERLOAD
            : 0u;
}

bool lep_priv_session_process(lep_session *s, const lep_sample *smp, double t, double t_utc,
                              double arrived, uint8_t flags)
{
    double y[LEP_AXES], off[LEP_AXES];
    int k;
    uint32_t phase;
    uint64_t processed = lep_priv_sink_processed(&s->sink);
    session_row row_, *row = &row_;

    if (s->proc.ended)
        return false;
    overload(s, smp, t, &flags);
    if (s->proc.lp.cutoff_hz > 0.0) {
        if (lowpass_run(&s->proc.lp, smp->raw, y))
            flags |= LEP_SF_SETTLING;
    } else {
        for (k = 0; k < LEP_AXES; k++)
            y[k] = (double)smp->raw[k];
    }
    memcpy(off, s->proc.tare, sizeof off); /* a sample averaged by a tare keeps the old offset */
    if (s->proc.taring) {
        bool by_time = s->proc.tare_n_goal == 0;
        if (by_time && s->proc.tare_n == 0)
            s->proc.tare_until = t + s->proc.tare_duration;
        if (by_time && t >= s->proc.tare_until && s->proc.tare_n > 0) {
            tare_finish(s, t, processed); /* this sample comes after the averaging time */
            memcpy(off, s->proc.tare, sizeof off);
        } else {
            bool hold = s->proc.tare_hold;
            for (k = 0; k < LEP_AXES; k++)
                s->proc.tare_sum[k] += (double)smp->raw[k];
            s->proc.tare_n++;
            flags |= LEP_SF_TARING;
            if (!by_time && s->proc.tare_n >= s->proc.tare_n_goal)
                tare_finish(s, t, processed + (hold || s->proc.dec_phase != 0u ? 0u : 1u));
            if (hold) {
                s->proc.carry_flags |= flags & LEP_SF_GAP;
                return false;
            }
        }
    }
    phase = s->proc.dec_phase;
    s->proc.dec_phase = s->proc.decimate > 1u ? (phase + 1u) % s->proc.decimate : 0u;
    if (phase != 0u) {
        s->proc.carry_flags |= flags & LEP_SF_GAP;
        return false;
    }
    if (s->opt.duration_s > 0.0 && processed > 0 &&
        t - s->proc.first_delivered_t >= s->opt.duration_s) {
        s->proc.ended = true;
        return false;
    }
    flags |= s->proc.carry_flags;
    s->proc.carry_flags = 0;
    row->t_mono = t;
    row->t_utc = t_utc;
    fill_row(s, smp, y, off, row);
    row->arrived = arrived;
    row->flags = flags | lep_priv_load_limits(s, row->si, t, processed);
    if (processed == 0)
        s->proc.first_delivered_t = t;
    lep_priv_sink_row(&s->sink, row); /* row number `processed` */
    if (s->opt.count > 0 && processed + 1u >= s->opt.count)
        s->proc.ended = true;
    return true;
}
