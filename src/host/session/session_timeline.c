/* The session's timeline: the sensor's clock from read arrivals, stamps and
 * gaps on it (contract in session_timeline.h). No clock, no I/O, no malloc. */
#include "session_timeline.h"

#include <math.h>
#include <string.h>

#define NONE (-1e300)

/* Tell the recorder, if any. */
static void tap(const session_timeline *tl, char what, double t, size_t n, uint64_t lost)
{
    timeline_fed f;
    memset(&f, 0, sizeof f);
    f.what = what;
    f.t = t;
    f.n = n;
    f.lost = lost;
    f.nominal = tl->nominal;
    f.gap_periods = tl->nominal > 0.0 ? tl->thr / tl->nominal : 0.0;
    f.arrival_gaps = tl->arrival_gaps;
    tl->tap->fed(tl->tap->user, &f);
}

void lep_priv_timeline_init(session_timeline *tl, double nominal_period_s, double gap_periods,
                            bool arrival_gaps)
{
    const timeline_tap *keep = tl->tap;
    memset(tl, 0, sizeof *tl);
    tl->tap = keep;
    tl->nominal = nominal_period_s;
    tl->thr = gap_periods * nominal_period_s;
    tl->arrival_gaps = arrival_gaps;
    tl->prior = nominal_period_s;
    tl->period = nominal_period_s;
    tl->last = NONE;
    tl->floor = NONE;
    tl->empty_t = NONE;
    if (tl->tap != NULL)
        tap(tl, 'i', 0.0, 0, 0);
}

void lep_priv_timeline_restart(session_timeline *tl)
{
    if (tl->tap != NULL)
        tap(tl, 's', 0.0, 0, 0);
    tl->started = false;
    tl->held = false;
}

void lep_priv_timeline_empty(session_timeline *tl, double t)
{
    if (tl->tap != NULL)
        tap(tl, 'e', t, 0, 0);
    tl->empty_t = t;
}

bool lep_priv_timeline_holding(const session_timeline *tl)
{
    return tl->held;
}

void lep_priv_timeline_forget_held(session_timeline *tl)
{
    tl->held = false;
}

double lep_priv_timeline_last(const session_timeline *tl)
{
    return tl->last;
}

static const timeline_point *point(const session_timeline *tl, size_t i)
{
    return &tl->pts[(tl->head + i) % TIMELINE_BLOCKS];
}

/* The earliest point of each block, over the last TIMELINE_BLOCKS blocks
 * (earliest against the nominal period). */
static void add_point(session_timeline *tl, double k, double t)
{
    timeline_point p;
    p.k = k;
    p.t = t;
    p.block = (int64_t)floor((t - tl->t0) / TIMELINE_BLOCK_S);
    if (tl->len > 0) {
        timeline_point *newest = &tl->pts[(tl->head + tl->len - 1u) % TIMELINE_BLOCKS];
        if (newest->block >= p.block) {
            if (t - tl->nominal * k < newest->t - tl->nominal * newest->k)
                *newest = p;
            return;
        }
    }
    if (tl->len == TIMELINE_BLOCKS) {
        tl->head = (tl->head + 1u) % TIMELINE_BLOCKS;
        tl->len--;
    }
    tl->pts[(tl->head + tl->len) % TIMELINE_BLOCKS] = p;
    tl->len++;
    while (tl->len > 1 && point(tl, 0)->block <= p.block - TIMELINE_BLOCKS) {
        tl->head = (tl->head + 1u) % TIMELINE_BLOCKS;
        tl->len--;
    }
}

/* The slope: of the lower hull between its vertices nearest a quarter and
 * three quarters of the window, in coordinates relative to the oldest point,
 * time less the nominal period. */
