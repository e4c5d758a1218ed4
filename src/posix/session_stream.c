/* Host session, the stream: reading the port into a session-owned buffer,
 * stepping the client over it, arrival times, gaps, data timeouts,
 * reconnection, health and the event queue. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <errno.h>
#include <math.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "leptrino/error.h"
#include "posix_clock.h"
#include "session_priv.h"

/* ---- clocks ---- */

double lep_priv_utc_offset(void)
{
    /* The wall clock read between two monotonic reads; of three tries, the
     * one with the narrowest bracket wins, so a thread descheduled between
     * the reads (which skews one try by the time it lost) does not move the
     * offset: UTC intervals then equal monotonic ones to well under 1 ms. */
    double best = 0.0, best_width = -1.0;
    int i;
    for (i = 0; i < 3; ++i) {
        struct timespec a, r, b;
        double ma, mb, rt;
        (void)clock_gettime(CLOCK_MONOTONIC, &a);
        (void)clock_gettime(CLOCK_REALTIME, &r);
        (void)clock_gettime(CLOCK_MONOTONIC, &b);
        ma = (double)a.tv_sec + (double)a.tv_nsec / 1e9;
        mb = (double)b.tv_sec + (double)b.tv_nsec / 1e9;
        rt = (double)r.tv_sec + (double)r.tv_nsec / 1e9;
        if (best_width < 0.0 || mb - ma < best_width) {
            best_width = mb - ma;
            best = rt - (ma + mb) / 2.0;
        }
    }
    return best;
}

/* Whether the wall clock may have moved by more than SESSION_UTC_STEP_S
 * from utc_off, judged from one CLOCK_REALTIME read: it happened at a
 * monotonic instant between t_before (a monotonic time taken earlier) and a
 * monotonic read just after it, so the true offset lies in that bracket.
 * Two clock reads instead of lep_priv_utc_offset's nine; only when the
 * bracket leaves utc_off +- SESSION_UTC_STEP_S (a step, or this thread lost
 * the CPU in between) does the caller measure the offset properly. */
static bool utc_may_have_moved(double utc_off, double t_before)
{
    struct timespec r, b;
    double rt, lo, hi;
    (void)clock_gettime(CLOCK_REALTIME, &r);
    (void)clock_gettime(CLOCK_MONOTONIC, &b);
    rt = (double)r.tv_sec + (double)r.tv_nsec / 1e9;
    lo = rt - ((double)b.tv_sec + (double)b.tv_nsec / 1e9);
    hi = rt - t_before;
    return lo < utc_off - SESSION_UTC_STEP_S || hi > utc_off + SESSION_UTC_STEP_S;
}

/* Milliseconds from now until t, rounded up, clipped to int; -1 for infinity. */
static int ms_until(double t, double now)
{
    double ms;
    if (isinf(t))
        return -1;
    ms = ceil((t - now) * 1000.0);
    if (ms <= 0.0)
        return 0;
    return ms > 2147483647.0 ? 2147483647 : (int)ms;
}

/* ---- events ---- */

void lep_priv_session_event_init(lep_session_event *ev, int type, uint64_t sample, double t_mono)
{
    memset(ev, 0, sizeof *ev);
    ev->type = type;
    ev->sample = sample;
    ev->t_mono = t_mono;
    ev->t_utc = t_mono + lep_priv_utc_offset();
}

void lep_priv_session_push_event(lep_session *s, const lep_session_event *ev)
{
    if (s->ev_len == SESSION_EVENTS) { /* full: the oldest goes */
        s->ev_head = (s->ev_head + 1u) % SESSION_EVENTS;
        s->ev_len--;
    }
    s->ev[(s->ev_head + s->ev_len) % SESSION_EVENTS] = *ev;
    s->ev_len++;
    s->ev_pushed++;
}

