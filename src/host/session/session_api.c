/* The session's public functions in flat form (leptrino/session.h): options
 * by name, samples into caller arrays, events, health and metadata as
 * arrays of doubles, texts by key. Each fills or reads the session's own
 * structs (struct_api.h) and calls the one implementation. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "leptrino/session.h"
#include "options_priv.h"
#include "session_priv.h"

int lep_session_open(const lep_options *o, lep_session **out, char *err, size_t errlen)
{
    if (o == NULL) {
        if (out != NULL)
            *out = NULL;
        lep_priv_set_err(err, errlen, "session: no options handle given (lep_options_new)");
        return LEP_E_ARG;
    }
    return lep_session_open_so(&o->so, out, err, errlen);
}

/* ---- samples ---- */

int lep_session_read(lep_session *s, int timeout_ms, size_t cap, size_t *n, double *t_mono,
                     double *t_utc, double *si, int16_t *raw, double *zeroed, uint8_t *status,
                     uint8_t *flags, uint16_t *seq)
{
    lep_session_batch b;
    int rc;
    if (n != NULL)
        *n = 0;
    if (s == NULL || n == NULL)
        return LEP_E_ARG;
    memset(&b, 0, sizeof b);
    b.cap = cap;
    b.t_mono = t_mono;
    b.t_utc = t_utc;
    b.si = si;
    b.raw = raw;
    b.zeroed = zeroed;
    b.status = status;
    b.flags = flags;
    b.seq = seq;
    rc = lep_session_read_batch(s, &b, timeout_ms);
    *n = b.n;
    return rc;
}

int lep_session_read_one(lep_session *s, double *t_mono, double *t_utc, double *si, int16_t *raw,
                         double *zeroed, uint8_t *status, uint8_t *flags, uint16_t *seq)
{
    lep_session_batch b;
    memset(&b, 0, sizeof b);
    b.cap = 1;
    b.t_mono = t_mono;
    b.t_utc = t_utc;
    b.si = si;
    b.raw = raw;
    b.zeroed = zeroed;
    b.status = status;
    b.flags = flags;
    b.seq = seq;
    return lep_session_read_one_batch(s, &b);
}

/* ---- events ---- */

size_t lep_session_event_fields(void)
{
    return LEP_EVF_COUNT;
}

void lep_event_to_fields(const lep_session_event *ev, double f[LEP_EVF_COUNT])
{
    int k;
    f[LEP_EVF_TYPE] = ev->type;
    f[LEP_EVF_SAMPLE] = (double)ev->sample;
    f[LEP_EVF_T_MONO] = ev->t_mono;
    f[LEP_EVF_T_UTC] = ev->t_utc;
    f[LEP_EVF_GAP_FROM] = ev->gap_from;
    f[LEP_EVF_GAP_TO] = ev->gap_to;
    f[LEP_EVF_LOST] = ev->lost;
    f[LEP_EVF_ERROR] = ev->error;
    f[LEP_EVF_AXES] = ev->axes;
    f[LEP_EVF_STATUS] = ev->status;
    for (k = 0; k < LEP_AXES; k++) {
        f[LEP_EVF_TARE + k] = ev->tare[k];
        f[LEP_EVF_WRENCH + k] = ev->wrench[k];
    }
    f[LEP_EVF_ROW] = (double)ev->row;
}

void lep_event_from_fields(const double *f, lep_session_event *ev)
{
    int k;
    memset(ev, 0, sizeof *ev);
    ev->type = (int)f[LEP_EVF_TYPE];
    ev->sample = f[LEP_EVF_SAMPLE] > 0.0 ? (uint64_t)f[LEP_EVF_SAMPLE] : 0u;
    ev->t_mono = f[LEP_EVF_T_MONO];
    ev->t_utc = f[LEP_EVF_T_UTC];
    ev->gap_from = f[LEP_EVF_GAP_FROM];
    ev->gap_to = f[LEP_EVF_GAP_TO];
    ev->lost = f[LEP_EVF_LOST] > 0.0 ? (uint32_t)f[LEP_EVF_LOST] : 0u;
    ev->error = (int)f[LEP_EVF_ERROR];
    ev->axes = (uint8_t)f[LEP_EVF_AXES];
    ev->status = (uint8_t)f[LEP_EVF_STATUS];
    for (k = 0; k < LEP_AXES; k++) {
        ev->tare[k] = f[LEP_EVF_TARE + k];
        ev->wrench[k] = f[LEP_EVF_WRENCH + k];
    }
    ev->row = (int64_t)f[LEP_EVF_ROW];
}