static double hull_slope(const session_timeline *tl)
{
    double x[TIMELINE_BLOCKS], y[TIMELINE_BLOCKS], q1, q3, slope;
    size_t h[TIMELINE_BLOCKS], m = 0, i, a = 0, b = 0;
    const timeline_point *p0 = point(tl, 0), *pn = point(tl, tl->len - 1u);
    if (tl->len < 2 || pn->t - p0->t < TIMELINE_MIN_SPAN_S)
        return tl->prior;
    for (i = 0; i < tl->len; i++) {
        const timeline_point *p = point(tl, i);
        x[i] = p->k - p0->k;
        y[i] = (p->t - p0->t) - tl->nominal * x[i];
        while (m >= 2) {
            size_t u = h[m - 2], w = h[m - 1];
            double cross = (x[w] - x[u]) * (y[i] - y[u]) - (y[w] - y[u]) * (x[i] - x[u]);
            if (cross > 0.0)
                break;
            m--;
        }
        h[m++] = i;
    }
    /* the vertices nearest a quarter and three quarters of the window: far
     * apart, so their delays above the line hardly tilt the slope (an edge's
     * two ends may be close together) */
    q1 = x[tl->len - 1u] / 4.0;
    q3 = 3.0 * q1;
    for (i = 0; i < m; i++) {
        if (fabs(x[h[i]] - q1) < fabs(x[h[a]] - q1))
            a = i;
        if (fabs(x[h[i]] - q3) < fabs(x[h[b]] - q3))
            b = i;
    }
    if (a == b) {
        a = 0;
        b = m - 1u;
    }
    if (!(x[h[b]] > x[h[a]]))
        return tl->prior;
    slope = tl->nominal + (y[h[b]] - y[h[a]]) / (x[h[b]] - x[h[a]]);
    if (fabs(slope / tl->nominal - 1.0) > TIMELINE_MAX_PPM * 1e-6)
        slope = tl->nominal * (1.0 + (slope > tl->nominal ? 1.0 : -1.0) * TIMELINE_MAX_PPM * 1e-6);
    return slope;
}

/* The line: the slope, and the offset that puts no point below it (the
 * newest, which may not be its block's earliest, included). */
static void fit(session_timeline *tl, double k_new, double t_new)
{
    size_t i;
    double off;
    tl->period = hull_slope(tl);
    off = t_new - tl->period * k_new;
    for (i = 0; i < tl->len; i++) {
        const timeline_point *p = point(tl, i);
        double o = p->t - tl->period * p->k;
        if (o < off)
            off = o;
    }
    tl->offset = off;
    if (tl->len >= 2 && point(tl, tl->len - 1u)->t - point(tl, 0)->t >= TIMELINE_MIN_SPAN_S)
        tl->prior = tl->period; /* learned: kept across a restart */
}

static double line(const session_timeline *tl, double k)
{
    return tl->offset + tl->period * k;
}

double lep_priv_timeline_stamp(const session_timeline *tl, uint64_t j)
{
    double t = line(tl, (double)(tl->read_k0 + j));
    if (t < tl->floor)
        t = tl->floor;
    if (t > tl->read_t)
        t = tl->read_t;
    return t;
}

static void suspect(session_timeline *tl, size_t n, uint64_t lost, double late, timeline_verdict *v)
{
    tl->held = true;
    tl->susp_k = tl->read_k0;
    tl->susp_n = n;
    tl->susp_t = tl->read_t;
    tl->susp_late = late;
    tl->susp_from = tl->floor;
    tl->susp_first = lep_priv_timeline_stamp(tl, 0);
    tl->susp_last = lep_priv_timeline_stamp(tl, n - 1u + lost);
    tl->susp_last_t = tl->read_t;
    tl->susp_held = n;
    tl->susp_reads = 0;
    tl->susp_min_late = late;
    tl->susp_silent = tl->empty_t - tl->floor > tl->thr;
    v->hold = true;
}