bool lep_session_next_event(lep_session *s, lep_session_event *ev)
{
    bool got = false;
    if (s == NULL || ev == NULL)
        return false;
    pthread_mutex_lock(&s->mu);
    if (s->ev_len > 0) {
        *ev = s->ev[s->ev_head];
        s->ev_head = (s->ev_head + 1u) % SESSION_EVENTS;
        s->ev_len--;
        got = true;
    }
    pthread_mutex_unlock(&s->mu);
    return got;
}

static uint64_t events_pushed(lep_session *s)
{
    uint64_t n;
    pthread_mutex_lock(&s->mu);
    n = s->ev_pushed;
    pthread_mutex_unlock(&s->mu);
    return n;
}

/* ---- health ---- */

static uint64_t conn_errors(const lep_client_stats *now, const lep_client_stats *base)
{
    return (uint64_t)(uint32_t)(now->bcc_errors - base->bcc_errors) +
           (uint32_t)(now->frame_errors - base->frame_errors) +
           (uint32_t)(now->invalid - base->invalid);
}

/* [mu] held */
static void health_sample(lep_session *s, double t)
{
    lep_session_health *h = &s->h;
    h->received++;
    if (h->received == 1) {
        s->first_t = t;
        s->window_t = t;
        s->window_n = 1;
    }
    h->elapsed_s = t - s->first_t;
    if (h->elapsed_s > 0.0)
        h->measured_hz = (double)(h->received - 1u) / h->elapsed_s;
    if (t - s->window_t >= 1.0) {
        h->recent_hz = (double)(h->received - s->window_n) / (t - s->window_t);
        s->window_t = t;
        s->window_n = h->received;
    } else if (s->window_n == 1u) {
        h->recent_hz = h->measured_hz; /* the first second: the run so far, not 0 */
    }
    h->shortfall = h->elapsed_s >= 1.0 && h->measured_hz < 0.98 * h->nominal_hz;
}

/* [mu] held */
static void gap_event(lep_session *s, int type, uint64_t sample, double from, double to,
                      uint32_t lost, int error)
{
    lep_session_event ev;
    lep_priv_session_event_init(&ev, type, sample, to);
    ev.gap_from = from;
    ev.gap_to = to;
    ev.lost = lost;
    ev.error = error;
    lep_priv_session_push_event(s, &ev);
    s->lp.settle = s->lp.settle_n; /* the filter's output after a hole is a transient */
    s->h.gaps++;
    s->h.lost += lost;
    if (to - from > s->h.max_gap_s)
        s->h.max_gap_s = to - from;
}

static uint32_t clip_u32(double v)
{
    if (!(v > 0.0))
        return 0;
    return v >= 4294967295.0 ? 4294967295u : (uint32_t)v;
}

/* ---- holes on a sensor without sequence numbers ---- */

/* Lateness of the stream after a read: how far the samples received since
 * the anchor fall behind one per nominal period. Transit jitter (USB
 * packets, a sender running late) makes it rise and fall back when the late
 * samples arrive; a hole makes it rise and stay. So a read that leaves the
 * stream late by more than gap_periods is only a suspect: its rows are held
 * back until the next read, which confirms the hole (still late: LEP_EV_GAP,
 * the first held row flagged) or refutes it (caught up: rows released as
 * they are). The anchor follows a sensor running fast (lateness below 0) at
 * once, and one running slow by the smallest lateness of each second.
 * [mu] held. */
