/* Host session, timing (session_timing.h): the session's side of stamps and
 * gaps. The model of the sensor's clock, the stamps and the gaps from
 * arrival times are the timeline's (session_timeline.c); here its verdicts
 * are applied to the rows held back in the sink, and the gaps it cannot see
 * are found: after a reconnect, and from the virtual sensor's sequence
 * numbers. */
#include <math.h>

#include "session_clock.h"
#include "session_timing.h"

void lep_priv_timing_start(session_timing *tm, double nominal_hz, double gap_periods, bool numbered)
{
    tm->utc_off = lep_priv_utc_offset();
    tm->hz = nominal_hz;
    tm->numbered = numbered;
    tm->have_seq = false;
    tm->gap_next = false;
    lep_priv_timeline_init(&tm->tl, 1.0 / nominal_hz, gap_periods, !numbered);
}

void lep_priv_timing_tap(session_timing *tm, const timeline_tap *tap)
{
    tm->tl.tap = tap;
}

void lep_priv_timing_resume(session_timing *tm, double now)
{
    if (tm->last_sample_t > now)
        tm->last_sample_t = now;
}

void lep_priv_timing_lost(session_timing *tm, session_sink *sk)
{
    lep_priv_sink_release(sk); /* a suspected hole ends in the loss itself */
    lep_priv_timeline_restart(&tm->tl);
}

void lep_priv_timing_reconnected(session_timing *tm, int error)
{
    tm->have_seq = false;
    tm->gap_next = true;
    tm->gap_from = tm->last_sample_t;
    tm->gap_error = error;
    lep_priv_timeline_restart(&tm->tl);
}

void lep_priv_timing_empty(session_timing *tm, double t)
{
    lep_priv_timeline_empty(&tm->tl, t);
}

double lep_priv_timing_utc(session_timing *tm, double t_read)
{
    if (lep_priv_utc_may_have_moved(tm->utc_off, t_read)) {
        double width, fresh = lep_priv_utc_offset_within(&width);
        /* the wall clock was set (NTP step, by hand): its whole bracket left
         * the band (a measurement skewed by a lost CPU moves nothing) */
        if (fabs(fresh - tm->utc_off) - width / 2.0 > SESSION_UTC_STEP_S)
            tm->utc_off = fresh;
    }
    return tm->utc_off;
}

double lep_priv_timing_utc_offset(const session_timing *tm)
{
    return tm->utc_off;
}

double lep_priv_timing_last(const session_timing *tm)
{
    return tm->last_sample_t;
}

static uint32_t clip_u32(double v)
{
    if (!(v > 0.0))
        return 0;
    return v >= 4294967295.0 ? 4294967295u : (uint32_t)v;
}

/* [mu] held */
static void gap_event(session_sink *sk, int type, uint64_t sample, double from, double to,
                      uint32_t lost, int error)
{
    lep_session_event ev;
    lep_priv_event_init(&ev, type, sample, to);
    ev.gap_from = from;
    ev.gap_to = to;
    ev.lost = lost;
    ev.error = error;
    lep_priv_sink_event(sk, &ev); /* counts the gap */
}

/* Samples known to be missing before each of got[0..n) (the virtual
 * sensor's sequence numbers, when numbered) into lost[]; their sum. */
static uint64_t seq_lost(session_timing *tm, const lep_sample *got, size_t n, double t_read,
                         uint32_t *lost)
{
    uint64_t total = 0;
    size_t i;
    for (i = 0; i < n; i++) {
        lost[i] = 0;
        if (tm->numbered && tm->have_seq) {
            /* The virtual sensor numbers its samples: every missing number is lost. */
            uint32_t d = (uint16_t)(got[i].reserved - tm->last_seq);
            double est = i == 0 ? (t_read - tm->last_sample_t) * tm->hz : 0.0;
            if (est > (double)d + 32768.0) /* a hole of 65536 or more */
                d += 65536u * (uint32_t)floor((est - (double)d) / 65536.0 + 0.5);
            lost[i] = d > 0 ? d - 1u : 0u;
        }
        if (tm->numbered) {
            tm->have_seq = true;
            tm->last_seq = got[i].reserved;
        }
        total += lost[i];
    }
    return total;
}

