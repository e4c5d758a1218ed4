/* Host session: options, open (port or virtual sensor, start-up recovery,
 * identity, rated values, filter), start, stop, close, and the accessors.
 * The lifecycle of the units (session_priv.h): it makes them, starts and
 * stops them, and none calls it. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "options_priv.h"
#include "session_priv.h"
#include "session_tap.h"

void lep_session_options_init(lep_session_options *o)
{
    if (o == NULL)
        return;
    memset(o, 0, sizeof *o);
    lep_sim_options_init(&o->sim);
    o->timeout_ms = 500;
    o->sync_quiet_ms = 30;
    o->data_timeout_ms = 2000;
    o->gap_periods = 3.0;
    o->nominal_hz = 0.0;
    o->reconnect_min_ms = 100;
    o->reconnect_max_ms = 1000;
    o->reconnect_give_up_ms = -1;
    o->decimate = 1;
    o->retries = LEP_CLIENT_DEFAULT_RETRIES;
    o->rotation[0] = o->rotation[4] = o->rotation[8] = 1.0;
    o->gravity[2] = -LEP_STANDARD_GRAVITY;
}

static bool finite_nonneg(double v)
{
    return isfinite(v) && v >= 0.0;
}

/* Options that make no sense are refused before anything is opened. */
static int check_options(const lep_session_options *o, char *err, size_t errlen)
{
    if (!o->use_sim && (o->port == NULL || o->port[0] == '\0')) {
        lep_priv_set_err(err, errlen, "session: no port given (a serial device, or use_sim)");
        return LEP_E_ARG;
    }
    if (!o->use_sim && strlen(o->port) >= sizeof(((lep_session *)0)->port_buf)) {
        lep_priv_set_err(err, errlen, "session: port path longer than 255 bytes");
        return LEP_E_ARG;
    }
    return lep_priv_session_options_check(o, err, errlen);
}

int lep_priv_session_options_check(const lep_session_options *o, char *err, size_t errlen)
{
    if (o->timeout_ms <= 0 || o->data_timeout_ms <= 0 || o->sync_quiet_ms < 0) {
        lep_priv_set_err(err, errlen,
                         "session: timeout_ms and data_timeout_ms must be > 0, sync_quiet_ms >= 0");
        return LEP_E_ARG;
    }
    if (!isfinite(o->gap_periods) || o->gap_periods < 1.0) {
        lep_priv_set_err(err, errlen, "session: gap_periods must be >= 1 (got %g)", o->gap_periods);
        return LEP_E_ARG;
    }
    if (!finite_nonneg(o->nominal_hz) || o->nominal_hz > 100000.0) {
        lep_priv_set_err(err, errlen, "session: nominal_hz must be 0 (auto) or a rate in Hz");
        return LEP_E_ARG;
    }
    if (o->reconnect_min_ms <= 0 || o->reconnect_max_ms < o->reconnect_min_ms) {
        lep_priv_set_err(
            err, errlen,
            "session: reconnect backoff needs 0 < reconnect_min_ms <= reconnect_max_ms");
        return LEP_E_ARG;
    }
    if (o->latency_ms < 0 || o->latency_ms > 10000) {
        lep_priv_set_err(err, errlen, "session: latency_ms must be 0..10000 (got %d)",
                         o->latency_ms);
        return LEP_E_ARG;
    }
    if (o->retries < 0 || o->retries > 255) {
        lep_priv_set_err(err, errlen, "session: retries must be 0..255 (got %d)", o->retries);
        return LEP_E_ARG;
    }
    if (o->decimate == 0) {
        lep_priv_set_err(err, errlen, "session: decimate must be >= 1");
        return LEP_E_ARG;
    }
    /* name the option that is wrong, and its value, not a list of suspects */
    if (!finite_nonneg(o->lowpass_hz)) {
        lep_priv_set_err(err, errlen,
                         "session: lowpass_hz %g: must be 0 (off) or a cut-off in Hz > 0",
                         o->lowpass_hz);
        return LEP_E_ARG;
    }
    if (!finite_nonneg(o->duration_s)) {
        lep_priv_set_err(err, errlen, "session: duration_s %g: must be 0 (none) or seconds > 0",
                         o->duration_s);
        return LEP_E_ARG;
    }
    return lep_priv_load_check(o, err, errlen);
}

