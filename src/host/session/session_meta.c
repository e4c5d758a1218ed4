/* Host session, what a recording says about itself: the metadata struct and
 * the one JSON object every front end writes. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "leptrino/error.h"
#include "leptrino/leptrino.h"
#include "session_priv.h"

/* Copy src into dst[0..cap), truncating, always terminated. */
static void copy_str(char *dst, size_t cap, const char *src)
{
    size_t n = strlen(src);
    if (n >= cap)
        n = cap - 1u;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

void lep_session_get_metadata(lep_session *s, lep_session_meta *out)
{
    if (out == NULL)
        return;
    memset(out, 0, sizeof *out);
    if (s == NULL)
        return;
    pthread_mutex_lock(&s->mu);
    out->info = s->info; /* a reconnect may renew it */
    pthread_mutex_unlock(&s->mu);
    copy_str(out->protocol, sizeof out->protocol,
             out->info.has_output_rate ? "rate field (38-byte)" : "v1.13 (32-byte info)");
    out->rated = s->rated;
    out->sensor_filter = s->sensor_filter;
    copy_str(out->sensor_filter_label, sizeof out->sensor_filter_label,
             s->sensor_filter < 0 ? "not supported by sensor"
                                  : lep_filter_label((uint8_t)s->sensor_filter));
    out->nominal_hz = s->nominal_hz;
    copy_str(out->port, sizeof out->port, s->port_buf);
    out->sim = s->sim != NULL;
    copy_str(out->library_version, sizeof out->library_version, lep_version());
    pthread_mutex_lock(&s->mu);
    lep_priv_chain_meta(&s->chain, out);
    out->start_utc = s->start_utc;
    out->start_mono = s->start_mono;
    pthread_mutex_unlock(&s->mu);
}

/* ---- JSON ---- */

typedef struct jbuf {
    char *p;
    size_t cap, len;
    bool over;
} jbuf;

static void jput(jbuf *j, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void jput(jbuf *j, const char *fmt, ...)
{
    va_list ap;
    int n;
    size_t room = j->len < j->cap ? j->cap - j->len : 0;
    va_start(ap, fmt);
    n = vsnprintf(room > 0 ? j->p + j->len : NULL, room, fmt, ap);
    va_end(ap);
    if (n < 0) {
        j->over = true;
        return;
    }
    if ((size_t)n >= room)
        j->over = true;
    j->len += (size_t)n;
}

/* A JSON string: quotes, backslashes and control characters escaped. */
static void jstr(jbuf *j, const char *s)
{
    jput(j, "\"");
    for (; *s != '\0'; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            jput(j, "\\%c", c);
        else if (c < 0x20u)
            jput(j, "\\u%04x", c);
        else
            jput(j, "%c", c);
    }
    jput(j, "\"");
}

/* The shortest of 15, 16 or 17 significant digits that reads back as the
 * same double. */
static void jnum(jbuf *j, double v)
{
    char t[40];
    int digits;
    if (!isfinite(v)) {
        jput(j, "null");
        return;
    }
    for (digits = 15; digits < 17; digits++) {
        snprintf(t, sizeof t, "%.*g", digits, v);
        if (strtod(t, NULL) == v)
            break;
    }
    jput(j, "%.*g", digits, v);
}

static void jarr(jbuf *j, const double *v, size_t n)
{
    size_t i;
    jput(j, "[");
    for (i = 0; i < n; i++) {
        if (i > 0)
            jput(j, ",");
        jnum(j, v[i]);
    }
    jput(j, "]");
}

/* "2026-11-22T22:47:08.123456Z" */
static void iso8601(double utc, char *out, size_t cap)
{
    time_t sec = (time_t)floor(utc);
    long usec = (long)floor((utc - floor(utc)) * 1e6 + 0.5);
    struct tm tm;
    if (usec >= 1000000L) {
        sec++;
        usec -= 1000000L;
    }
    if (utc <= 0.0 || gmtime_r(&sec, &tm) == NULL) {
        snprintf(out, cap, "%s", "");
        return;
    }
    snprintf(out, cap, "%04d-%02d-%02dT%02d:%02d:%02d.%06ldZ", tm.tm_year + 1900, tm.tm_mon + 1,
             tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, usec);
}

int lep_session_metadata_json(lep_session *s, char *buf, size_t cap, size_t *len)
{
    static const char *const rated_names[LEP_AXES] = { "fx_N",  "fy_N",  "fz_N",
                                                       "mx_Nm", "my_Nm", "mz_Nm" };
    lep_session_meta m;
    jbuf j;
    char iso[96];
    int k;

    if (len != NULL)
        *len = 0;
    if (s == NULL || (buf == NULL && cap > 0))
        return LEP_E_ARG;
    lep_session_get_metadata(s, &m);
    j.p = buf;
    j.cap = cap;
    j.len = 0;
    j.over = false;
    jput(&j, "{\"library_version\":");
    jstr(&j, m.library_version);
    jput(&j, ",\"model\":");
    jstr(&j, m.info.model);
    jput(&j, ",\"serial\":");
    jstr(&j, m.info.serial);
    jput(&j, ",\"firmware\":");
    jstr(&j, m.info.firmware);
    jput(&j, ",\"protocol\":");
    jstr(&j, m.protocol);
    jput(&j, ",\"output_rate\":");
    jstr(&j, m.info.output_rate);
    jput(&j, ",\"nominal_hz\":");
    jnum(&j, m.nominal_hz);
    jput(&j, ",\"rated\":{");
    for (k = 0; k < LEP_AXES; k++) {
        /* float values: 9 significant digits give the float back */
        jput(&j, "%s\"%s\":%.9g", k > 0 ? "," : "", rated_names[k], (double)m.rated.axis[k]);
    }
    jput(&j, "},\"sensor_filter\":%d,\"sensor_filter_label\":", m.sensor_filter);
    jstr(&j, m.sensor_filter_label);
    jput(&j, ",\"host_lowpass_hz\":");
    jnum(&j, m.lowpass_hz);
    jput(&j, ",\"host_lowpass\":");
    jstr(&j, m.lowpass_name);
    jput(&j, ",\"host_lowpass_delay_s\":");
    jnum(&j, m.lowpass_delay_s);
    jput(&j, ",\"decimate\":%u,\"rotation\":", m.decimate);
    jarr(&j, m.rotation, 9);
    jput(&j, ",\"shift_m\":");
    jarr(&j, m.shift_m, 3);
    jput(&j, ",\"tared\":%s,\"tare_counts\":", m.tared ? "true" : "false");
    jarr(&j, m.tare, LEP_AXES);
    if (m.payload.mass_kg > 0.0) {
        jput(&j, ",\"payload\":{\"mass_kg\":");
        jnum(&j, m.payload.mass_kg);
        jput(&j, ",\"com_m\":");
        jarr(&j, m.payload.com_m, 3);
        jput(&j, "}");
    } else {
        jput(&j, ",\"payload\":null");
    }
    jput(&j, ",\"gravity\":");
    jarr(&j, m.gravity, 3);
    jput(&j, ",\"limit\":");
    jarr(&j, m.limit, LEP_AXES);
    iso8601(m.start_utc, iso, sizeof iso);
    jput(&j, ",\"start_utc\":");
    jnum(&j, m.start_utc);
    jput(&j, ",\"start_utc_iso\":");
    jstr(&j, iso);
    jput(&j, ",\"port\":");
    jstr(&j, m.port);
    jput(&j, ",\"sim\":%s}", m.sim ? "true" : "false");
    if (len != NULL)
        *len = j.len; /* the room needed, also when it did not fit */
    if (j.over) {
        if (cap > 0)
            buf[0] = '\0';
        return LEP_E_BUFFER;
    }
    return LEP_OK;
}