static void time_gaps(lep_session *s, size_t n, double t_read, double before_t, double first_t,
                      size_t rows_before)
{
    const double thr = s->opt.gap_periods * s->period_s;
    double late;

    if (!s->tm_started || s->gap_next) {
        s->tm_started = true;
        s->tm_anchor_t = t_read;
        s->tm_anchor_k = 0;
        s->tm_k = 0;
        s->tm_window_t = t_read;
        s->tm_window_min = INFINITY;
        return;
    }
    s->tm_k += n;
    late = t_read - (s->tm_anchor_t + (double)(s->tm_k - s->tm_anchor_k) * s->period_s);
    if (late < 0.0) {
        s->tm_anchor_t = t_read;
        s->tm_anchor_k = s->tm_k;
        late = 0.0;
    }
    if (s->held > 0) {
        if (late > thr) {
            /* the held rows are the ones just before this read's */
            size_t first = (s->pend_head + rows_before - s->held) % SESSION_PENDING;
            s->pending[first].flags |= LEP_SF_GAP;
            gap_event(s, LEP_EV_GAP, s->suspect_index, s->suspect_from, s->suspect_to,
                      clip_u32(floor(late / s->period_s + 0.5)), 0);
            s->tm_anchor_t = t_read;
            s->tm_anchor_k = s->tm_k;
            late = 0.0;
        }
        s->held = 0;
    } else if (late > thr && s->pend_len > rows_before) {
        s->held = s->pend_len - rows_before;
        s->suspect_from = before_t;
        s->suspect_to = first_t;
        s->suspect_index = s->h.delivered - s->held;
        return;
    }
    if (late < s->tm_window_min)
        s->tm_window_min = late;
    if (t_read - s->tm_window_t >= 1.0) {
        if (s->tm_window_min > 0.0 && s->tm_window_min < thr)
            s->tm_anchor_t += s->tm_window_min;
        s->tm_window_t = t_read;
        s->tm_window_min = INFINITY;
    }
}

/* ---- feeding ---- */

void lep_priv_session_feed(lep_session *s, const uint8_t *data, size_t len, double t_read)
{
    lep_sample got[SESSION_PENDING];
    lep_client_stats st;
    size_t n = 0, off = 0, i;
    double lower, t_utc_off, first_t = 0.0, before_t;
    size_t rows_before;

    while (off < len) {
        size_t used = 0;
        int rc = lep_client_step(&s->client, data + off, len - off, &used);
        off += used;
        if (rc == LEP_STEP_SAMPLE && n < SESSION_PENDING &&
            lep_client_get_sample(&s->client, &got[n]) == LEP_OK)
            ++n;
        if (used == 0)
            break;
    }
    lep_client_get_stats(&s->client, &st);
    if (n > 0 && utc_may_have_moved(s->utc_off, t_read)) {
        double fresh = lep_priv_utc_offset();
        if (fabs(fresh - s->utc_off) > SESSION_UTC_STEP_S)
            s->utc_off = fresh; /* the wall clock was set (NTP step, by hand) */
    }
    t_utc_off = s->utc_off;

    pthread_mutex_lock(&s->mu);
    s->h.client = st;
    s->h.errors = s->errors_before + conn_errors(&st, &s->base_stats) + s->data_timeouts;
    lower = s->last_read_t > s->last_sample_t ? s->last_read_t : s->last_sample_t;
    before_t = s->last_sample_t;
    rows_before = s->pend_len;
    for (i = 0; i < n; i++) {
        const lep_sample *smp = &got[i];
        double t = t_read - (double)(n - 1u - i) * s->period_s;
        uint8_t flags = 0;
        session_row *row;

        if (t < lower)
            t = lower;
        if (s->gap_next) {
            double est = (t - s->gap_from) * s->nominal_hz - 1.0;
            gap_event(s, LEP_EV_RECONNECTED, s->h.delivered, s->gap_from, t,
                      clip_u32(floor(est + 0.5)), s->gap_error);
            flags |= LEP_SF_GAP;
            s->gap_next = false;
        } else if (s->sim != NULL && s->have_seq) {
            /* The virtual sensor numbers its samples: every missing number is lost. */
            uint32_t d = (uint16_t)(smp->reserved - s->last_seq);
            double est = (t - s->last_sample_t) * s->nominal_hz;
            uint32_t lost;
            if (est > (double)d + 32768.0) /* a hole of 65536 or more */
                d += 65536u * (uint32_t)floor((est - (double)d) / 65536.0 + 0.5);
            lost = d > 0 ? d - 1u : 0u;
            if (lost > 0) {
                gap_event(s, LEP_EV_GAP, s->h.delivered, s->last_sample_t, t, lost, 0);
                flags |= LEP_SF_GAP;
            }
        }
        if (i == 0)
            first_t = t;
        s->have_seq = true;
        s->last_seq = smp->reserved;
        health_sample(s, t);
        row = &s->pending[(s->pend_head + s->pend_len) % SESSION_PENDING];
        if (s->pend_len < SESSION_PENDING &&
            lep_priv_session_process(s, smp, t, t + t_utc_off, flags, row))
            s->pend_len++;
        s->last_sample_t = t;
        s->have_sample = true;
        lower = t;
    }
    if (n > 0 && s->sim == NULL)
        time_gaps(s, n, t_read, before_t, first_t, rows_before);
    if (n > 0)
        s->last_data_read_t = t_read;
    s->last_read_t = t_read;
    pthread_mutex_unlock(&s->mu);
}