/* Saturation magnitude: v1.13 firmware (and earlier) clips at 32000, later
 * firmware is reported to clip at 15000 (spec 6.1). */
static int16_t saturation_for(const char *firmware)
{
    int major = 0, minor = 0;
    if (sscanf(firmware, "%d.%d", &major, &minor) == 2 && (major > 1 || (major == 1 && minor > 13)))
        return LEP_SATURATION_LATER;
    return LEP_SATURATION_V113;
}

static int read_identity(lep_session *s, char *err, size_t errlen)
{
    uint8_t code = 0;
    lep_client *c = lep_priv_reader_client(&s->rd); /* a handshake: the stream is not running */
    int rc = lep_client_rated(c, &s->rated);
    if (rc != LEP_OK) {
        lep_priv_set_err(err, errlen, "%s: rated values: %s", s->opt.port, lep_strerror(rc));
        return rc;
    }
    /* Some sensors refuse the filter query, or never answer it: not an error. */
    rc = lep_client_filter_get(c, &code);
    s->sensor_filter = rc == LEP_OK ? (int)code : -1;
    if (rc == LEP_E_DISCONNECTED) {
        lep_priv_set_err(err, errlen, "%s: filter query: %s", s->opt.port, lep_strerror(rc));
        return rc;
    }
    if (s->opt.nominal_hz > 0.0)
        s->nominal_hz = s->opt.nominal_hz;
    else if (s->info.has_output_rate && s->info.output_rate_hz > 0)
        s->nominal_hz = (double)s->info.output_rate_hz;
    else if (s->sim != NULL)
        s->nominal_hz = s->opt.sim.rate_hz; /* the virtual sensor's rate is known */
    else
        s->nominal_hz = LEP_SESSION_NOMINAL_HZ;
    s->period_s = 1.0 / s->nominal_hz;
    s->saturation = saturation_for(s->info.firmware);
    lep_priv_reader_set_rate(&s->rd, s->nominal_hz);
    return LEP_OK;
}

