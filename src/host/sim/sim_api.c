/* Virtual sensor: the public API (start, stop, requests, stats). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "posix_clock.h"
#include "options_priv.h"
#include "sim_priv.h"

int lep_sim_start_so(const lep_sim_options *o, lep_sim **out, char *err, size_t errlen)
{
    lep_sim_options defaults;
    lep_sim *s;
    int rc;
    sigset_t all, old;
    if (err != NULL && errlen > 0)
        err[0] = '\0';
    if (out == NULL) {
        lep_priv_set_err(err, errlen, "no place for the result");
        return LEP_E_ARG;
    }
    *out = NULL;
    if (o == NULL) {
        lep_sim_options_init(&defaults);
        o = &defaults;
    }
    rc = lep_sim_options_check(o, err, errlen);
    if (rc != LEP_OK)
        return rc;
    s = calloc(1, sizeof *s);
    if (s == NULL) {
        lep_priv_set_err(err, errlen, "out of memory");
        return LEP_E_IO;
    }
    s->master = s->slave = -1;
    s->lock_fd = -1;
    s->wake[0] = s->wake[1] = -1;
    s->req_stall_ms = -1;
    s->req_hold_ms = -1;
    s->opt = *o;
    s->link = s->opt.link;
    s->period_ns = NS_PER_S / o->rate_hz;
    s->rng = o->seed ^ 0x5EEDF00DCAFEBEEFu;
    (void)lep_sim_model_rated_f(s->opt.model, &s->rated);
    if (pthread_mutex_init(&s->lock, NULL) != 0) {
        free(s);
        lep_priv_set_err(err, errlen, "cannot create a mutex");
        return LEP_E_IO;
    }
    rc = lep_priv_signal_init(&s->sig, o, &s->rated, err, errlen);
    if (rc != LEP_OK) {
        pthread_mutex_destroy(&s->lock);
        free(s);
        return rc;
    }
    {
        uint8_t code;
        for (code = 0; code <= LEP_FILTER_MAX; code++)
            lep_priv_fir_design(&s->fir[code], code, o->rate_hz);
    }
    rc = lep_priv_sim_init_device(s, err, errlen);
    if (rc == LEP_OK && (pipe(s->wake) != 0 || lep_priv_sim_set_flags(s->wake[0]) != 0 ||
                         lep_priv_sim_set_flags(s->wake[1]) != 0)) {
        lep_priv_set_err(err, errlen, "cannot create a pipe: %s", strerror(errno));
        rc = LEP_E_IO;
    }
    if (rc == LEP_OK)
        rc = lep_priv_sim_link_claim(s, err, errlen);
    if (rc == LEP_OK)
        rc = lep_priv_sim_open_pty(s, err, errlen);
    if (rc != LEP_OK) {
        s->link = "";
        lep_sim_stop(s);
        return rc;
    }
    snprintf(s->port, sizeof s->port, "%s", s->link[0] ? s->link : s->pty);
    s->power_on = lep_priv_monotonic_ns();
    if (s->streaming)
        s->t0 = s->power_on;
    if (o->stall_ms > 0)
        s->stall_at = s->power_on + (int64_t)(o->stall_after_s * NS_PER_S) + 1;
    if (o->hangup_after_s > 0)
        s->hangup_at = s->power_on + (int64_t)(o->hangup_after_s * NS_PER_S);
    lep_priv_sim_publish(s);
    /* The thread takes no signals: they belong to the application. */
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    rc = pthread_create(&s->thread, NULL, lep_priv_sim_serve, s);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (rc != 0) {
        lep_priv_set_err(err, errlen, "cannot start the serving thread");
        lep_sim_stop(s);
        return LEP_E_IO;
    }
    s->thread_started = true;
    *out = s;
    return LEP_OK;
}

int lep_sim_sample_at(const lep_sim *s, uint64_t k, uint8_t filter, lep_sample *out)
{
    if (s == NULL || out == NULL || filter > LEP_FILTER_MAX)
        return LEP_E_ARG;
    lep_priv_fir_sample(&s->fir[filter], &s->sig, k, out);
    out->reserved = (uint16_t)(k & 0xFFFFu);
    return LEP_OK;
}

const char *lep_sim_port(const lep_sim *s)
{
    return s ? s->port : "";
}

const char *lep_sim_pty_path(const lep_sim *s)
{
    return s ? s->pty : "";
}

static void request(lep_sim *s, bool *flag, int *ms_field, int ms)
{
    static const uint8_t one = 1;
    if (s == NULL)
        return;
    pthread_mutex_lock(&s->lock);
    if (flag != NULL)
        *flag = true;
    if (ms_field != NULL)
        *ms_field = ms;
    pthread_mutex_unlock(&s->lock);
    if (s->wake[1] >= 0)
        (void)!write(s->wake[1], &one, 1);
}

void lep_sim_power_cycle(lep_sim *s)
{
    if (s != NULL)
        request(s, &s->req_power_cycle, NULL, 0);
}

void lep_sim_hangup(lep_sim *s)
{
    if (s != NULL)
        request(s, &s->req_hangup, NULL, 0);
}

void lep_sim_stall(lep_sim *s, int ms)
{
    if (s != NULL)
        request(s, NULL, &s->req_stall_ms, ms < 0 ? 0 : ms);
}

void lep_sim_hold(lep_sim *s, int ms)
{
    if (s != NULL)
        request(s, NULL, &s->req_hold_ms, ms < 0 ? 0 : ms);
}

