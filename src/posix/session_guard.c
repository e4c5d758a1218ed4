/* Host session: the thread guard of the public entry points. The driving
 * calls (start, read, stop, set_latency) are for one thread at a time: a
 * second thread is refused (LEP_E_STATE) instead of sharing the stream's
 * state. lep_session_close from another thread interrupts a driving call
 * (it returns LEP_E_STATE) and waits for it to leave before freeing. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <math.h>

#include "leptrino/error.h"
#include "session_priv.h"

int lep_priv_guard_init(session_guard *g)
{
    g->inside = 0;
    g->driving = false;
    g->closing = false;
    if (pthread_mutex_init(&g->mu, NULL) != 0)
        return LEP_E_IO;
    if (pthread_cond_init(&g->left, NULL) != 0) {
        pthread_mutex_destroy(&g->mu);
        return LEP_E_IO;
    }
    return LEP_OK;
}

void lep_priv_guard_destroy(session_guard *g)
{
    pthread_cond_destroy(&g->left);
    pthread_mutex_destroy(&g->mu);
}

int lep_priv_guard_enter(session_guard *g)
{
    int rc = LEP_OK;
    pthread_mutex_lock(&g->mu);
    if (g->closing || g->driving) {
        rc = LEP_E_STATE; /* closing, or another thread is inside a driving call */
    } else {
        g->driving = true;
        g->inside++;
    }
    pthread_mutex_unlock(&g->mu);
    return rc;
}

void lep_priv_guard_leave(session_guard *g)
{
    pthread_mutex_lock(&g->mu);
    g->driving = false;
    g->inside--;
    pthread_cond_broadcast(&g->left);
    pthread_mutex_unlock(&g->mu);
}

bool lep_priv_guard_closing(session_guard *g)
{
    bool c;
    pthread_mutex_lock(&g->mu);
    c = g->closing;
    pthread_mutex_unlock(&g->mu);
    return c;
}

bool lep_priv_guard_close(session_guard *g)
{
    bool first;
    pthread_mutex_lock(&g->mu);
    first = !g->closing;
    g->closing = true;
    while (g->inside > 0)
        pthread_cond_wait(&g->left, &g->mu);
    pthread_mutex_unlock(&g->mu);
    return first;
}

/* Longest wait of one pass of the stream reader: how soon a close from
 * another thread is seen (a latency budget lengthens it, see below). */
#define GUARD_SLICE_MS 50

int lep_session_read(lep_session *s, lep_session_batch *b, int timeout_ms)
{
    double deadline;
    int rc, slice_ms;
    if (s == NULL || b == NULL || b->n > b->cap)
        return LEP_E_ARG;
    rc = lep_priv_guard_enter(&s->guard);
    if (rc != LEP_OK)
        return rc;
    /* A pass must be able to sleep out the latency budget, or the budget
     * would end at every pass. */
    slice_ms = s->opt.latency_ms + GUARD_SLICE_MS;
    deadline = timeout_ms < 0 ? INFINITY : lep_monotonic_seconds() + (double)timeout_ms / 1000.0;
    for (;;) {
        double left_ms = (deadline - lep_monotonic_seconds()) * 1000.0;
        int wait = left_ms > (double)slice_ms ? slice_ms : left_ms > 0.0 ? (int)ceil(left_ms) : 0;
        rc = lep_priv_session_read(s, b, wait);
        /* nothing in this pass, the stream not given up: wait on unless the
         * caller's time is out or the session is being closed */
        if (rc != LEP_E_TIMEOUT || s->failed != 0 || left_ms <= (double)slice_ms)
            break;
        if (lep_priv_guard_closing(&s->guard)) {
            rc = LEP_E_STATE;
            break;
        }
    }
    lep_priv_guard_leave(&s->guard);
    return rc;
}