int lep_session_open_so(const lep_session_options *o, lep_session **out, char *err, size_t errlen)
{
    lep_session *s;
    int rc;
    char warning[256] = ""; /* the virtual sensor's, given back on success */

    if (out != NULL)
        *out = NULL;
    if (o == NULL || out == NULL) {
        lep_priv_set_err(err, errlen, "session: NULL options or result pointer");
        return LEP_E_ARG;
    }
    rc = check_options(o, err, errlen);
    if (rc != LEP_OK)
        return rc;
    s = calloc(1, sizeof *s);
    if (s == NULL) {
        lep_priv_set_err(err, errlen, "session: out of memory");
        return LEP_E_IO;
    }
    lep_priv_sink_open(&s->sink); /* not streaming: events go as they come */
    if (pthread_mutex_init(&s->mu, NULL) != 0) {
        free(s);
        lep_priv_set_err(err, errlen, "session: cannot create a mutex");
        return LEP_E_IO;
    }
    if (lep_priv_guard_init(&s->guard) != LEP_OK) {
        pthread_mutex_destroy(&s->mu);
        free(s);
        lep_priv_set_err(err, errlen, "session: cannot create a mutex");
        return LEP_E_IO;
    }
    s->opt = *o;
    s->sensor_filter = -1;
    if (o->use_sim) {
        lep_sim_options so = o->sim;
        if (o->reconnect && so.reopen_after_ms >= 0 && so.link[0] == '\0') {
            /* The port must come back under the same name: make up a link. */
            const char *dir = getenv("TMPDIR");
            if (dir == NULL || dir[0] == '\0' || strlen(dir) > 64)
                dir = "/tmp";
            snprintf(s->link_buf, sizeof s->link_buf, "%s/leptrino-sim-%ld-%lx", dir,
                     (long)getpid(), (unsigned long)(uintptr_t)s);
            snprintf(so.link, sizeof so.link, "%s", s->link_buf);
        }
        rc = lep_sim_start_so(&so, &s->sim, err, errlen);
        if (rc != LEP_OK) {
            s->sim = NULL;
            lep_session_close(s);
            return rc;
        }
        if (err != NULL && errlen > 0)
            snprintf(warning, sizeof warning, "%s", err);
        snprintf(s->port_buf, sizeof s->port_buf, "%s", lep_sim_port(s->sim));
    } else {
        snprintf(s->port_buf, sizeof s->port_buf, "%s", o->port);
    }
    /* The copy must not point into the caller's memory (the sim options own
     * their strings since they became arrays). */
    s->opt.port = s->port_buf;

    {
        reader_config rcfg;
        lep_product_info info;
        memset(&rcfg, 0, sizeof rcfg);
        rcfg.port = s->port_buf;
        rcfg.timeout_ms = o->timeout_ms;
        rcfg.retries = o->retries;
        rcfg.sync_quiet_ms = o->sync_quiet_ms;
        rcfg.data_timeout_ms = o->data_timeout_ms;
        rcfg.reconnect = o->reconnect;
        rcfg.reconnect_min_ms = o->reconnect_min_ms;
        rcfg.reconnect_max_ms = o->reconnect_max_ms;
        rcfg.reconnect_give_up_ms = o->reconnect_give_up_ms;
        lep_priv_reader_init(&s->rd, &rcfg);
        rc = lep_priv_reader_connect(&s->rd, &info, err, errlen);
        if (rc == LEP_OK) {
            pthread_mutex_lock(&s->mu); /* the metadata may be read from another thread */
            s->info = info;
            pthread_mutex_unlock(&s->mu);
            rc = read_identity(s, err, errlen);
        }
    }
    if (rc != LEP_OK) {
        lep_session_close(s);
        return rc;
    }
    /* Until a stream starts, the metadata's start is the open (a handshake
     * read, `leptrino read`, says when it was taken). */
    s->start_mono = lep_monotonic_seconds();
    s->start_utc = s->start_mono + lep_priv_utc_offset();
    {
        session_chain_config cc;
        memset(&cc, 0, sizeof cc);
        cc.rated = s->rated;
        cc.saturation = s->saturation;
        cc.tare_samples = o->tare_samples;
        cc.duration_s = o->duration_s;
        cc.count = o->count;
        lep_priv_chain_init(&s->chain, o, &cc);
    }
    rc = lep_session_set_rotation(s, o->rotation, o->shift_m);
    if (rc != LEP_OK) {
        lep_priv_set_err(err, errlen, "session: rotation is not a rotation matrix (R R^T != I)");
        lep_session_close(s);
        return LEP_E_ARG;
    }
    rc = lep_session_set_lowpass(s, o->lowpass_hz);
    if (rc != LEP_OK) {
        lep_priv_set_err(err, errlen,
                         "session: lowpass_hz %g is above 0.45 x the %g Hz output rate",
                         o->lowpass_hz, s->nominal_hz);
        lep_session_close(s);
        return LEP_E_ARG;
    }
    if (warning[0] != '\0')
        lep_priv_set_err(err, errlen, "%s", warning);
    *out = s;
    return LEP_OK;
}

static int session_stop(lep_session *s);

void lep_session_close(lep_session *s)
{
    if (s == NULL)
        return;
    /* a driving call in another thread returns (LEP_E_STATE) before this goes on */
    if (!lep_priv_guard_close(&s->guard))
        return; /* another thread is closing it */
    if (s->streaming)
        (void)session_stop(s);
    lep_priv_reader_disconnect(&s->rd);
    lep_sim_stop(s->sim);
    lep_priv_guard_destroy(&s->guard);
    pthread_mutex_destroy(&s->mu);
    free(s);
}

