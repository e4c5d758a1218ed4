/* Host session, reading: lep_session_read (wait for samples within the
 * timeout and the latency budget, read the port, hand the bytes to the feed,
 * reconnect inside the call) and lep_session_read_one (one handshake sample
 * through the session's units and processing). */
#include <math.h>
#include <string.h>

#include "leptrino/error.h"
#include "posix_clock.h"
#include "session_priv.h"

/* Not an outcome: go round the read loop again. */
#define READ_AGAIN 1

/* A read with a latency budget sleeps the budget out, drains the port, then
 * waits for the next frame: its arrival, seen at once, is a point on the
 * sensor's clock as close as an unbudgeted read's (a drain alone returns
 * at a time unrelated to the last sample's arrival, up to a period after
 * it, and in lockstep with the stream when the budget is a whole number of
 * periods). It costs one wake-up more per budget, and is made only when a
 * budget spans PROBE_MIN_PERIODS periods or more (so the wait, at most
 * PROBE_WAIT_PERIODS, is small beside the budget). */
#define PROBE_MIN_PERIODS 4.0
#define PROBE_WAIT_PERIODS 2.0

/* Where a call with a latency budget is. */
enum budget_stage {
    BUDGET_AWAKE,   /* not slept yet */
    BUDGET_SLEPT,   /* slept out the budget: draining without waiting */
    BUDGET_DRAINED, /* the port found empty: the next read waits for a frame */
    BUDGET_DONE     /* the budgeted read is made: deliver */
};

/* One call of lep_session_read. */
typedef struct read_call {
    lep_session_batch *b;
    double budget;   /* latency budget, s */
    double deadline; /* of the call's timeout, monotonic s (INFINITY: none) */
    double first;    /* arrival of the first sample appended (< 0: none yet) */
    bool probe;      /* wait for a frame after the drain (see PROBE_MIN_PERIODS) */
    int stage;       /* enum budget_stage */
    bool got;        /* samples appended or events queued */
    size_t n0;
    uint64_t ev0;
} read_call;

static uint64_t events_pushed(lep_session *s)
{
    uint64_t n;
    pthread_mutex_lock(&s->mu);
    n = s->events.pushed;
    pthread_mutex_unlock(&s->mu);
    return n;
}

/* Rows into the caller's batch: counted, and their events free to go. */
static void deliver_rows(lep_session *s, lep_session_batch *b, double *first)
{
    size_t n = b->n;
    lep_priv_rows_deliver(&s->rows, b, first);
    if (b->n == n)
        return;
    pthread_mutex_lock(&s->mu);
    s->hs.h.delivered += b->n - n;
    lep_priv_events_returned(&s->events, s->hs.h.delivered);
    pthread_mutex_unlock(&s->mu);
}

/* Deliver what is pending, and say whether the call is over: its outcome,
 * or READ_AGAIN. */
static int delivered(lep_session *s, read_call *c, double *now)
{
    lep_session_batch *b = c->b;
    for (;;) {
        deliver_rows(s, b, &c->first);
        if (!(s->proc.ended && s->rows.len == s->rows.held))
            break;
        s->rows.held = 0; /* nothing comes after the end to judge it by */
        lep_priv_timeline_forget_held(&s->tm.tl);
        if (s->rows.len == 0)
            return LEP_E_END;
    }
    if (b->n == b->cap)
        return LEP_OK;
    c->got = b->n > c->n0 || events_pushed(s) != c->ev0;
    if (s->rc.failed != 0)
        return c->got ? LEP_OK : s->rc.failed;
    *now = lep_monotonic_seconds();
    if (c->got && !s->backlog &&
        (c->budget <= 0.0 || b->n == c->n0 || c->stage == BUDGET_DONE ||
         *now >= c->first + c->budget))
        return LEP_OK;
    return READ_AGAIN;
}

/* How long the next port read may wait, ms; with a budget, sleep it out first. */
static int port_wait(lep_session *s, read_call *c, double now, double data_deadline)
{
    double wake;
    if (s->backlog)
        return 0; /* the last read filled the buffer: more is waiting, take it now */
    if (c->budget <= 0.0)
        return lep_priv_ms_until(c->deadline < data_deadline ? c->deadline : data_deadline, now);
    if (c->stage == BUDGET_DRAINED) {
        /* the port is empty: the next frame's arrival is seen at once */
        wake = now + PROBE_WAIT_PERIODS * s->period_s;
        c->stage = BUDGET_DONE;
        return lep_priv_ms_until(wake < c->deadline ? wake : c->deadline, now);
    }
    /* Save wake-ups: sleep until the budget is spent (less the probe's
     * period), then take everything in reads that do not wait. */
    wake = c->got ? c->first + c->budget : s->tm.last_read_t + c->budget;
    if (c->probe)
        wake -= s->period_s;
    if (s->rows.held > 0 && wake > s->tm.last_read_t + SESSION_CONFIRM_S)
        wake = s->tm.last_read_t + SESSION_CONFIRM_S; /* judge a suspected hole soon */
    if (wake > c->deadline)
        wake = c->deadline;
    if (wake > data_deadline)
        wake = data_deadline;
    lep_priv_sleep_until_ns((int64_t)(wake * 1e9));
    c->stage = BUDGET_SLEPT;
    return 0;
}

