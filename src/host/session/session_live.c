/* Host session, the any-thread calls (leptrino/session.h, struct_api.h):
 * each takes the session's mutex and asks the unit that owns the state. */
#include <string.h>

#include "leptrino/error.h"
#include "session_priv.h"

bool lep_session_pop_event(lep_session *s, lep_session_event *ev)
{
    bool got;
    if (s == NULL || ev == NULL)
        return false;
    pthread_mutex_lock(&s->mu);
    got = lep_priv_sink_pop(&s->sink, ev);
    pthread_mutex_unlock(&s->mu);
    return got;
}

void lep_session_get_health(lep_session *s, lep_session_health_info *out)
{
    if (out == NULL)
        return;
    if (s == NULL) {
        memset(out, 0, sizeof *out);
        return;
    }
    pthread_mutex_lock(&s->mu);
    lep_priv_sink_health(&s->sink, out);
    pthread_mutex_unlock(&s->mu);
}