static int session_start(lep_session *s)
{
    lep_client_stats base;
    int rc;
    double now;
    if (s->streaming)
        return LEP_E_STATE;
    rc = lep_priv_reader_start(&s->rd);
    if (rc != LEP_OK)
        return rc;
    lep_priv_reader_stats(&s->rd, &base);
    now = lep_monotonic_seconds();
    lep_priv_timing_start(&s->tm, s->nominal_hz, s->opt.gap_periods,
                          s->sim != NULL); /* measures the UTC offset */
    pthread_mutex_lock(&s->mu);
    lep_priv_sink_start(&s->sink, s->nominal_hz, &base);
    s->start_mono = now;
    s->start_utc = now + lep_priv_timing_utc_offset(&s->tm);
    lep_priv_chain_start(&s->chain);
    pthread_mutex_unlock(&s->mu);
    s->streaming = true;
    lep_priv_session_resume(s, now);
    return LEP_OK;
}

/* A driving call: fn runs inside the thread guard (session_guard.c). */
static int guarded(lep_session *s, int (*fn)(lep_session *))
{
    int rc;
    if (s == NULL)
        return LEP_E_ARG;
    rc = lep_priv_guard_enter(&s->guard);
    if (rc != LEP_OK)
        return rc;
    rc = fn(s);
    lep_priv_guard_leave(&s->guard);
    return rc;
}

int lep_session_start(lep_session *s)
{
    return guarded(s, session_start);
}

int lep_session_set_latency(lep_session *s, int latency_ms)
{
    int rc;
    if (s == NULL || latency_ms < 0 || latency_ms > 10000)
        return LEP_E_ARG;
    rc = lep_priv_guard_enter(&s->guard);
    if (rc != LEP_OK)
        return rc;
    pthread_mutex_lock(&s->mu); /* lep_session_get reads it from any thread */
    s->opt.latency_ms = latency_ms;
    pthread_mutex_unlock(&s->mu);
    lep_priv_guard_leave(&s->guard);
    return LEP_OK;
}

int lep_session_latency(const lep_session *s)
{
    return s != NULL ? s->opt.latency_ms : 0;
}

static int session_stop(lep_session *s)
{
    int rc;
    if (!s->streaming)
        return LEP_E_STATE;
    s->streaming = false;
    pthread_mutex_lock(&s->mu);
    lep_priv_sink_stop(&s->sink); /* the rows, and the gate of the events that waited for them */
    pthread_mutex_unlock(&s->mu);
    rc = lep_priv_reader_stop(&s->rd);
    pthread_mutex_lock(&s->mu);
    lep_priv_chain_stop(&s->chain);
    pthread_mutex_unlock(&s->mu);
    return rc;
}

int lep_session_stop(lep_session *s)
{
    return guarded(s, session_stop);
}

lep_client *lep_session_client(lep_session *s)
{
    return s != NULL ? lep_priv_reader_client(&s->rd) : NULL;
}

lep_sim *lep_session_sim(lep_session *s)
{
    return s != NULL ? s->sim : NULL;
}

const char *lep_session_port(const lep_session *s)
{
    return s != NULL ? s->port_buf : "";
}

int lep_session_fd(const lep_session *s)
{
    return s != NULL ? lep_priv_reader_fd(&s->rd) : -1;
}

int lep_session_streaming(const lep_session *s)
{
    return s != NULL && s->streaming ? 1 : 0;
}

int lep_session_get_serial_info(const lep_session *s, lep_serial_info *out)
{
    if (out != NULL)
        memset(out, 0, sizeof *out);
    if (s == NULL || out == NULL)
        return LEP_E_ARG;
    return lep_priv_reader_serial_info(&s->rd, out);
}

void lep_priv_session_tap_timeline(lep_session *s, const timeline_tap *tap)
{
    lep_priv_timing_tap(&s->tm, tap);
}
