/* Host session, the load on the sensor: the payload's gravity wrench removed
 * from the SI values (leptrino/payload.h, the one implementation of the
 * model), and per-axis limits on what is left, with their episodes: the
 * chain's part (session_chain.h); its events go into the sink it is given. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "struct_api.h"
#include "session_chain.h"

/* A limit episode ends when every axis is back within this share of its limit. */
#define LIMIT_CLEAR 0.95

static const char *const axis_name[LEP_AXES] = { "fx", "fy", "fz", "mx", "my", "mz" };

static bool limits_ok(const double limit[LEP_AXES], int *bad)
{
    int k;
    for (k = 0; k < LEP_AXES; k++) {
        if (!isfinite(limit[k]) || limit[k] < 0.0) {
            *bad = k;
            return false;
        }
    }
    return true;
}

int lep_priv_load_check(const lep_session_options *o, char *err, size_t errlen)
{
    double w[LEP_AXES];
    int bad = 0;
    if (lep_payload_wrench_p(&o->payload, o->gravity, w) != LEP_OK) {
        lep_priv_set_err(err, errlen,
                         "session: payload (mass %g kg, com %g %g %g m) or gravity (%g %g %g): "
                         "a mass >= 0 and finite numbers expected",
                         o->payload.mass_kg, o->payload.com_m[0], o->payload.com_m[1],
                         o->payload.com_m[2], o->gravity[0], o->gravity[1], o->gravity[2]);
        return LEP_E_ARG;
    }
    if (!limits_ok(o->limit, &bad)) {
        lep_priv_set_err(err, errlen, "session: limit %s %g: must be 0 (none) or > 0",
                         axis_name[bad], o->limit[bad]);
        return LEP_E_ARG;
    }
    return LEP_OK;
}

void lep_priv_load_init(session_load *l, const lep_session_options *o)
{
    memset(l, 0, sizeof *l);
    l->payload = o->payload;
    memcpy(l->gravity, o->gravity, sizeof l->gravity);
    memcpy(l->limit, o->limit, sizeof l->limit);
    (void)lep_payload_wrench_p(&l->payload, l->gravity, l->wrench); /* checked at open */
}

void lep_priv_load_start(session_load *l)
{
    l->beyond = false;
}

void lep_priv_load_compensate(const session_load *l, double si[LEP_AXES])
{
    int k;
    for (k = 0; k < LEP_AXES; k++)
        si[k] -= l->wrench[k];
}

void lep_priv_load_counts(const session_load *l, const lep_rated *rated, double counts[LEP_AXES])
{
    int k;
    for (k = 0; k < LEP_AXES; k++)
        counts[k] = l->wrench[k] * (double)LEP_RAW_FULL_SCALE / (double)rated->axis[k];
}

uint8_t lep_priv_load_limits(session_load *l, session_sink *sk, const double si[LEP_AXES], double t,
                             uint64_t sample)
{
    uint8_t axes = 0, near = 0;
    int k;
    for (k = 0; k < LEP_AXES; k++) {
        double a = fabs(si[k]);
        if (l->limit[k] <= 0.0)
            continue;
        if (a > l->limit[k])
            axes |= (uint8_t)(1u << k);
        if (a > LIMIT_CLEAR * l->limit[k])
            near |= (uint8_t)(1u << k);
    }
    if (axes != 0u ? !l->beyond : (l->beyond && near == 0u)) {
        lep_session_event ev;
        l->beyond = axes != 0u;
        lep_priv_event_init(&ev, l->beyond ? LEP_EV_LIMIT_EXCEEDED : LEP_EV_LIMIT_CLEARED, sample,
                            t);
        ev.axes = axes;
        memcpy(ev.wrench, si, sizeof ev.wrench);
        lep_priv_sink_event(sk, &ev); /* counts an episode begun */
    }
    return axes != 0u ? LEP_SF_LIMIT : 0u;
}

int lep_limits_parse(const char *text, double limit[LEP_AXES])
{
    double v[LEP_AXES] = { 0 };
    int rc;
    if (limit == NULL)
        return LEP_E_ARG;
    rc = lep_limits_add(text, v);
    if (rc == LEP_OK)
        memcpy(limit, v, sizeof v);
    return rc;
}

int lep_limits_add(const char *text, double limit[LEP_AXES])
{
    double v[LEP_AXES];
    const char *p = text;
    int k;
    if (text == NULL || limit == NULL)
        return LEP_E_ARG;
    for (k = 0; k < LEP_AXES; k++)
        if (!isfinite(limit[k]) || limit[k] < 0.0)
            return LEP_E_ARG;
    memcpy(v, limit, sizeof v);
    for (;;) {
        char *end;
        int axis = -1;
        for (k = 0; k < LEP_AXES; k++)
            if (strncmp(p, axis_name[k], 2) == 0 && p[2] == '=')
                axis = k;
        if (axis < 0 || v[axis] > 0.0) /* unknown, or limited twice: which would the user mean? */
            return LEP_E_ARG;
        errno = 0;
        v[axis] = strtod(p + 3, &end);
        if (end == p + 3 || errno == ERANGE || !isfinite(v[axis]) || !(v[axis] > 0.0))
            return LEP_E_ARG;
        if (*end == '\0')
            break;
        if (*end != ',')
            return LEP_E_ARG;
        p = end + 1;
    }
    memcpy(limit, v, sizeof v);
    return LEP_OK;
}

/* ---- the setters ---- */

int lep_priv_chain_set_payload(session_chain *ch, const lep_payload *p)
{
    session_load *l = &ch->load;
    static const lep_payload none = { 0.0, { 0.0, 0.0, 0.0 } };
    double w[LEP_AXES];
    if (p == NULL)
        p = &none;
    if (lep_payload_wrench_p(p, l->gravity, w) != LEP_OK)
        return LEP_E_ARG;
    l->payload = *p;
    memcpy(l->wrench, w, sizeof w);
    return LEP_OK;
}

int lep_priv_chain_set_gravity(session_chain *ch, const double gravity[3])
{
    session_load *l = &ch->load;
    double w[LEP_AXES];
    if (lep_payload_wrench_p(&l->payload, gravity, w) != LEP_OK)
        return LEP_E_ARG;
    memcpy(l->gravity, gravity, sizeof l->gravity);
    memcpy(l->wrench, w, sizeof w);
    return LEP_OK;
}

int lep_priv_chain_set_limits(session_chain *ch, const double limit[LEP_AXES])
{
    session_load *l = &ch->load;
    static const double none[LEP_AXES] = { 0 };
    int bad;
    if (limit == NULL)
        limit = none;
    if (!limits_ok(limit, &bad))
        return LEP_E_ARG;
    memcpy(l->limit, limit, sizeof l->limit);
    return LEP_OK;
}

void lep_priv_load_meta(const session_load *l, lep_session_meta *out)
{
    out->payload = l->payload;
    memcpy(out->gravity, l->gravity, sizeof out->gravity);
    memcpy(out->limit, l->limit, sizeof out->limit);
}
