/* Host session, reading: lep_session_read (inside the thread guard, in
 * passes that see a close) and lep_session_read_one. This file wires the
 * units for one call: the reader's bytes and their read times, stepped into
 * samples, fed to the pipeline (the timing stamps them and hands them to the
 * chain, which keeps their rows in the sink), the sink's rows delivered into
 * the caller's batch; a loss and a reconnection
 * told to each unit in turn. It writes no unit's fields: it calls their
 * functions, with the session's mutex held for the [mu] ones. */
#include <math.h>
#include <string.h>

#include "leptrino/error.h"
#include "session_priv.h"

/* Not an outcome: go round the read loop again. */
#define READ_AGAIN 1

/* One call of lep_session_read. */
typedef struct read_call {
    lep_session_batch *b;
    reader_call rc; /* the budget, the reader's */
    double first;   /* stamp of the first row appended (< 0: none yet) */
    bool got;       /* rows appended or events queued */
    size_t n0;
    uint64_t ev0;
} read_call;

static uint64_t events_pushed(lep_session *s)
{
    uint64_t n;
    pthread_mutex_lock(&s->mu);
    n = lep_priv_sink_pushed(&s->sink);
    pthread_mutex_unlock(&s->mu);
    return n;
}

/* Bytes read at t_read: the samples they complete stamped, checked for
 * gaps, counted, processed and kept as rows for the next read. */
static void feed(lep_session *s, const uint8_t *data, size_t len, double t_read)
{
    lep_sample got[SESSION_PENDING];
    lep_client_stats st;
    size_t n = lep_priv_reader_samples(&s->rd, data, len, got, t_read);

    lep_priv_reader_stats(&s->rd, &st);
    if (n > 0)
        (void)lep_priv_timing_utc(&s->tm, t_read); /* outside the mutex: clock reads */
    pthread_mutex_lock(&s->mu);
    lep_priv_sink_client(&s->sink, &st);
    if (n > 0)
        lep_priv_timing_feed(&s->tm, &s->chain, &s->sink, got, n, t_read);
    pthread_mutex_unlock(&s->mu);
}

void lep_priv_session_resume(lep_session *s, double now)
{
    uint8_t left[LEP_CLIENT_RX_SIZE];
    size_t n = lep_priv_reader_resume(&s->rd, now, left);
    lep_priv_timing_resume(&s->tm, now);
    if (n > 0)
        feed(s, left, n, now);
}

/* The stream is lost at now (error: LEP_E_DISCONNECTED, port gone, or
 * LEP_E_TIMEOUT, no data for data_timeout_ms): the event and the counters,
 * the stamps start over, the reader gives up or begins to reconnect. */
static void stream_lost(lep_session *s, int error, double now)
{
    lep_session_event ev;
    lep_client_stats st;
    lep_priv_reader_stats(&s->rd, &st);
    pthread_mutex_lock(&s->mu);
    lep_priv_event_init(&ev, LEP_EV_DISCONNECTED, lep_priv_sink_processed(&s->sink), now);
    ev.error = error;
    ev.gap_from = lep_priv_timing_last(&s->tm);
    lep_priv_sink_lost(&s->sink, &ev, &st);
    lep_priv_timing_lost(&s->tm, &s->sink);
    pthread_mutex_unlock(&s->mu);
    lep_priv_reader_lost(&s->rd, error, now);
    if (s->opt.reconnect)
        lep_priv_timing_reconnected(&s->tm, error);
}

/* While disconnected: the reader waits or attempts; a sensor that answered
 * is the metadata's, a stream running again is resumed. False when the
 * deadline passed asleep. */
static bool reconnect_wait(lep_session *s, double now, double deadline)
{
    lep_product_info info;
    bool identified = false;
    int w = lep_priv_reader_wait(&s->rd, now, deadline, &info, &identified);
    if (identified) {
        pthread_mutex_lock(&s->mu); /* the metadata may be read from another thread */
        s->info = info;
        pthread_mutex_unlock(&s->mu);
    }
    if (w == READER_RECONNECTED) {
        lep_client_stats base;
        lep_priv_reader_stats(&s->rd, &base);
        pthread_mutex_lock(&s->mu);
        lep_priv_sink_reconnected(&s->sink, &base);
        lep_priv_chain_restart_filter(&s->chain);
        pthread_mutex_unlock(&s->mu);
        lep_priv_session_resume(s, lep_monotonic_seconds());
    }
    return w != READER_TIMED_OUT;
}