/* One read of the port, fed on; the call's outcome or READ_AGAIN. */
static int read_port(lep_session *s, read_call *c, double now)
{
    double data_deadline = s->tm.last_data_read_t + (double)s->opt.data_timeout_ms / 1000.0;
    int wait = port_wait(s, c, now, data_deadline);
    int rc = s->client.io.read(s->client.io.user, s->rbuf, sizeof s->rbuf, wait);
    now = lep_monotonic_seconds();
    /* More may be waiting: a read returns at most what the tty layer holds
     * (4 KiB on Linux), so with a budget, read until one comes back empty;
     * without, only after a read that filled the buffer. */
    s->backlog =
        rc == (int)sizeof s->rbuf || (c->budget > 0.0 && rc > 0 && c->stage != BUDGET_DONE);
    if (rc == 0 && c->stage == BUDGET_SLEPT)
        c->stage = c->probe ? BUDGET_DRAINED : BUDGET_DONE;
    if (rc > 0) {
        lep_priv_session_feed(s, s->rbuf, (size_t)rc, now);
        return READ_AGAIN;
    }
    if (rc == 0) {
        s->tm.last_read_t = now;
        lep_priv_timeline_empty(&s->tm.tl, now);
        if (now >= data_deadline)
            lep_priv_reconnect_lost(s, LEP_E_TIMEOUT, now);
        else if (now >= c->deadline)
            return c->got ? LEP_OK : LEP_E_TIMEOUT;
        return READ_AGAIN;
    }
    if (rc == LEP_E_DISCONNECTED || rc == LEP_E_IO) {
        lep_priv_reconnect_lost(s, LEP_E_DISCONNECTED, now);
        return READ_AGAIN;
    }
    return c->got ? LEP_OK : rc;
}

/* One pass of a read, for the thread inside the guard. */
static int read_pass(lep_session *s, lep_session_batch *b, int timeout_ms)
{
    read_call c;
    double kernel_s;

    if (!s->streaming)
        return LEP_E_STATE;
    memset(&c, 0, sizeof c);
    c.b = b;
    c.first = -1.0;
    c.n0 = b->n;
    c.ev0 = events_pushed(s);
    /* Never sleep longer than the kernel can buffer for us. */
    c.budget = (double)s->opt.latency_ms / 1000.0;
    kernel_s = SESSION_KERNEL_BYTES / (s->nominal_hz * SESSION_MIN_FRAME);
    if (c.budget > kernel_s)
        c.budget = kernel_s;
    c.probe = c.budget >= PROBE_MIN_PERIODS * s->period_s;
    c.deadline = timeout_ms < 0 ? INFINITY : lep_monotonic_seconds() + (double)timeout_ms / 1000.0;
    for (;;) {
        double now = 0.0;
        int rc = delivered(s, &c, &now);
        if (rc == READ_AGAIN && s->conn == CONN_DOWN)
            rc = lep_priv_reconnect_wait(s, now, c.deadline) ? READ_AGAIN
                 : c.got                                     ? LEP_OK
                                                             : LEP_E_TIMEOUT;
        else if (rc == READ_AGAIN)
            rc = read_port(s, &c, now);
        if (rc != READ_AGAIN)
            return rc;
    }
}

static int read_one(lep_session *s, lep_session_batch *b)
{
    lep_sample smp;
    session_row row;
    double t;
    int rc;

    if (s->streaming)
        return LEP_E_STATE;
    if (s->conn != CONN_UP)
        return LEP_E_DISCONNECTED;
    rc = lep_client_sample(&s->client, &smp);
    t = lep_monotonic_seconds();
    if (rc != LEP_OK)
        return rc;
    pthread_mutex_lock(&s->mu);
    lep_priv_proc_one(s, &smp, t, t + lep_priv_utc_offset(), &row);
    pthread_mutex_unlock(&s->mu);
    lep_priv_rows_append(b, &row);
    return LEP_OK;
}

/* Longest wait of one pass of the stream reader: how soon a close from
 * another thread is seen (a latency budget lengthens it, see below). */
#define GUARD_SLICE_MS 50

int lep_session_read_batch(lep_session *s, lep_session_batch *b, int timeout_ms)
{
    double deadline;
    int rc, slice_ms;
    if (s == NULL || b == NULL || b->n > b->cap)
        return LEP_E_ARG;
    rc = lep_priv_guard_enter(&s->guard);
    if (rc != LEP_OK)
        return rc;
    pthread_mutex_lock(&s->mu); /* the events' batch rows count from this batch's row 0 */
    lep_priv_events_batch(&s->events, s->hs.h.delivered, b->n);
    pthread_mutex_unlock(&s->mu);
    /* A pass must be able to sleep out the latency budget, or the budget
     * would end at every pass. */
    slice_ms = s->opt.latency_ms + GUARD_SLICE_MS;
    deadline = timeout_ms < 0 ? INFINITY : lep_monotonic_seconds() + (double)timeout_ms / 1000.0;
    for (;;) {
        double left_ms = (deadline - lep_monotonic_seconds()) * 1000.0;
        int wait = left_ms > (double)slice_ms ? slice_ms : left_ms > 0.0 ? (int)ceil(left_ms) : 0;
        rc = read_pass(s, b, wait);
        /* nothing in this pass, the stream not given up: wait on unless the
         * caller's time is out or the session is being closed */
        if (rc != LEP_E_TIMEOUT || s->rc.failed != 0 || left_ms <= (double)slice_ms)
            break;
        if (lep_priv_guard_closing(&s->guard)) {
            rc = LEP_E_STATE;
            break;
        }
    }
    lep_priv_guard_leave(&s->guard);
    return rc;
}

int lep_session_read_one_batch(lep_session *s, lep_session_batch *b)
{
    int rc;
    if (s == NULL || b == NULL || b->n >= b->cap)
        return LEP_E_ARG;
    rc = lep_priv_guard_enter(&s->guard);
    if (rc != LEP_OK)
        return rc;
    rc = read_one(s, b);
    lep_priv_guard_leave(&s->guard);
    return rc;
}