int lep_session_next_event(lep_session *s, double *fields, size_t nfields)
{
    lep_session_event ev;
    double all[LEP_EVF_COUNT];
    if (s == NULL || fields == NULL)
        return LEP_E_ARG;
    if (!lep_session_pop_event(s, &ev))
        return 0;
    lep_event_to_fields(&ev, all);
    memcpy(fields, all, sizeof(double) * (nfields < LEP_EVF_COUNT ? nfields : LEP_EVF_COUNT));
    return 1;
}

double lep_session_stop_wait(const lep_session *s)
{
    /* one stop transaction: the first try and `retries` more, a timeout each
     * (options read at open only: no lock needed) */
    if (s == NULL)
        return 0.0;
    return ((double)s->opt.retries + 1.0) * (double)s->opt.timeout_ms / 1000.0;
}

/* ---- options of an open session ---- */

/* The session's options now, as a handle's (under the session's mutex). */
static void snapshot(lep_session *s, lep_options *o)
{
    pthread_mutex_lock(&s->mu);
    lep_priv_options_from(o, &s->opt);
    pthread_mutex_unlock(&s->mu);
    snprintf(o->port, sizeof o->port, "%s", s->port_buf);
    o->so.port = o->port;
}

/* Apply the live option r from o to s (the setter of each one). */
static int apply(lep_session *s, const opt_row *r, const lep_session_options *o, char *err,
                 size_t errlen)
{
    const char *name = r->public_name;
    int rc;
    if (strcmp(name, "lowpass") == 0) {
        rc = lep_session_set_lowpass(s, o->lowpass_hz);
        if (rc == LEP_E_VALUE)
            lep_priv_set_err(err, errlen,
                             "lowpass %g: expected 0 (off) or a cut-off up to 0.45 x the nominal "
                             "rate (%g Hz)",
                             o->lowpass_hz, 0.45 * s->nominal_hz);
        return rc;
    }
    if (strcmp(name, "rotation") == 0 || strcmp(name, "shift") == 0) {
        rc = lep_session_set_rotation(s, o->rotation, o->shift_m);
        if (rc == LEP_E_VALUE)
            lep_priv_set_err(err, errlen,
                             "rotation: not an orthonormal matrix (R R^T = I to 1e-6)");
        return rc;
    }
    if (strcmp(name, "payload") == 0)
        rc = lep_session_set_payload(s, &o->payload);
    else if (strcmp(name, "gravity") == 0)
        rc = lep_session_set_gravity(s, o->gravity);
    else if (strcmp(name, "limit") == 0)
        rc = lep_session_set_limits(s, o->limit);
    else if (strcmp(name, "latency") == 0)
        rc = lep_session_set_latency(s, o->latency_ms);
    else
        rc = LEP_E_STATE;
    if (rc == LEP_E_ARG)
        lep_priv_set_err(err, errlen, "%s: refused (a negative mass or limit)", name);
    else if (rc == LEP_E_STATE)
        lep_priv_set_err(err, errlen, "%s: not now (another thread is inside a driving call)",
                         name);
    return rc;
}

/* Set through a handle holding the session's options, then apply. */
typedef int (*handle_setter)(lep_options *o, const char *name, const void *value, size_t n,
                             char *err, size_t errlen);

