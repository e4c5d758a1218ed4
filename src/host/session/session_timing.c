/* Host session, timing: the arrival time of each sample of a read, and gaps
 * in the stream: after a reconnect, from the virtual sensor's sequence
 * numbers, and, on a port without them, from arrival times (a suspected hole
 * holds the newest rows back until the next read judges it). */
#include <math.h>

#include "session_priv.h"

void lep_priv_timing_start(session_timing *tm)
{
    tm->utc_off = lep_priv_utc_offset();
    tm->started = false;
    tm->have_seq = false;
    tm->gap_next = false;
}

void lep_priv_timing_lost(lep_session *s)
{
    s->rows.held = 0; /* a suspected hole ends in the loss itself */
    s->tm.started = false;
}

void lep_priv_timing_reconnected(session_timing *tm, double gap_from, int error)
{
    tm->have_seq = false;
    tm->gap_next = true;
    tm->gap_from = gap_from;
    tm->gap_error = error;
    tm->started = false;
}

double lep_priv_timing_stamp(const lep_session *s, size_t i, size_t n, double t_read, double lower)
{
    double t = t_read - (double)(n - 1u - i) * s->period_s;
    return t < lower ? lower : t;
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

uint8_t lep_priv_timing_sample(lep_session *s, const lep_sample *smp, double t)
{
    session_timing *tm = &s->tm;
    uint8_t flags = 0;
    if (tm->gap_next) {
        double est = (t - tm->gap_from) * s->nominal_hz - 1.0;
        gap_event(s, LEP_EV_RECONNECTED, s->hs.processed, tm->gap_from, t,
                  clip_u32(floor(est + 0.5)), tm->gap_error);
        flags = LEP_SF_GAP;
        tm->gap_next = false;
    } else if (s->sim != NULL && tm->have_seq) {
        /* The virtual sensor numbers its samples: every missing number is lost. */
        uint32_t d = (uint16_t)(smp->reserved - tm->last_seq);
        double est = (t - tm->last_sample_t) * s->nominal_hz;
        uint32_t lost;
        if (est > (double)d + 32768.0) /* a hole of 65536 or more */
            d += 65536u * (uint32_t)floor((est - (double)d) / 65536.0 + 0.5);
        lost = d > 0 ? d - 1u : 0u;
        if (lost > 0) {
            gap_event(s, LEP_EV_GAP, s->hs.processed, tm->last_sample_t, t, lost, 0);
            flags = LEP_SF_GAP;
        }
    }
    tm->have_seq = true;
    tm->last_seq = smp->reserved;
    return flags;
}

/* The rows of the read just made (those after rows_before) are held back as
 * a suspected hole: the silence before its first sample. */
static void suspect(lep_session *s, size_t n, double late, double t_read, double before_t,
                    double first_t, size_t rows_before)
{
    session_timing *tm = &s->tm;
    session_rows *rows = &s->rows;
    rows->held = rows->len - rows_before;
    tm->suspect_from = before_t;
    tm->suspect_to = first_t;
    tm->suspect_index = s->hs.processed - rows->held;
    tm->suspect_read_t = t_read;
    tm->suspect_n = n;
    tm->suspect_late = late;
    tm->suspect_silent = tm->empty_t - before_t > s->opt.gap_periods * s->period_s;
}

/* Lateness of the stream after a read: how far the samples received since
 * the anchor fall behind one per nominal period. Transit jitter (USB
 * packets, a sender running late) makes it rise and fall back when the late
 * samples arrive; a hole makes it rise and stay. So a read that leaves the
 * stream late by more than gap_periods is only a suspect: its rows are held
 * back until the next read, which confirms the hole (still late: LEP_EV_GAP,
 * the first held row flagged) or refutes it (caught up: rows released as
 * they are, also when the next read brought more than was due since: the
 * reads lag, the samples were waiting in the kernel). A next read that
 * comes after a silence of its own (the stream later by more than
 * gap_periods than the suspected read left it) confirms the suspected hole
 * at the size it had, and is suspected in turn. A hole hidden in a lag is
 * found once the reads catch up, at the rows of that read. The anchor
 * follows a sensor running fast (lateness below 0) at once, and one running
 * slow by the smallest lateness of each second. */
void lep_priv_timing_read(lep_session *s, size_t n, double t_read, double before_t, double first_t,
                          size_t rows_before)
{
    session_timing *tm = &s->tm;
    session_rows *rows = &s->rows;
    const double thr = s->opt.gap_periods * s->period_s;
    double late;

    if (!tm->started || tm->gap_next) {
        tm->started = true;
        tm->anchor_t = t_read;
        tm->anchor_k = 0;
        tm->k = 0;
        tm->window_t = t_read;
        tm->window_min = INFINITY;
        return;
    }
    tm->k += n;
    late = t_read - (tm->anchor_t + (double)(tm->k - tm->anchor_k) * s->period_s);
    if (late < 0.0) {
        tm->anchor_t = t_read;
        tm->anchor_k = tm->k;
        late = 0.0;
    }
    if (rows->held > 0) {
        /* Still late: a hole, unless the reads lag (a caller busy
         * elsewhere): then this read brought more than was due since the
         * suspected one; the samples were waiting in the kernel, and
         * lateness says nothing about the sensor. How much the suspected
         * read took says little: the tty layer hands a backlog over in
         * pieces of up to 4 KiB, and a read may find a piece half made. But
         * after a silence the session saw (a read found the port empty
         * later than gap_periods after the last sample), a burst may be a
         * sender catching up after a hole: then the suspected read must
         * have taken most of a piece, as a backlog's reads do. */
        double due = (t_read - tm->suspect_read_t) / s->period_s + SESSION_BURST;
        bool lag = (double)n > due && (!tm->suspect_silent || tm->suspect_n >= SESSION_LAG_READ);
        if (late > thr && !lag) {
            double again = late - tm->suspect_late; /* a silence since the suspected read */
            double hole = again > thr ? tm->suspect_late : late;
            /* the held rows are the ones just before this read's */
            lep_priv_rows_back(rows, rows->len - rows_before + rows->held - 1u)->flags |=
                LEP_SF_GAP;
            gap_event(s, LEP_EV_GAP, tm->suspect_index, tm->suspect_from, tm->suspect_to,
                      clip_u32(floor(hole / s->period_s + 0.5)), 0);
            /* the anchor leaves the stream as late as it is beyond the hole */
            late -= hole;
            tm->anchor_t = t_read - late;
            tm->anchor_k = tm->k;
            if (again > thr && rows->len > rows_before) {
                suspect(s, n, late, t_read, before_t, first_t, rows_before);
                return;
            }
        }
        rows->held = 0;
    } else if (late > thr && rows->len > rows_before) {
        suspect(s, n, late, t_read, before_t, first_t, rows_before);
        return;
    }
    if (late < tm->window_min)
        tm->window_min = late;
    if (t_read - tm->window_t >= 1.0) {
        if (tm->window_min > 0.0 && tm->window_min < thr)
            tm->anchor_t += tm->window_min;
        tm->window_t = t_read;
        tm->window_min = INFINITY;
    }
}