void lep_priv_session_stream_reset(lep_session *s, double now)
{
    uint8_t left[LEP_CLIENT_RX_SIZE];
    lep_client_rx *rx = s->client.rx; /* the serial port's, attached by lep_serial_client_init */
    size_t n = 0;
    s->last_read_t = now;
    s->last_data_read_t = now;
    if (s->last_sample_t > now)
        s->last_sample_t = now;
    /* Bytes the client read past the start command's answer are stream data. */
    if (rx != NULL && rx->pos < rx->len) {
        n = (size_t)(rx->len - rx->pos);
        memcpy(left, rx->buf + rx->pos, n);
        rx->pos = rx->len;
    }
    if (n > 0)
        lep_priv_session_feed(s, left, n, now);
}

/* ---- loss and reconnection ---- */

/* The stream is lost (port gone, or no data for data_timeout_ms). */
static void stream_lost(lep_session *s, int error, double now)
{
    lep_session_event ev;
    lep_client_stats st;
    lep_client_get_stats(&s->client, &st);
    pthread_mutex_lock(&s->mu);
    lep_priv_session_event_init(&ev, LEP_EV_DISCONNECTED, s->h.delivered, now);
    ev.error = error;
    ev.gap_from = s->last_sample_t;
    lep_priv_session_push_event(s, &ev);
    s->h.disconnects++;
    s->held = 0; /* a suspected hole ends in the loss itself */
    s->tm_started = false;
    if (error == LEP_E_TIMEOUT)
        s->data_timeouts++;
    s->errors_before += conn_errors(&st, &s->base_stats);
    s->base_stats = st;
    s->h.errors = s->errors_before + s->data_timeouts;
    pthread_mutex_unlock(&s->mu);
    if (!s->opt.reconnect) {
        s->failed = error;
        return;
    }
    lep_priv_session_disconnect(s);
    s->down_since = now;
    s->port_missing = access(s->opt.port, F_OK) != 0;
    s->backoff_ms = s->opt.reconnect_min_ms;
    s->next_attempt = now + (double)s->backoff_ms / 1000.0;
    s->gap_from = s->last_sample_t;
    s->gap_error = error;
}

/* The sensor that answered a reconnect is the one the session opened. */
static bool same_sensor(lep_session *s)
{
    bool same;
    pthread_mutex_lock(&s->mu);
    same = strcmp(s->info.model, s->first_info.model) == 0 &&
           strcmp(s->info.serial, s->first_info.serial) == 0;
    pthread_mutex_unlock(&s->mu);
    return same;
}

