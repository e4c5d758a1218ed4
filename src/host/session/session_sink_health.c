/* Host session, the sink's health counters (session_sink.h): samples
 * received and their rate, gaps, losses, errors over every connection.
 * [mu] held by the callers. */
#include <string.h>

#include "leptrino/error.h"
#include "session_sink.h"

static uint64_t conn_errors(const lep_client_stats *now, const lep_client_stats *base)
{
    return (uint64_t)(uint32_t)(now->bcc_errors - base->bcc_errors) +
           (uint32_t)(now->frame_errors - base->frame_errors) +
           (uint32_t)(now->invalid - base->invalid);
}

void lep_priv_health_start(session_health_state *hs, double nominal_hz,
                           const lep_client_stats *base)
{
    memset(hs, 0, sizeof *hs);
    hs->h.nominal_hz = nominal_hz;
    hs->base_stats = *base;
}

void lep_priv_health_client(session_health_state *hs, const lep_client_stats *st)
{
    hs->h.client = *st;
    hs->h.errors = hs->errors_before + conn_errors(st, &hs->base_stats) + hs->data_timeouts;
}

void lep_priv_health_sample(session_health_state *hs, double t)
{
    lep_session_health_info *h = &hs->h;
    h->received++;
    if (h->received == 1) {
        hs->first_t = t;
        hs->window_t = t;
        hs->window_n = 1;
    }
    h->elapsed_s = t - hs->first_t;
    if (h->elapsed_s > 0.0)
        h->measured_hz = (double)(h->received - 1u) / h->elapsed_s;
    if (t - hs->window_t >= 1.0) {
        h->recent_hz = (double)(h->received - hs->window_n) / (t - hs->window_t);
        hs->window_t = t;
        hs->window_n = h->received;
    } else if (hs->window_n == 1u) {
        h->recent_hz = h->measured_hz; /* the first second: the run so far, not 0 */
    }
    h->shortfall = h->elapsed_s >= 1.0 && h->measured_hz < 0.98 * h->nominal_hz;
}

void lep_priv_health_gap(session_health_state *hs, double from, double to, uint32_t lost)
{
    hs->h.gaps++;
    hs->h.lost += lost;
    if (to - from > hs->h.max_gap_s)
        hs->h.max_gap_s = to - from;
}

void lep_priv_health_lost(session_health_state *hs, const lep_client_stats *st, int error)
{
    hs->h.disconnects++;
    if (error == LEP_E_TIMEOUT)
        hs->data_timeouts++;
    hs->errors_before += conn_errors(st, &hs->base_stats);
    hs->base_stats = *st;
    hs->h.errors = hs->errors_before + hs->data_timeouts;
}

void lep_priv_health_reconnected(session_health_state *hs, const lep_client_stats *base)
{
    hs->base_stats = *base;
    hs->h.reconnects++;
}