static int session_set(lep_session *s, const char *name, handle_setter set, const void *value,
                       size_t n, char *err, size_t errlen)
{
    lep_options o;
    const opt_row *r;
    size_t at;
    int rc;
    if (err != NULL && errlen > 0)
        err[0] = '\0';
    if (s == NULL || name == NULL) {
        lep_priv_set_err(err, errlen, "no session or no option name given");
        return LEP_E_ARG;
    }
    r = lep_priv_options_find(NULL, name, NULL);
    if (r == NULL) {
        lep_priv_set_err(err, errlen, "unknown option '%s'", name);
        return LEP_E_ARG;
    }
    if (r->scope != LEP_SCOPE_LIVE) {
        lep_priv_set_err(err, errlen,
                         "%s: cannot change on an open session (these can: lowpass, rotation, "
                         "shift, payload, gravity, limit, latency)",
                         r->public_name);
        return LEP_E_STATE;
    }
    snapshot(s, &o);
    rc = set(&o, name, value, n, err, errlen);
    if (rc != LEP_OK)
        return rc;
    rc = apply(s, r, &o.so, err, errlen);
    if (rc != LEP_OK)
        return rc;
    /* Keep the session's copy in step, for lep_session_get ("latency" is the
     * driving thread's own field, written by its setter). */
    if (strcmp(r->public_name, "latency") == 0)
        return LEP_OK;
    at = r->offset - offsetof(struct lep_options, so);
    pthread_mutex_lock(&s->mu);
    memcpy((unsigned char *)&s->opt + at, (const unsigned char *)&o.so + at, r->size);
    pthread_mutex_unlock(&s->mu);
    return LEP_OK;
}

static int set_text(lep_options *o, const char *name, const void *v, size_t n, char *err,
                    size_t errlen)
{
    (void)n;
    return lep_options_set(o, name, (const char *)v, err, errlen);
}

static int set_int(lep_options *o, const char *name, const void *v, size_t n, char *err,
                   size_t errlen)
{
    (void)n;
    return lep_options_set_int(o, name, *(const int64_t *)v, err, errlen);
}

static int set_double(lep_options *o, const char *name, const void *v, size_t n, char *err,
                      size_t errlen)
{
    (void)n;
    return lep_options_set_double(o, name, *(const double *)v, err, errlen);
}

static int set_doubles(lep_options *o, const char *name, const void *v, size_t n, char *err,
                       size_t errlen)
{
    return lep_options_set_doubles(o, name, (const double *)v, n, err, errlen);
}

int lep_session_set(lep_session *s, const char *name, const char *value, char *err, size_t errlen)
{
    return session_set(s, name, set_text, value, 0, err, errlen);
}

int lep_session_set_int(lep_session *s, const char *name, int64_t value, char *err, size_t errlen)
{
    return session_set(s, name, set_int, &value, 1, err, errlen);
}

int lep_session_set_double(lep_session *s, const char *name, double value, char *err, size_t errlen)
{
    return session_set(s, name, set_double, &value, 1, err, errlen);
}

int lep_session_set_doubles(lep_session *s, const char *name, const double *values, size_t n,
                            char *err, size_t errlen)
{
    return session_set(s, name, set_doubles, values, n, err, errlen);
}

int lep_session_get(lep_session *s, const char *name, char *buf, size_t cap, size_t *len)
{
    lep_options o;
    if (len != NULL)
        *len = 0;
    if (s == NULL)
        return LEP_E_ARG;
    snapshot(s, &o);
    return lep_options_get(&o, name, buf, cap, len);
}

int lep_session_get_int(lep_session *s, const char *name, int64_t *out)
{
    lep_options o;
    if (s == NULL)
        return LEP_E_ARG;
    snapshot(s, &o);
    return lep_options_get_int(&o, name, out);
}

int lep_session_get_double(lep_session *s, const char *name, double *out)
{
    lep_options o;
    if (s == NULL)
        return LEP_E_ARG;
    snapshot(s, &o);
    return lep_options_get_double(&o, name, out);
}

int lep_session_get_doubles(lep_session *s, const char *name, double *out, size_t cap, size_t *n)
{
    lep_options o;
    if (n != NULL)
        *n = 0;
    if (s == NULL)
        return LEP_E_ARG;
    snapshot(s, &o);
    return lep_options_get_doubles(&o, name, out, cap, n);
}

/* ---- identity, health, metadata ---- */

static int metadata_json(lep_session *s, char *buf, size_t cap, size_t *len)
{
    char small[4096];
    size_t need = 0;
    char *big;
    int rc = lep_session_metadata_json(s, small, sizeof small, &need);
    if (rc == LEP_OK)
        return lep_priv_text_out(small, buf, cap, len);
    if (rc != LEP_E_BUFFER)
        return rc;
    big = malloc(need + 1);
    if (big == NULL)
        return LEP_E_IO;
    rc = lep_session_metadata_json(s, big, need + 1, &need);
    if (rc == LEP_OK)
        rc = lep_priv_text_out(big, buf, cap, len);
    free(big);
    return rc;
}