/* The timeline's verdict on a read into v; the rows held back at the
 * previous read judged (true: a gap before them, queued in sk). */
static bool judge(session_timing *tm, session_sink *sk, const lep_sample *got, size_t n,
                  double t_read, uint32_t *lost, timeline_verdict *v)
{
    uint64_t known = seq_lost(tm, got, n, t_read, lost);
    lep_priv_timeline_read(&tm->tl, t_read, n, known, v);
    if (!v->release || !lep_priv_sink_judged(sk, v->gap, v->shift))
        return false;
    gap_event(sk, LEP_EV_GAP, tm->suspect_index, v->from, v->to, v->lost, 0);
    return true;
}

/* Sample j of the read (lost ones counted), after `lost` missing ones: its
 * stamp into *t; a gap before it (a reconnect, or lost > 0) queued in sk
 * and LEP_SF_GAP returned, else 0. */
static uint8_t stamp_sample(session_timing *tm, session_sink *sk, uint64_t j, uint32_t lost,
                            double *t)
{
    double stamp = lep_priv_timeline_stamp(&tm->tl, j);
    uint8_t flags = 0;
    if (tm->gap_next) {
        double est = (stamp - tm->gap_from) * tm->hz - 1.0;
        gap_event(sk, LEP_EV_RECONNECTED, lep_priv_sink_processed(sk), tm->gap_from, stamp,
                  clip_u32(floor(est + 0.5)), tm->gap_error);
        tm->gap_next = false;
        flags = LEP_SF_GAP;
    } else if (lost > 0) {
        gap_event(sk, LEP_EV_GAP, lep_priv_sink_processed(sk), tm->last_sample_t, stamp, lost, 0);
        flags = LEP_SF_GAP;
    }
    tm->last_sample_t = stamp;
    *t = stamp;
    return flags;
}

/* After the read's rows were kept (the sink had `before` pending before
 * them): hold them back as the verdict says. */
static void hold(session_timing *tm, session_sink *sk, const timeline_verdict *v, size_t before)
{
    size_t n;
    if (v->extend) {
        (void)lep_priv_sink_hold_since(sk, before, true); /* too soon to judge */
    } else if (v->hold) {
        n = lep_priv_sink_hold_since(sk, before, false);
        if (n > 0)
            tm->suspect_index = lep_priv_sink_processed(sk) - n;
        else
            lep_priv_timeline_forget_held(&tm->tl); /* nothing kept to hold */
    }
}

void lep_priv_timing_feed(session_timing *tm, session_chain *ch, session_sink *sk,
                          const lep_sample *got, size_t n, double t_read)
{
    uint32_t lost[SESSION_PENDING];
    timeline_verdict v;
    uint64_t j = 0;
    size_t i, before;
    if (n > SESSION_PENDING)
        n = SESSION_PENDING;
    if (judge(tm, sk, got, n, t_read, lost, &v))
        lep_priv_chain_hole(ch);
    before = lep_priv_sink_pending(sk);
    for (i = 0; i < n; i++) {
        double t;
        uint8_t flags;
        j += lost[i];
        flags = stamp_sample(tm, sk, j++, lost[i], &t);
        if (flags & LEP_SF_GAP)
            lep_priv_chain_hole(ch);
        if (lep_priv_sink_received(sk, t))
            lep_priv_chain_sample(ch, sk, &got[i], t, t + tm->utc_off, t_read, flags);
    }
    hold(tm, sk, &v, before);
}

bool lep_priv_timing_end(session_timing *tm, session_sink *sk)
{
    if (!lep_priv_sink_end(sk))
        return false;
    lep_priv_timeline_forget_held(&tm->tl);
    return true;
}
