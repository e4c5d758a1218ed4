/* Host session, the sink (session_sink.h): processed rows waiting for
 * lep_session_read (a ring of two reads' worth), the newest held back while a
 * hole is suspected, their delivery into the caller's batch; and the entry
 * points that queue events and count what they imply. */
#include <string.h>

#include "leptrino/error.h"
#include "session_sink.h"

void lep_priv_sink_open(session_sink *sk)
{
    lep_priv_events_stop(&sk->events);
}

void lep_priv_sink_start(session_sink *sk, double nominal_hz, const lep_client_stats *base)
{
    sk->rows.head = sk->rows.len = 0;
    sk->rows.held = 0;
    lep_priv_health_start(&sk->hs, nominal_hz, base);
    lep_priv_events_start(&sk->events);
}

void lep_priv_sink_stop(session_sink *sk)
{
    sk->rows.head = sk->rows.len = 0;
    sk->rows.held = 0;
    lep_priv_events_stop(&sk->events); /* the rows their samples wait for are gone */
}

void lep_priv_sink_batch(session_sink *sk, size_t held)
{
    lep_priv_events_batch(&sk->events, sk->hs.h.delivered, held);
}

void lep_priv_sink_row(session_sink *sk, const session_row *row)
{
    session_rows *r = &sk->rows;
    if (r->len >= SESSION_ROWS)
        return;
    r->pending[(r->head + r->len) % SESSION_ROWS] = *row;
    r->len++;
    sk->hs.processed++;
}

uint64_t lep_priv_sink_processed(const session_sink *sk)
{
    return sk->hs.processed;
}

size_t lep_priv_sink_pending(const session_sink *sk)
{
    return sk->rows.len;
}

size_t lep_priv_sink_held(const session_sink *sk)
{
    return sk->rows.held;
}

size_t lep_priv_sink_hold_since(session_sink *sk, size_t before, bool extend)
{
    size_t n = sk->rows.len > before ? sk->rows.len - before : 0u;
    if (extend)
        sk->rows.held += n;
    else if (n > 0)
        sk->rows.held = n;
    return n;
}

bool lep_priv_sink_end(session_sink *sk)
{
    if (sk->rows.len != sk->rows.held)
        return false;
    sk->rows.held = 0;
    return true;
}

void lep_priv_sink_release(session_sink *sk)
{
    sk->rows.held = 0;
}

/* The row `back` rows before the newest pending one (0: the newest). */
static session_row *row_back(session_rows *r, size_t back)
{
    return &r->pending[(r->head + r->len - 1u - back) % SESSION_ROWS];
}

bool lep_priv_sink_judged(session_sink *sk, bool gap, double shift)
{
    session_rows *rows = &sk->rows;
    size_t b;
    if (!gap || rows->held == 0) {
        rows->held = 0;
        return false;
    }
    for (b = 0; b < rows->held; b++) {
        session_row *r = row_back(rows, b);
        double t = r->t_mono + shift < r->arrived ? r->t_mono + shift : r->arrived;
        r->t_utc += t - r->t_mono;
        r->t_mono = t;
    }
    row_back(rows, rows->held - 1u)->flags |= LEP_SF_GAP;
    rows->held = 0;
    return true;
}

void lep_priv_row_append(lep_session_batch *b, const session_row *r)
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

size_t lep_priv_sink_deliver(session_sink *sk, lep_session_batch *b, double *first)
{
    session_rows *r = &sk->rows;
    size_t n = b->n;
    while (r->len > r->held && b->n < b->cap) {
        const session_row *row = &r->pending[r->head];
        if (*first < 0.0)
            *first = row->t_mono;
        lep_priv_row_append(b, row);
        r->head = (r->head + 1u) % SESSION_ROWS;
        r->len--;
    }
    if (r->len == 0)
        r->head = 0;
    return b->n - n;
}

void lep_priv_sink_returned(session_sink *sk, size_t n)
{
    sk->hs.h.delivered += n;
    lep_priv_events_returned(&sk->events, sk->hs.h.delivered);
}

void lep_priv_sink_event(session_sink *sk, const lep_session_event *ev)
{
    lep_priv_events_push(&sk->events, ev);
    switch (ev->type) {
    case LEP_EV_OVERLOAD_BEGIN:
        sk->hs.h.overloads++;
        break;
    case LEP_EV_LIMIT_EXCEEDED:
        sk->hs.h.limit_episodes++;
        break;
    case LEP_EV_GAP:
    case LEP_EV_RECONNECTED:
        lep_priv_health_gap(&sk->hs, ev->gap_from, ev->gap_to, ev->lost);
        break;
    default:
        break;
    }
}

void lep_priv_sink_lost(session_sink *sk, const lep_session_event *ev, const lep_client_stats *st)
{
    lep_priv_events_push(&sk->events, ev);
    lep_priv_health_lost(&sk->hs, st, ev->error);
}

void lep_priv_sink_reconnected(session_sink *sk, const lep_client_stats *base)
{
    lep_priv_health_reconnected(&sk->hs, base);
}

void lep_priv_sink_client(session_sink *sk, const lep_client_stats *st)
{
    lep_priv_health_client(&sk->hs, st);
}

bool lep_priv_sink_received(session_sink *sk, double t)
{
    lep_priv_health_sample(&sk->hs, t);
    return sk->rows.len < SESSION_ROWS;
}

uint64_t lep_priv_sink_pushed(const session_sink *sk)
{
    return sk->events.pushed;
}

bool lep_priv_sink_pop(session_sink *sk, lep_session_event *ev)
{
    return lep_priv_events_pop(&sk->events, ev);
}

void lep_priv_sink_health(const session_sink *sk, lep_session_health_info *out)
{
    *out = sk->hs.h;
    out->events_dropped = sk->events.dropped;
}
