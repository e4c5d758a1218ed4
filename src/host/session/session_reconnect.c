/* Host session, loss and reconnection: a stream lost (port gone, or no data
 * for data_timeout_ms) is reported as LEP_EV_DISCONNECTED; without reconnect
 * it ends the stream (a sticky outcome for lep_session_read), with reconnect
 * the port is reopened with backoff, re-synced and restarted. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <unistd.h>

#include "leptrino/error.h"
#include "posix_clock.h"
#include "session_priv.h"

void lep_priv_reconnect_start(session_reconnect *r)
{
    r->failed = 0;
}

void lep_priv_reconnect_lost(lep_session *s, int error, double now)
{
    session_reconnect *r = &s->rc;
    lep_session_event ev;
    lep_client_stats st;
    lep_client_get_stats(&s->client, &st);
    pthread_mutex_lock(&s->mu);
    lep_priv_event_init(&ev, LEP_EV_DISCONNECTED, lep_priv_sink_processed(&s->sink), now);
    ev.error = error;
    ev.gap_from = s->tm.last_sample_t;
    lep_priv_sink_lost(&s->sink, &ev, &st);
    lep_priv_timing_lost(s);
    pthread_mutex_unlock(&s->mu);
    if (!s->opt.reconnect) {
        /* a data timeout is the stream lost; a port gone stays a disconnect */
        r->failed = error == LEP_E_TIMEOUT ? LEP_E_LOST : error;
        return;
    }
    lep_priv_session_disconnect(s);
    r->down_since = now;
    r->port_missing = access(s->opt.port, F_OK) != 0;
    r->backoff_ms = s->opt.reconnect_min_ms;
    r->next_attempt = now + (double)r->backoff_ms / 1000.0;
    lep_priv_timing_reconnected(&s->tm, s->tm.last_sample_t, error);
}

/* One reconnection attempt: open, recover, restart the stream. */
static int attempt(lep_session *s)
{
    session_reconnect *r = &s->rc;
    lep_client_stats base;
    char err[256];
    int rc = lep_priv_session_connect(s, err, sizeof err);
    if (rc == LEP_OK && !lep_priv_session_same_sensor(s)) {
        /* Another sensor on the port: its data is not this recording's
         * (other rated values, other frame). Stop here, clearly. */
        lep_priv_session_disconnect(s);
        r->failed = LEP_E_UNEXPECTED;
        return LEP_E_UNEXPECTED;
    }
    if (rc == LEP_OK)
        rc = lep_client_start(&s->client);
    if (rc != LEP_OK) {
        /* a port that is not there: watch for it to come back (a replug) */
        r->port_missing = rc == LEP_E_NOT_FOUND;
        lep_priv_session_disconnect(s);
        r->backoff_ms = r->backoff_ms * 2 > s->opt.reconnect_max_ms ? s->opt.reconnect_max_ms
                                                                    : r->backoff_ms * 2;
        r->next_attempt = lep_monotonic_seconds() + (double)r->backoff_ms / 1000.0;
        return rc;
    }
    lep_client_get_stats(&s->client, &base);
    pthread_mutex_lock(&s->mu);
    lep_priv_sink_reconnected(&s->sink, &base);
    lep_priv_chain_restart_filter(&s->chain);
    pthread_mutex_unlock(&s->mu);
    r->port_missing = false;
    lep_priv_session_stream_reset(s, lep_monotonic_seconds());
    return LEP_OK;
}

bool lep_priv_reconnect_wait(lep_session *s, double now, double deadline)
{
    session_reconnect *r = &s->rc;
    double wake;
    if (s->opt.reconnect_give_up_ms >= 0 &&
        now - r->down_since >= (double)s->opt.reconnect_give_up_ms / 1000.0) {
        r->failed = LEP_E_DISCONNECTED;
        return true;
    }
    /* Attempt when the backoff is over, or at once when a port that had
     * vanished is back (checked every SESSION_WATCH_S). */
    if (now < r->next_attempt && !(r->port_missing && access(s->opt.port, F_OK) == 0)) {
        wake = r->next_attempt < deadline ? r->next_attempt : deadline;
        if (r->port_missing && wake > now + SESSION_WATCH_S)
            wake = now + SESSION_WATCH_S;
        lep_priv_sleep_until_ns((int64_t)(wake * 1e9));
        return lep_monotonic_seconds() < deadline;
    }
    (void)attempt(s);
    return true;
}
