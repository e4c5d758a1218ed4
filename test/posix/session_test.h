/* Helpers of the session tests: a session on an in-process virtual sensor,
 * and a batch with every column. */
#ifndef LEP_SESSION_TEST_H
#define LEP_SESSION_TEST_H

#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "leptrino/error.h"
#include "leptrino/session.h"
#include "leptrino/sim.h"
#include "struct_api.h"
#include "unity.h"

typedef struct st_batch {
    lep_session_batch b;
    double *t_mono, *t_utc, *zeroed, *si;
    int16_t *raw;
    uint8_t *status, *flags;
    uint16_t *seq;
} st_batch;

static void st_batch_init(st_batch *x, size_t cap)
{
    memset(x, 0, sizeof *x);
    x->t_mono = calloc(cap, sizeof(double));
    x->t_utc = calloc(cap, sizeof(double));
    x->zeroed = calloc(cap * LEP_AXES, sizeof(double));
    x->si = calloc(cap * LEP_AXES, sizeof(double));
    x->raw = calloc(cap * LEP_AXES, sizeof(int16_t));
    x->status = calloc(cap, 1);
    x->flags = calloc(cap, 1);
    x->seq = calloc(cap, sizeof(uint16_t));
    TEST_ASSERT_NOT_NULL(x->seq);
    x->b.cap = cap;
    x->b.t_mono = x->t_mono;
    x->b.t_utc = x->t_utc;
    x->b.zeroed = x->zeroed;
    x->b.si = x->si;
    x->b.raw = x->raw;
    x->b.status = x->status;
    x->b.flags = x->flags;
    x->b.seq = x->seq;
}

static void st_batch_free(st_batch *x)
{
    free(x->t_mono);
    free(x->t_utc);
    free(x->zeroed);
    free(x->si);
    free(x->raw);
    free(x->status);
    free(x->flags);
    free(x->seq);
}

/* A flag one thread raises and another polls (race-free under TSan). */
typedef struct st_flag {
    pthread_mutex_t mu;
    bool up;
} st_flag;

static inline void st_flag_init(st_flag *f)
{
    pthread_mutex_init(&f->mu, NULL);
    f->up = false;
}

static inline void st_flag_raise(st_flag *f)
{
    pthread_mutex_lock(&f->mu);
    f->up = true;
    pthread_mutex_unlock(&f->mu);
}

static inline bool st_flag_is_up(st_flag *f)
{
    bool up;
    pthread_mutex_lock(&f->mu);
    up = f->up;
    pthread_mutex_unlock(&f->mu);
    return up;
}

/* Open a session on a virtual sensor with options *in (defaults when NULL);
 * *o gets the options used. */
static lep_session *open_sim(lep_session_options *o, const lep_session_options *in)
{
    lep_session *s = NULL;
    char err[512] = "";
    if (in == NULL)
        lep_session_options_init(o);
    else if (in != o)
        *o = *in;
    o->use_sim = true;
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_session_open_so(o, &s, err, sizeof err), err);
    TEST_ASSERT_NOT_NULL(s);
    return s;
}

/* A virtual sensor started on its own (options *so, defaults when NULL) and
 * a session opened on its port path with options *o (reconnect etc. kept;
 * the port is set): the session sees a port, not the in-process sensor. */
static inline lep_session *open_on_port(lep_sim **sim, const lep_sim_options *so,
                                        lep_session_options *o)
{
    lep_sim_options d;
    lep_session *s = NULL;
    char err[256] = "";
    if (so == NULL) {
        lep_sim_options_init(&d);
        so = &d;
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_start_so(so, sim, err, sizeof err), err);
    o->use_sim = false;
    o->port = lep_sim_port(*sim);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_session_open_so(o, &s, err, sizeof err), err);
    return s;
}

#endif