int lep_session_info(lep_session *s, int which, char *buf, size_t cap, size_t *len)
{
    lep_session_meta m;
    const char *text;
    if (len != NULL)
        *len = 0;
    if (s == NULL)
        return LEP_E_ARG;
    if (which == LEP_INFO_METADATA_JSON)
        return metadata_json(s, buf, cap, len);
    lep_session_get_metadata(s, &m);
    switch (which) {
    case LEP_INFO_MODEL:
        text = m.info.model;
        break;
    case LEP_INFO_SERIAL:
        text = m.info.serial;
        break;
    case LEP_INFO_FIRMWARE:
        text = m.info.firmware;
        break;
    case LEP_INFO_OUTPUT_RATE:
        text = m.info.output_rate;
        break;
    case LEP_INFO_PROTOCOL:
        text = m.protocol;
        break;
    case LEP_INFO_FILTER_LABEL:
        text = m.sensor_filter_label;
        break;
    case LEP_INFO_LOWPASS_NAME:
        text = m.lowpass_name;
        break;
    case LEP_INFO_PORT:
        text = m.port;
        break;
    case LEP_INFO_LIBRARY_VERSION:
        text = m.library_version;
        break;
    default:
        return LEP_E_ARG;
    }
    return lep_priv_text_out(text, buf, cap, len);
}

int lep_session_rated(lep_session *s, double rated[6])
{
    int k;
    if (s == NULL || rated == NULL)
        return LEP_E_ARG;
    for (k = 0; k < LEP_AXES; k++)
        rated[k] = (double)s->rated.axis[k];
    return LEP_OK;
}

static const char *const health_names[LEP_H_COUNT] = { "elapsed_s",
                                                       "nominal_hz",
                                                       "measured_hz",
                                                       "recent_hz",
                                                       "shortfall",
                                                       "received",
                                                       "delivered",
                                                       "lost",
                                                       "gaps",
                                                       "errors",
                                                       "overloads",
                                                       "limit_episodes",
                                                       "disconnects",
                                                       "reconnects",
                                                       "events_dropped",
                                                       "max_gap_s",
                                                       "messages",
                                                       "bcc_errors",
                                                       "frame_errors",
                                                       "bytes_discarded",
                                                       "naks",
                                                       "retries",
                                                       "unexpected",
                                                       "invalid",
                                                       "timeouts",
                                                       "samples",
                                                       "resent_after_timeout",
                                                       "resent_confirmed",
                                                       "recoveries",
                                                       "reserved_nonzero",
                                                       "stalls" };

size_t lep_session_health_fields(void)
{
    return LEP_H_COUNT;
}

const char *lep_session_health_field_name(size_t i)
{
    return i < LEP_H_COUNT ? health_names[i] : NULL;
}

int lep_session_health(lep_session *s, double *out, size_t n)
{
    lep_session_health_info h;
    double f[LEP_H_COUNT];
    if (s == NULL || (out == NULL && n > 0))
        return LEP_E_ARG;
    lep_session_get_health(s, &h);
    f[LEP_H_ELAPSED_S] = h.elapsed_s;
    f[LEP_H_NOMINAL_HZ] = h.nominal_hz;
    f[LEP_H_MEASURED_HZ] = h.measured_hz;
    f[LEP_H_RECENT_HZ] = h.recent_hz;
    f[LEP_H_SHORTFALL] = h.shortfall ? 1.0 : 0.0;
    f[LEP_H_RECEIVED] = (double)h.received;
    f[LEP_H_DELIVERED] = (double)h.delivered;
    f[LEP_H_LOST] = (double)h.lost;
    f[LEP_H_GAPS] = (double)h.gaps;
    f[LEP_H_ERRORS] = (double)h.errors;
    f[LEP_H_OVERLOADS] = (double)h.overloads;
    f[LEP_H_LIMIT_EPISODES] = (double)h.limit_episodes;
    f[LEP_H_DISCONNECTS] = (double)h.disconnects;
    f[LEP_H_RECONNECTS] = (double)h.reconnects;
    f[LEP_H_EVENTS_DROPPED] = (double)h.events_dropped;
    f[LEP_H_MAX_GAP_S] = h.max_gap_s;
    f[LEP_H_MESSAGES] = h.client.messages;
    f[LEP_H_BCC_ERRORS] = h.client.bcc_errors;
    f[LEP_H_FRAME_ERRORS] = h.client.frame_errors;
    f[LEP_H_BYTES_DISCARDED] = h.client.bytes_discarded;
    f[LEP_H_NAKS] = h.client.naks;
    f[LEP_H_RETRIES] = h.client.retries;
    f[LEP_H_UNEXPECTED] = h.client.unexpected;
    f[LEP_H_INVALID] = h.client.invalid;
    f[LEP_H_TIMEOUTS] = h.client.timeouts;
    f[LEP_H_SAMPLES] = h.client.samples;
    f[LEP_H_RESENT_AFTER_TIMEOUT] = h.client.resent_after_timeout;
    f[LEP_H_RESENT_CONFIRMED] = h.client.resent_confirmed;
    f[LEP_H_RECOVERIES] = h.client.recoveries;
    f[LEP_H_RESERVED_NONZERO] = h.client.reserved_nonzero;
    f[LEP_H_STALLS] = h.client.stalls;
    memcpy(out, f, sizeof(double) * (n < LEP_H_COUNT ? n : LEP_H_COUNT));
    return LEP_OK;
}

