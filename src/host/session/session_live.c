/* Host session, the any-thread calls (leptrino/session.h, struct_api.h):
 * each takes the session's mutex and asks the unit that owns the state. */
#include <math.h>
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

/* ---- the processing chain's settings ---- */

int lep_session_set_lowpass(lep_session *s, double cutoff_hz)
{
    int rc;
    if (s == NULL)
        return LEP_E_ARG;
    pthread_mutex_lock(&s->mu);
    rc = lep_priv_chain_set_lowpass(&s->chain, cutoff_hz, s->nominal_hz);
    pthread_mutex_unlock(&s->mu);
    return rc;
}

int lep_session_set_rotation(lep_session *s, const double rotation[9], const double shift_m[3])
{
    int rc;
    if (s == NULL)
        return LEP_E_ARG;
    pthread_mutex_lock(&s->mu);
    rc = lep_priv_chain_set_rotation(&s->chain, rotation, shift_m);
    pthread_mutex_unlock(&s->mu);
    return rc;
}

int lep_session_tare(lep_session *s, int samples, double duration_s)
{
    if (s == NULL || samples < 0 || !isfinite(duration_s) || duration_s < 0.0 ||
        (samples == 0 && duration_s <= 0.0))
        return LEP_E_ARG;
    pthread_mutex_lock(&s->mu);
    lep_priv_chain_tare(&s->chain, (unsigned)samples, duration_s);
    pthread_mutex_unlock(&s->mu);
    return LEP_OK;
}

/* offset NULL: untare. */
static int set_tare(lep_session *s, const double *offset)
{
    pthread_mutex_lock(&s->mu);
    lep_priv_chain_set_tare(&s->chain, &s->sink, offset, lep_monotonic_seconds(),
                            lep_priv_sink_processed(&s->sink));
    pthread_mutex_unlock(&s->mu);
    return LEP_OK;
}

int lep_session_untare(lep_session *s)
{
    if (s == NULL)
        return LEP_E_ARG;
    return set_tare(s, NULL);
}

int lep_session_set_tare(lep_session *s, const double offset[LEP_AXES])
{
    int k;
    if (s == NULL || offset == NULL)
        return LEP_E_ARG;
    for (k = 0; k < LEP_AXES; k++)
        if (!isfinite(offset[k]))
            return LEP_E_ARG;
    return set_tare(s, offset);
}

int lep_session_get_tare(lep_session *s, double offset[LEP_AXES])
{
    bool tared;
    if (s == NULL) {
        if (offset != NULL)
            memset(offset, 0, sizeof(double) * LEP_AXES);
        return LEP_E_ARG;
    }
    pthread_mutex_lock(&s->mu);
    tared = lep_priv_chain_tared(&s->chain, offset);
    pthread_mutex_unlock(&s->mu);
    return tared ? 1 : 0;
}

int lep_session_taring(lep_session *s)
{
    bool taring;
    if (s == NULL)
        return 0;
    pthread_mutex_lock(&s->mu);
    taring = lep_priv_chain_taring(&s->chain);
    pthread_mutex_unlock(&s->mu);
    return taring ? 1 : 0;
}

int lep_session_set_payload(lep_session *s, const lep_payload *p)
{
    int rc;
    if (s == NULL)
        return LEP_E_ARG;
    pthread_mutex_lock(&s->mu);
    rc = lep_priv_chain_set_payload(&s->chain, p);
    pthread_mutex_unlock(&s->mu);
    return rc;
}

int lep_session_set_gravity(lep_session *s, const double gravity[3])
{
    int rc;
    if (s == NULL || gravity == NULL)
        return LEP_E_ARG;
    pthread_mutex_lock(&s->mu);
    rc = lep_priv_chain_set_gravity(&s->chain, gravity);
    pthread_mutex_unlock(&s->mu);
    return rc;
}

int lep_session_set_limits(lep_session *s, const double limit[LEP_AXES])
{
    int rc;
    if (s == NULL)
        return LEP_E_ARG;
    pthread_mutex_lock(&s->mu);
    rc = lep_priv_chain_set_limits(&s->chain, limit);
    pthread_mutex_unlock(&s->mu);
    return rc;
}