/* The held rows follow a hole of `lost`: the count moves on. */
static void confirm(session_timeline *tl, uint32_t lost, double k_new, double t_new,
                    timeline_verdict *v)
{
    double shift = (double)lost * tl->period, held_last;
    v->gap = true;
    v->lost = lost;
    v->shift = shift;
    v->from = tl->susp_from;
    v->to = tl->susp_first + shift < tl->susp_t ? tl->susp_first + shift : tl->susp_t;
    tl->k += lost;
    tl->read_k0 += lost;
    /* The window starts over after the hole, at the period learned: a hole
     * judged wrongly (its size, or a false one) would otherwise bend the
     * hull for the whole window and put the stamps off; starting over, the
     * count is only a label and the stamps stay on the arrivals. */
    tl->head = tl->len = 0;
    add_point(tl, k_new + (double)lost, t_new);
    held_last = tl->susp_last + shift < tl->susp_last_t ? tl->susp_last + shift : tl->susp_last_t;
    if (held_last > tl->floor)
        tl->floor = held_last;
    fit(tl, k_new + (double)lost, t_new);
}

void lep_priv_timeline_read(session_timeline *tl, double t, size_t n, uint64_t lost,
                            timeline_verdict *v)
{
    double k_new, late;
    memset(v, 0, sizeof *v);
    if (n == 0)
        return;
    if (tl->tap != NULL)
        tap(tl, 'r', t, n, lost);
    if (!tl->started) {
        tl->started = true;
        tl->t0 = t;
        tl->k = 0;
        tl->head = tl->len = 0;
        tl->period = tl->prior;
        tl->last = NONE;
        tl->held = false;
    }
    tl->floor = tl->last;
    tl->read_k0 = tl->k;
    tl->k += n + lost;
    tl->read_t = t;
    k_new = (double)(tl->k - 1u);
    add_point(tl, k_new, t);
    fit(tl, k_new, t);
    late = t - line(tl, k_new);
    if (tl->arrival_gaps && tl->held) {
        /* A catching-up read (the samples were waiting: a caller away, a
         * sender running late) says nothing about the sensor. */
        double due = (t - tl->susp_t) / tl->nominal + TIMELINE_BURST;
        bool lag = (double)n > due && (!tl->susp_silent || tl->susp_n >= TIMELINE_LAG_READ);
        if (late > tl->thr && !lag && late - tl->susp_late <= tl->thr &&
            (t - tl->susp_t < TIMELINE_JUDGE_S || tl->susp_reads < TIMELINE_JUDGE_READS) &&
            tl->susp_held + n <= TIMELINE_HOLD_MAX) {
            /* too soon to judge: these rows join the held ones */
            tl->susp_last = lep_priv_timeline_stamp(tl, n - 1u + lost);
            tl->susp_last_t = t;
            tl->susp_held += n;
            tl->susp_reads++;
            if (late < tl->susp_min_late)
                tl->susp_min_late = late;
            tl->last = tl->susp_last;
            v->hold = true;
            v->extend = true;
            return;
        }
        tl->held = false;
        v->release = true;
        /* the least lateness since the suspected read: a read held up on
         * the way (a reader descheduled) is late once, a hole every time */
        if (late - tl->susp_late <= tl->thr && tl->susp_min_late < late)
            late = tl->susp_min_late;
        if (late > tl->thr && !lag && late - tl->susp_late > tl->thr) {
            /* Later again: a silence since the suspected read. Its lateness
             * may have been a silence at its end rather than a hole before
             * it (a budgeted read some time after a stall began): the held
             * rows go as they are and this read is suspected with the whole
             * lateness (two holes so close are reported as one, here). */
            suspect(tl, n, lost, late, v);
        } else if (late > tl->thr && !lag) {
            double periods = floor(late / tl->nominal + 0.5);
            confirm(tl, periods >= 4294967295.0 ? 4294967295u : (uint32_t)periods, k_new, t, v);
        }
    } else if (tl->arrival_gaps && late > tl->thr) {
        suspect(tl, n, lost, late, v);
    }
    tl->last = lep_priv_timeline_stamp(tl, n - 1u + lost);
}