size_t lep_session_metadata_fields(void)
{
    return LEP_MD_COUNT;
}

int lep_session_metadata(lep_session *s, double *out, size_t n)
{
    lep_session_meta m;
    double f[LEP_MD_COUNT];
    int k;
    if (s == NULL || (out == NULL && n > 0))
        return LEP_E_ARG;
    lep_session_get_metadata(s, &m);
    for (k = 0; k < LEP_AXES; k++) {
        f[LEP_MD_RATED + k] = (double)m.rated.axis[k];
        f[LEP_MD_TARE + k] = m.tare[k];
        f[LEP_MD_LIMIT + k] = m.limit[k];
    }
    f[LEP_MD_OUTPUT_RATE_HZ] = m.info.output_rate_hz;
    f[LEP_MD_SENSOR_FILTER] = m.sensor_filter;
    f[LEP_MD_NOMINAL_HZ] = m.nominal_hz;
    f[LEP_MD_LOWPASS_HZ] = m.lowpass_hz;
    f[LEP_MD_LOWPASS_DELAY_S] = m.lowpass_delay_s;
    f[LEP_MD_DECIMATE] = m.decimate;
    for (k = 0; k < 9; k++)
        f[LEP_MD_ROTATION + k] = m.rotation[k];
    for (k = 0; k < 3; k++) {
        f[LEP_MD_SHIFT_M + k] = m.shift_m[k];
        f[LEP_MD_PAYLOAD + 1 + k] = m.payload.com_m[k];
        f[LEP_MD_GRAVITY + k] = m.gravity[k];
    }
    f[LEP_MD_PAYLOAD] = m.payload.mass_kg;
    f[LEP_MD_TARED] = m.tared ? 1.0 : 0.0;
    f[LEP_MD_START_UTC] = m.start_utc;
    f[LEP_MD_START_MONO] = m.start_mono;
    f[LEP_MD_SIM] = m.sim ? 1.0 : 0.0;
    f[LEP_MD_OUTPUT_RATE_FIELD] = m.info.has_output_rate ? 1.0 : 0.0;
    memcpy(out, f, sizeof(double) * (n < LEP_MD_COUNT ? n : LEP_MD_COUNT));
    return LEP_OK;
}

int lep_session_serial_info(lep_session *s, int *out, size_t n)
{
    lep_serial_info si;
    int f[LEP_SERIAL_INFO_COUNT];
    int rc;
    if (s == NULL || (out == NULL && n > 0))
        return LEP_E_ARG;
    rc = lep_session_get_serial_info(s, &si);
    f[LEP_SERIAL_LOW_LATENCY] = si.low_latency ? 1 : 0;
    f[LEP_SERIAL_FTDI_LATENCY_MS] = si.ftdi_latency_ms;
    f[LEP_SERIAL_FTDI_LOWERED] = si.ftdi_lowered ? 1 : 0;
    if (rc != LEP_OK)
        memset(f, 0, sizeof f);
    memcpy(out, f, sizeof(int) * (n < LEP_SERIAL_INFO_COUNT ? n : LEP_SERIAL_INFO_COUNT));
    return rc;
}
