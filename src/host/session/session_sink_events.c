/* Host session, the sink's event queue (session_sink.h): events wait here until
 * lep_session_next_event takes them, and until the rows before their sample
 * are returned (a read may process more rows than its batch takes); a full
 * queue drops its oldest and counts it (lep_session_health_info.events_dropped). */
#include <stdint.h>
#include <string.h>

#include "session_clock.h"
#include "session_sink.h"

void lep_priv_event_init(lep_session_event *ev, int type, uint64_t sample, double t_mono)
{
    memset(ev, 0, sizeof *ev);
    ev->type = type;
    ev->sample = sample;
    ev->t_mono = t_mono;
    ev->t_utc = t_mono + lep_priv_utc_offset();
}

void lep_priv_events_start(session_events *q)
{
    q->dropped = 0; /* a health counter: since start; the queue itself goes on */
    q->ungated = q->len;
    q->gate = 0;
}

void lep_priv_events_stop(session_events *q)
{
    q->gate = UINT64_MAX;
}

void lep_priv_events_returned(session_events *q, uint64_t rows)
{
    q->gate = rows;
}

void lep_priv_events_push(session_events *q, const lep_session_event *ev)
{
    if (q->len == SESSION_EVENTS) { /* full: the oldest goes */
        q->head = (q->head + 1u) % SESSION_EVENTS;
        q->len--;
        q->dropped++;
        if (q->ungated > 0)
            q->ungated--;
    }
    q->ev[(q->head + q->len) % SESSION_EVENTS] = *ev;
    q->len++;
    q->pushed++;
}

bool lep_priv_events_pop(session_events *q, lep_session_event *ev)
{
    if (q->len == 0 || (q->ungated == 0 && q->ev[q->head].sample > q->gate))
        return false;
    if (q->ungated > 0)
        q->ungated--;
    *ev = q->ev[q->head];
    q->head = (q->head + 1u) % SESSION_EVENTS;
    q->len--;
    return true;
}