/* One reconnection attempt: open, recover, restart the stream. */
static int reconnect_once(lep_session *s)
{
    char err[256];
    int rc = lep_priv_session_connect(s, err, sizeof err);
    if (rc == LEP_OK && !same_sensor(s)) {
        /* Another sensor on the port: its data is not this recording's
         * (other rated values, other frame). Stop here, clearly. */
        lep_priv_session_disconnect(s);
        s->failed = LEP_E_UNEXPECTED;
        return LEP_E_UNEXPECTED;
    }
    if (rc == LEP_OK)
        rc = lep_client_start(&s->client);
    if (rc != LEP_OK) {
        /* a port that is not there: watch for it to come back (a replug) */
        s->port_missing = rc == LEP_E_NOT_FOUND;
        lep_priv_session_disconnect(s);
        s->backoff_ms = s->backoff_ms * 2 > s->opt.reconnect_max_ms ? s->opt.reconnect_max_ms
                                                                    : s->backoff_ms * 2;
        s->next_attempt = lep_monotonic_seconds() + (double)s->backoff_ms / 1000.0;
        return rc;
    }
    lep_client_get_stats(&s->client, &s->base_stats);
    pthread_mutex_lock(&s->mu);
    s->h.reconnects++;
    lep_priv_lowpass_restart(&s->lp);
    pthread_mutex_unlock(&s->mu);
    s->have_seq = false;
    s->gap_next = true;
    s->tm_started = false;
    s->port_missing = false;
    lep_priv_session_stream_reset(s, lep_monotonic_seconds());
    return LEP_OK;
}

/* ---- delivery ---- */

static void copy_row(lep_session_batch *b, const session_row *r)
{
    size_t i = b->n, k;
    if (b->t_mono != NULL)
        b->t_mono[i] = r->t_mono;
    if (b->t_utc != NULL)
        b->t_utc[i] = r->t_utc;
    if (b->raw != NULL)
        memcpy(&b->raw[i * LEP_AXES], r->raw, sizeof r->raw);
    if (b->zeroed != NULL)
        for (k = 0; k < LEP_AXES; k++)
            b->zeroed[i * LEP_AXES + k] = r->zeroed[k];
    if (b->si != NULL)
        for (k = 0; k < LEP_AXES; k++)
            b->si[i * LEP_AXES + k] = r->si[k];
    if (b->status != NULL)
        b->status[i] = r->status;
    if (b->flags != NULL)
        b->flags[i] = r->flags;
    if (b->seq != NULL)
        b->seq[i] = r->seq;
    b->n = i + 1u;
}

/* Move pending rows into b; *first gets the arrival of the first one moved. */
static void deliver(lep_session *s, lep_session_batch *b, double *first)
{
    while (s->pend_len > s->held && b->n < b->cap) {
        const session_row *r = &s->pending[s->pend_head];
        if (*first < 0.0)
            *first = r->t_mono;
        copy_row(b, r);
        s->pend_head = (s->pend_head + 1u) % SESSION_PENDING;
        s->pend_len--;
    }
    if (s->pend_len == 0)
        s->pend_head = 0;
}