/* Rows into the caller's batch: counted, and their events free to go. */
static void deliver_rows(lep_session *s, lep_session_batch *b, double *first)
{
    size_t n = lep_priv_sink_deliver(&s->sink, b, first);
    if (n == 0)
        return;
    pthread_mutex_lock(&s->mu);
    lep_priv_sink_returned(&s->sink, n);
    pthread_mutex_unlock(&s->mu);
}

/* Deliver what is pending, and say whether the call is over: its outcome,
 * or READ_AGAIN. */
static int delivered(lep_session *s, read_call *c, double *now)
{
    lep_session_batch *b = c->b;
    int failed;
    for (;;) {
        deliver_rows(s, b, &c->first);
        if (!lep_priv_chain_ended(&s->chain) || !lep_priv_timing_end(&s->tm, &s->sink))
            break; /* (the end: rows held back go, nothing comes to judge them by) */
        if (lep_priv_sink_pending(&s->sink) == 0)
            return LEP_E_END;
    }
    if (b->n == b->cap)
        return LEP_OK;
    c->got = b->n > c->n0 || events_pushed(s) != c->ev0;
    failed = lep_priv_reader_failed(&s->rd);
    if (failed != 0)
        return c->got ? LEP_OK : failed;
    *now = lep_monotonic_seconds();
    if (c->got && lep_priv_reader_call_over(&s->rd, &c->rc, *now, b->n != c->n0, c->first))
        return LEP_OK;
    return READ_AGAIN;
}

/* One read of the port, fed on; the call's outcome or READ_AGAIN. */
static int read_port(lep_session *s, read_call *c, double now)
{
    double t;
    int rc = lep_priv_reader_read(&s->rd, &c->rc, now, c->got, c->first,
                                  lep_priv_sink_held(&s->sink) > 0, &t);
    if (rc > 0) {
        feed(s, lep_priv_reader_bytes(&s->rd), (size_t)rc, t);
        return READ_AGAIN;
    }
    if (rc == 0) {
        lep_priv_timing_empty(&s->tm, t);
        if (lep_priv_reader_silent(&s->rd, t))
            stream_lost(s, LEP_E_TIMEOUT, t);
        else if (t >= c->rc.deadline)
            return c->got ? LEP_OK : LEP_E_TIMEOUT;
        return READ_AGAIN;
    }
    if (rc == LEP_E_DISCONNECTED || rc == LEP_E_IO) {
        stream_lost(s, LEP_E_DISCONNECTED, t);
        return READ_AGAIN;
    }
    return c->got ? LEP_OK : rc;
}

/* One pass of a read, for the thread inside the guard. */
static int read_pass(lep_session *s, lep_session_batch *b, int timeout_ms)
{
    read_call c;

    if (!s->streaming)
        return LEP_E_STATE;
    memset(&c, 0, sizeof c);
    c.b = b;
    c.first = -1.0;
    c.n0 = b->n;
    c.ev0 = events_pushed(s);
    lep_priv_reader_call(&s->rd, &c.rc, s->opt.latency_ms, timeout_ms);
    for (;;) {
        double now = 0.0;
        int rc = delivered(s, &c, &now);
        if (rc == READ_AGAIN && !lep_priv_reader_up(&s->rd))
            rc = reconnect_wait(s, now, c.rc.deadline) ? READ_AGAIN
                 : c.got                               ? LEP_OK
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
    rc = lep_priv_reader_sample(&s->rd, &smp);
    t = lep_monotonic_seconds();
    if (rc != LEP_OK)
        return rc;
    pthread_mutex_lock(&s->mu);
    lep_priv_chain_one(&s->chain, &smp, t, t + lep_priv_utc_offset(), &row);
    pthread_mutex_unlock(&s->mu);
    lep_priv_row_append(b, &row);
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
    lep_priv_sink_batch(&s->sink, b->n);
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
        if (rc != LEP_E_TIMEOUT || lep_priv_reader_failed(&s->rd) != 0 ||
            left_ms <= (double)slice_ms)
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
