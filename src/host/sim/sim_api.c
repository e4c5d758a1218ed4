/* Virtual sensor: the public API (start, stop, requests, stats). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    lep_priv_sim_port_init(s);
    s->lock_fd = -1;
    s->req_stall_ms = -1;
    s->req_hold_ms = -1;
    s->opt = *o;
    s->link = s->opt.link;
    /* the crystal's true rate: off by sim-ppm, the nominal one reported */
    s->period_ns = NS_PER_S / (o->rate_hz * (1.0 + o->ppm * 1e-6));
    lep_priv_sim_queue_init(s);
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
    if (rc == LEP_OK)
        rc = lep_priv_sim_wake_open(s, err, errlen);
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
    rc = lep_priv_sim_start_thread(s, lep_priv_sim_serve);
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
    if (s == NULL)
        return;
    pthread_mutex_lock(&s->lock);
    if (flag != NULL)
        *flag = true;
    if (ms_field != NULL)
        *ms_field = ms;
    pthread_mutex_unlock(&s->lock);
    lep_priv_sim_wake(s);
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
    lep_priv_sim_wake_close(s);
    lep_priv_signal_free(&s->sig);
    pthread_mutex_destroy(&s->lock);
    free(s);
}