int lep_priv_session_read(lep_session *s, lep_session_batch *b, int timeout_ms)
{
    double budget = s != NULL ? (double)s->opt.latency_ms / 1000.0 : 0.0;
    double deadline, first = -1.0;
    bool budget_read = false; /* a read after sleeping out the budget was made */
    size_t n0;
    uint64_t ev0;

    if (s == NULL || b == NULL || b->n > b->cap)
        return LEP_E_ARG;
    if (!s->streaming)
        return LEP_E_STATE;
    /* Never sleep longer than the kernel can buffer for us. */
    if (budget > SESSION_KERNEL_BYTES / (s->nominal_hz * SESSION_MIN_FRAME))
        budget = SESSION_KERNEL_BYTES / (s->nominal_hz * SESSION_MIN_FRAME);
    n0 = b->n;
    ev0 = events_pushed(s);
    deadline = timeout_ms < 0 ? INFINITY : lep_monotonic_seconds() + (double)timeout_ms / 1000.0;
    for (;;) {
        double now, data_deadline, wake;
        bool got;
        int rc, wait;

        deliver(s, b, &first);
        if (s->ended && s->pend_len == s->held) {
            s->held = 0; /* nothing comes after the end to judge it by */
            if (s->pend_len > 0)
                continue;
            return LEP_E_END;
        }
        if (b->n == b->cap)
            return LEP_OK;
        got = b->n > n0 || events_pushed(s) != ev0;
        if (s->failed != 0)
            return got ? LEP_OK : s->failed;
        now = lep_monotonic_seconds();
        if (got && !s->backlog &&
            (budget <= 0.0 || b->n == n0 || budget_read || now >= first + budget))
            return LEP_OK;

        if (s->conn == CONN_DOWN) {
            if (s->opt.reconnect_give_up_ms >= 0 &&
                now - s->down_since >= (double)s->opt.reconnect_give_up_ms / 1000.0) {
                s->failed = LEP_E_DISCONNECTED;
                continue;
            }
            /* Attempt when the backoff is over, or at once when a port that
             * had vanished is back (checked every SESSION_WATCH_S). */
            if (now < s->next_attempt && !(s->port_missing && access(s->opt.port, F_OK) == 0)) {
                wake = s->next_attempt < deadline ? s->next_attempt : deadline;
                if (s->port_missing && wake > now + SESSION_WATCH_S)
                    wake = now + SESSION_WATCH_S;
                lep_priv_sleep_until_ns((int64_t)(wake * 1e9));
                if (lep_monotonic_seconds() >= deadline)
                    return got ? LEP_OK : LEP_E_TIMEOUT;
                continue;
            }
            (void)reconnect_once(s);
            continue;
        }

        data_deadline = s->last_data_read_t + (double)s->opt.data_timeout_ms / 1000.0;
        if (s->backlog) {
            /* the last read filled the buffer: more is waiting, take it now */
            wait = 0;
        } else if (budget > 0.0) {
            /* Save wake-ups: sleep until the budget is spent, then take
             * everything in one read that does not wait. */
            wake = got ? first + budget : s->last_read_t + budget;
            if (s->held > 0 && wake > s->last_read_t + SESSION_CONFIRM_S)
                wake = s->last_read_t + SESSION_CONFIRM_S; /* judge a suspected hole soon */
            if (wake > deadline)
                wake = deadline;
            if (wake > data_deadline)
                wake = data_deadline;
            lep_priv_sleep_until_ns((int64_t)(wake * 1e9));
            wait = 0;
            budget_read = true;
        } else {
            wait = ms_until(deadline < data_deadline ? deadline : data_deadline, now);
        }
        rc = s->client.io.read(s->client.io.user, s->rbuf, sizeof s->rbuf, wait);
        now = lep_monotonic_seconds();
        /* More may be waiting: a read returns at most what the tty layer
         * holds (4 KiB on Linux), so with a budget, read until one comes back
         * empty; without, only after a read that filled the buffer. */
        s->backlog = rc == (int)sizeof s->rbuf || (budget > 0.0 && rc > 0);
        if (rc > 0) {
            lep_priv_session_feed(s, s->rbuf, (size_t)rc, now);
            continue;
        }
        if (rc == 0) {
            s->last_read_t = now;
            if (now >= data_deadline) {
                stream_lost(s, LEP_E_TIMEOUT, now);
                continue;
            }
            if (now >= deadline)
                return got ? LEP_OK : LEP_E_TIMEOUT;
            continue;
        }
        if (rc == LEP_E_DISCONNECTED || rc == LEP_E_IO) {
            stream_lost(s, LEP_E_DISCONNECTED, now);
            continue;
        }
        return got ? LEP_OK : rc;
    }
}

void lep_session_get_health(lep_session *s, lep_session_health *out)
{
    if (out == NULL)
        return;
    if (s == NULL) {
        memset(out, 0, sizeof *out);
        return;
    }
    pthread_mutex_lock(&s->mu);
    *out = s->h;
    pthread_mutex_unlock(&s->mu);
}
