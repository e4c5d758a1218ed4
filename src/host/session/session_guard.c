/* Host session: the thread guard of the public entry points. The driving
 * calls (start, read, read_one, stop, set_latency) are for one thread at a time: a
 * second thread is refused (LEP_E_STATE) instead of sharing the stream's
 * state. lep_session_close from another thread interrupts a driving call
 * (it returns LEP_E_STATE) and waits for it to leave before freeing. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

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
