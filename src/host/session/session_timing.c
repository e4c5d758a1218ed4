/* Host session, timing: the session's side of stamps and gaps. The model of
 * the sensor's clock, the stamps and the gaps from arrival times are the
 * timeline's (session_timeline.c); here its verdicts are applied to the rows
 * and events, and the gaps it cannot see are found: after a reconnect, and
 * from the virtual sensor's sequence numbers. */
#include <math.h>

#include "session_priv.h"
#include "session_tap.h"

void lep_priv_timing_start(session_timing *tm, double period_s, double gap_periods,
                           bool arrival_gaps)
{
    tm->utc_off = lep_priv_utc_offset();
    tm->have_seq = false;
    tm->gap_next = false;
    lep_priv_timeline_init(&tm->tl, period_s, gap_periods, arrival_gaps);
}

void lep_priv_session_tap_timeline(lep_session *s, const timeline_tap *tap)
{
    s->tm.tl.tap = tap;
}

void lep_priv_timing_lost(lep_session *s)
{
    s->rows.held = 0; /* a suspected hole ends in the loss itself */
    lep_priv_timeline_restart(&s->tm.tl);
}

void lep_priv_timing_reconnected(session_timing *tm, double gap_from, int error)
{
    tm->have_seq = false;
    tm->gap_next = true;
    tm->gap_from = gap_from;
    tm->gap_error = error;
    lep_priv_timeline_restart(&tm->tl);
}

static uint32_t clip_u32(double v)
{
    if (!(v > 0.0))
        return 0;
    return v >= 4294967295.0 ? 4294967295u : (uint32_t)v;
}

/* [mu] held */
static void gap_event(lep_session *s, int type, uint64_t sample, double from, double to,
                      uint32_t lost, int error)
{
    lep_session_event ev;
    lep_priv_event_init(&ev, type, sample, to);
    ev.gap_from = from;
    ev.gap_to = to;
    ev.lost = lost;
    ev.error = error;
    lep_priv_events_push(&s->events, &ev);
    s->proc.lp.settle = s->proc.lp.settle_n; /* the filter's output after a hole is a transient */
    lep_priv_health_gap(&s->hs, from, to, lost);
}

uint64_t lep_priv_timing_seq(session_timing *tm, bool numbered, const lep_sample *got, size_t n,
                             double t_read, double hz, uint32_t *lost)
{
    uint64_t total = 0;
    size_t i;
    for (i = 0; i < n; i++) {
        lost[i] = 0;
        if (numbered && tm->have_seq) {
            /* The virtual sensor numbers its samples: every missing number is lost. */
            uint32_t d = (uint16_t)(got[i].reserved - tm->last_seq);
            double est = i == 0 ? (t_read - tm->last_sample_t) * hz : 0.0;
            if (est > (double)d + 32768.0) /* a hole of 65536 or more */
                d += 65536u * (uint32_t)floor((est - (double)d) / 65536.0 + 0.5);
            lost[i] = d > 0 ? d - 1u : 0u;
        }
        if (numbered) {
            tm->have_seq = true;
            tm->last_seq = got[i].reserved;
        }
        total += lost[i];
    }
    return total;
}

void lep_priv_timing_judged(lep_session *s, const timeline_verdict *v)
{
    session_rows *rows = &s->rows;
    size_t b;
    if (!v->release)
        return;
    if (v->gap && rows->held > 0) {
        for (b = 0; b < rows->held; b++) {
            session_row *r = lep_priv_rows_back(rows, b);
            double t = r->t_mono + v->shift < r->arrived ? r->t_mono + v->shift : r->arrived;
            r->t_utc += t - r->t_mono;
            r->t_mono = t;
        }
        lep_priv_rows_back(rows, rows->held - 1u)->flags |= LEP_SF_GAP;
        gap_event(s, LEP_EV_GAP, s->tm.suspect_index, v->from, v->to, v->lost, 0);
    }
    rows->held = 0;
}

uint8_t lep_priv_timing_sample(lep_session *s, uint32_t lost, double t)
{
    session_timing *tm = &s->tm;
    if (tm->gap_next) {
        double est = (t - tm->gap_from) * s->nominal_hz - 1.0;
        gap_event(s, LEP_EV_RECONNECTED, s->hs.processed, tm->gap_from, t,
                  clip_u32(floor(est + 0.5)), tm->gap_error);
        tm->gap_next = false;
        return LEP_SF_GAP;
    }
    if (lost > 0) {
        gap_event(s, LEP_EV_GAP, s->hs.processed, tm->last_sample_t, t, lost, 0);
        return LEP_SF_GAP;
    }
    return 0;
}
