/* Host session, the sink's event queue (session_sink.h): events wait here until
 * lep_session_next_event takes them, and until the rows before their sample
 * are returned (a read may process more rows than its batch takes); a full
 * queue drops its oldest and counts it (lep_session_health_info.events_dropped).
 * Each event says where it lies twice: its sample, the stream's row number
 * (0 for an event queued before the stream started), and its row in the
 * batch of the last read (sample less that batch's first row number), so a
 * front end places it among the rows it holds without counting them. */
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
    size_t k;
    q->dropped = 0;              /* a health counter: since start; the queue itself goes on */
    for (k = 0; k < q->len; k++) /* another stream's numbers: at this one's start */
        q->ev[(q->head + k) % SESSION_EVENTS].sample = 0;
    q->gate = 0;
    q->row_base = 0;
}

void lep_priv_events_stop(session_events *q)
{
    q->gate = UINT64_MAX;
    q->row_base = 0;
}

void lep_priv_events_returned(session_events *q, uint64_t rows)
{
    q->gate = rows;
}

void lep_priv_events_batch(session_events *q, uint64_t rows, size_t held)
{
    if (q->gate != UINT64_MAX) /* stopped: batch rows are the samples */
        q->row_base = (int64_t)rows - (int64_t)held;
}

void lep_priv_events_push(session_events *q, const lep_session_event *ev)
{
    if (q->len == SESSION_EVENTS) { /* full: the oldest goes */
        q->head = (q->head + 1u) % SESSION_EVENTS;
        q->len--;
        q->dropped++;
    }
    q->ev[(q->head + q->len) % SESSION_EVENTS] = *ev;
    if (q->gate == UINT64_MAX) /* stopped: it comes at the next stream's start */
        q->ev[(q->head + q->len) % SESSION_EVENTS].sample = 0;
    q->len++;
    q->pushed++;
}

bool lep_priv_events_pop(session_events *q, lep_session_event *ev)
{
    if (q->len == 0 || q->ev[q->head].sample > q->gate)
        return false;
    *ev = q->ev[q->head];
    ev->row = (int64_t)ev->sample - q->row_base;
    q->head = (q->head + 1u) % SESSION_EVENTS;
    q->len--;
    return true;
}