int lep_sim_trace_writes(lep_sim *s, const char *path, char *err, size_t errlen)
{
    lep_sim_trace *t = NULL;
    bool taken;
    int rc;
    if (s == NULL || path == NULL || path[0] == '\0') {
        lep_priv_set_err(err, errlen, "write trace: no sensor or no path");
        return LEP_E_ARG;
    }
    pthread_mutex_lock(&s->lock);
    taken = s->trace_requested;
    s->trace_requested = true;
    pthread_mutex_unlock(&s->lock);
    if (taken) {
        lep_priv_set_err(err, errlen, "write trace: this sensor already traces its writes");
        return LEP_E_STATE;
    }
    rc = lep_priv_sim_trace_open(path, &t, err, errlen);
    if (rc != LEP_OK) {
        pthread_mutex_lock(&s->lock);
        s->trace_requested = false;
        pthread_mutex_unlock(&s->lock);
        return rc;
    }
    pthread_mutex_lock(&s->lock);
    s->req_trace = t;
    pthread_mutex_unlock(&s->lock);
    request(s, NULL, NULL, 0);
    return LEP_OK;
}

void lep_sim_get_stats(lep_sim *s, lep_sim_counters *out)
{
    if (out == NULL)
        return;
    if (s == NULL) {
        memset(out, 0, sizeof *out);
        return;
    }
    pthread_mutex_lock(&s->lock);
    *out = s->stats;
    pthread_mutex_unlock(&s->lock);
}

void lep_sim_stop(lep_sim *s)
{
    if (s == NULL)
        return;
    if (s->thread_started) {
        request(s, &s->req_stop, NULL, 0);
        pthread_join(s->thread, NULL);
    }
    lep_priv_sim_trace_close(s->trace);
    lep_priv_sim_trace_close(s->req_trace); /* never picked up */
    lep_priv_sim_remove_link(s);
    lep_priv_sim_link_release(s);
    lep_priv_sim_close_pty(s);
    if (s->wake[0] >= 0)
        close(s->wake[0]);
    if (s->wake[1] >= 0)
        close(s->wake[1]);
    lep_priv_signal_free(&s->sig);
    pthread_mutex_destroy(&s->lock);
    free(s);
}

/* ---- the flat form (leptrino/sim.h) ---- */

int lep_sim_start(const lep_options *o, lep_sim **out, char *err, size_t errlen)
{
    lep_sim_options so;
    if (o == NULL) {
        lep_sim_options_init(&so);
        return lep_sim_start_so(&so, out, err, errlen);
    }
    return lep_sim_start_so(&o->so.sim, out, err, errlen);
}

int lep_sim_stream_sample(const lep_sim *s, uint64_t k, int filter, int16_t raw[6], uint8_t *status,
                          uint16_t *seq)
{
    lep_sample smp;
    int rc;
    if (filter < 0 || filter > (int)LEP_FILTER_MAX)
        return LEP_E_ARG;
    rc = lep_sim_sample_at(s, k, (uint8_t)filter, &smp);
    if (rc != LEP_OK)
        return rc;
    if (raw != NULL)
        memcpy(raw, smp.raw, sizeof smp.raw);
    if (status != NULL)
        *status = smp.status;
    if (seq != NULL)
        *seq = smp.reserved;
    return LEP_OK;
}

static const char *const stat_names[LEP_SIMST_COUNT] = {
    "samples_sent",    "samples_dropped", "commands",        "naks",
    "bytes_corrupted", "hangups",         "streaming",       "filter",
    "filter_pending",  "hung_up",         "sequence",        "responses",
    "faked_naks",      "samples_skipped", "samples_blocked", "garbage_bytes",
    "bytes_received",  "reopens",         "power_cycles",    "stalls"
};

size_t lep_sim_stats_fields(void)
{
    return LEP_SIMST_COUNT;
}

const char *lep_sim_stats_field_name(size_t i)
{
    return i < LEP_SIMST_COUNT ? stat_names[i] : NULL;
}

int lep_sim_stats(lep_sim *s, uint64_t *out, size_t n)
{
    lep_sim_counters c;
    uint64_t f[LEP_SIMST_COUNT];
    if (s == NULL || (out == NULL && n > 0))
        return LEP_E_ARG;
    lep_sim_get_stats(s, &c);
    f[LEP_SIMST_SAMPLES_SENT] = c.samples_sent;
    f[LEP_SIMST_SAMPLES_DROPPED] = c.samples_dropped;
    f[LEP_SIMST_COMMANDS] = c.commands;
    f[LEP_SIMST_NAKS] = c.naks;
    f[LEP_SIMST_BYTES_CORRUPTED] = c.bytes_corrupted;
    f[LEP_SIMST_HANGUPS] = c.hangups;
    f[LEP_SIMST_STREAMING] = c.streaming ? 1u : 0u;
    f[LEP_SIMST_FILTER] = c.filter;
    f[LEP_SIMST_FILTER_PENDING] = c.filter_pending;
    f[LEP_SIMST_HUNG_UP] = c.hung_up ? 1u : 0u;
    f[LEP_SIMST_SEQUENCE] = c.sequence;
    f[LEP_SIMST_RESPONSES] = c.responses;
    f[LEP_SIMST_FAKED_NAKS] = c.faked_naks;
    f[LEP_SIMST_SAMPLES_SKIPPED] = c.samples_skipped;
    f[LEP_SIMST_SAMPLES_BLOCKED] = c.samples_blocked;
    f[LEP_SIMST_GARBAGE_BYTES] = c.garbage_bytes;
    f[LEP_SIMST_BYTES_RECEIVED] = c.bytes_received;
    f[LEP_SIMST_REOPENS] = c.reopens;
    f[LEP_SIMST_POWER_CYCLES] = c.power_cycles;
    f[LEP_SIMST_STALLS] = c.stalls;
    memcpy(out, f, sizeof(uint64_t) * (n < LEP_SIMST_COUNT ? n : LEP_SIMST_COUNT));
    return LEP_OK;
}
