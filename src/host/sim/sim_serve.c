/* Virtual sensor: the serving thread (wait for input, deadlines and requests;
 * hang-up and reopen) and publishing counters to callers. Portable: the port
 * and the waiting are sim_pty.c's (POSIX) or sim_link_win32.c's (Windows). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE /* PATH_MAX */
#endif

#include "leptrino/error.h"
#include "posix_clock.h"
#include "sim_priv.h"
#include "sim_punctual.h"

void lep_priv_sim_publish(lep_sim *s)
{
    s->st.streaming = s->streaming;
    s->st.filter = lep_device_filter(&s->dev);
    s->st.filter_pending = lep_device_filter_pending(&s->dev);
    s->st.hung_up = s->hung;
    s->st.sequence = (uint16_t)(s->k & 0xFFFFu);
    pthread_mutex_lock(&s->lock);
    s->stats = s->st;
    pthread_mutex_unlock(&s->lock);
}

static void hang_up(lep_sim *s, int64_t now)
{
    lep_priv_sim_power_off(s); /* unplugged: a USB sensor loses power */
    s->hung = true;
    s->st.hangups++;
    s->reopen_at =
        s->opt.reopen_after_ms >= 0 ? now + (int64_t)s->opt.reopen_after_ms * 1000000 + 1 : 0;
    lep_priv_sim_publish(s); /* before the client can notice */
    /* Like udev's by-id link on unplug: the name goes away with the device,
     * so nobody reaches a stranger's pty that reuses the number meanwhile. */
    lep_priv_sim_remove_link(s);
    lep_priv_sim_close_pty(s);
}

static void reopen(lep_sim *s)
{
    char err[160];
    s->reopen_at = 0;
    if (lep_priv_sim_open_pty(s, err, sizeof err) == LEP_OK) {
        s->hung = false;
        s->power_on = lep_priv_monotonic_ns();
        s->st.reopens++;
        lep_priv_sim_publish(s);
    }
}

static int64_t earliest(int64_t a, int64_t b)
{
    if (a == 0)
        return b;
    if (b == 0)
        return a;
    return a < b ? a : b;
}

#define BLOCKED_WAKE_NS 100000000 /* 100 ms */
/* While streaming, a next deadline at most this far off is waited for in
 * clock_nanosleep, not ppoll: the pty and the requests are looked at once
 * per period instead (a command waits up to one period, at most this long). */
#define QUIET_WAIT_MAX_NS 2000000 /* 2 ms */

/* A caller's request is waiting (they are set under the lock, then the pipe
 * is written: the pipe is drained when the request is taken). */
static bool requests_pending(lep_sim *s)
{
    bool any;
    pthread_mutex_lock(&s->lock);
    any = s->req_stop || s->req_power_cycle || s->req_hangup || s->req_stall_ms >= 0 ||
          s->req_hold_ms >= 0 || (s->req_trace != NULL && s->trace == NULL);
    pthread_mutex_unlock(&s->lock);
    return any;
}

void *lep_priv_sim_serve(void *arg)
{
    lep_sim *s = arg;
    sim_punctual punctual; /* deadlines kept to the microsecond */
    lep_priv_sim_thread_init();
    lep_priv_sim_punctual_init(&punctual);
    for (;;) {
        bool port = false, want_out = false;
        unsigned ready = 0;
        int64_t now = lep_priv_monotonic_ns(), until = 0;
        bool stalled = s->stall_until != 0 && now < s->stall_until;
        bool held = s->hold_until != 0 && now < s->hold_until;
        bool stop, cycle, hangup, quiet, idle;
        int stall_ms, hold_ms;

        if (s->stall_until != 0 && !stalled) {
            s->stall_until = 0;
            lep_priv_sim_skip_due(s, now);
        }
        if (s->hold_until != 0 && !held)
            s->hold_until = 0;
        if (s->stall_at != 0 && now >= s->stall_at) {
            s->stall_at = 0;
            s->stall_until = now + (int64_t)s->opt.stall_ms * 1000000;
            s->st.stalls++;
            stalled = true;
        }
        if (s->hangup_at != 0 && now >= s->hangup_at) {
            s->hangup_at = 0;
            if (!s->hung)
                hang_up(s, now);
        }
        if (s->hung && s->reopen_at != 0 && now >= s->reopen_at)
            reopen(s);
        if (!s->hung && !stalled)
            lep_priv_sim_stream_due(s, now);
        if (s->trace_was_streaming && !s->streaming)
            lep_priv_sim_trace_mark(s->trace, LEP_SIM_TRACE_END, now);
        s->trace_was_streaming = s->streaming;
        lep_priv_sim_publish(s); /* counters first: a host that got an answer sees them */
        lep_priv_sim_queue_advance(s, now); /* the transport's frames up to now */
        if (!s->hung && !stalled && !held)
            lep_priv_sim_flush_out(s);

        if (!s->hung && !stalled) {
            port = true;
            want_out = lep_priv_sim_queue_ready(s) > 0 && !held;
            /* The next sample's deadline, unless the queue is full (nobody
             * reads): then wait for room (POLLOUT), waking every
             * BLOCKED_WAKE_NS instead of each sample to count the samples
             * due meanwhile as blocked. */
            if (s->streaming && !lep_priv_sim_queue_full(s))
                until = lep_priv_sim_deadline(s, s->k);
            else if (s->streaming)
                until = now + BLOCKED_WAKE_NS;
            if (!held) /* the transport releases more of the queue then */
                until = earliest(until, lep_priv_sim_queue_next(s));
        }
        if (stalled)
            until = earliest(until, s->stall_until);
        if (held)
            until = earliest(until, s->hold_until);
        until = earliest(until, s->stall_at);
        until = earliest(until, s->hangup_at);
        if (s->hung)
            until = earliest(until, s->reopen_at);

        /* Streaming with nothing to write (what is queued waits for the
         * transport's next frame): this period's write is done. Look
         * at the requests and the pty's input now (a read that does not
         * wait) and, with neither, sleep to the next deadline: one
         * clock_nanosleep and one read per period instead of a ppoll on
         * two descriptors, which costs more on every wake-up. Either
         * wait ends the punctual margin before the deadline and the rest
         * is watched on the clock (sim_punctual.h): a ppoll's early end
         * comes back here with the deadline that near, so quiet. */
        quiet = port && s->streaming && lep_priv_sim_queue_ready(s) == 0 && until != 0 &&
                until - now <= QUIET_WAIT_MAX_NS && !lep_priv_sim_queue_full(s);
        idle = quiet;
        if (quiet) {
            ready = (requests_pending(s) ? LEP_SIM_READY_WAKE : 0u) | LEP_SIM_READY_PORT;
        } else if (lep_priv_sim_wait(s, port, want_out,
                                     until != 0 ? lep_priv_sim_punctual_wake(&punctual, until) : 0,
                                     &ready) < 0) {
            break;
        }

        stop = cycle = hangup = false;
        stall_ms = hold_ms = -1;
        if (ready & LEP_SIM_READY_WAKE) {
            idle = false;
            /* a request: callers set it under the lock, then wake us */
            lep_priv_sim_wake_drain(s);
            pthread_mutex_lock(&s->lock);
            stop = s->req_stop;
            cycle = s->req_power_cycle;
            hangup = s->req_hangup;
            stall_ms = s->req_stall_ms;
            hold_ms = s->req_hold_ms;
            if (s->req_trace != NULL && s->trace == NULL) {
                s->trace = s->req_trace;
                s->req_trace = NULL;
            }
            s->req_power_cycle = s->req_hangup = false;
            s->req_stall_ms = s->req_hold_ms = -1;
            pthread_mutex_unlock(&s->lock);
        }
        if (stop)
            break;
        now = lep_priv_monotonic_ns();
        if (cycle && !s->hung) {
            lep_priv_sim_power_cycle(s);
            lep_priv_sim_publish(s);
        }
        if (hangup && !s->hung)
            hang_up(s, now);
        if (hold_ms >= 0)
            s->hold_until = hold_ms > 0 ? now + (int64_t)hold_ms * 1000000 : 0;
        if (stall_ms >= 0) {
            if (s->stall_until != 0 && stall_ms == 0)
                lep_priv_sim_skip_due(s, now);
            s->stall_until = stall_ms > 0 ? now + (int64_t)stall_ms * 1000000 : 0;
            if (stall_ms > 0)
                s->st.stalls++;
            continue;
        }
        if (port && !s->hung && (ready & LEP_SIM_READY_PORT)) {
            uint8_t buf[1024];
            long r = lep_priv_sim_read_port(s, buf, sizeof buf);
            if (r > 0) {
                idle = false;
                s->st.bytes_received += (uint64_t)r;
                lep_priv_sim_handle_input(s, buf, (size_t)r);
            } else if (r < 0) {
                /* the port cannot be read now: wait a little */
                idle = false;
                lep_priv_sleep_until_ns(lep_priv_monotonic_ns() + 10000000);
            }
        }
        if (idle)
            lep_priv_sim_punctual_sleep(&punctual, until);
    }
    if (s->trace_was_streaming || s->streaming) /* a stream running at lep_sim_stop */
        lep_priv_sim_trace_mark(s->trace, LEP_SIM_TRACE_END, lep_priv_monotonic_ns());
    lep_priv_sim_publish(s);
    return NULL;
}
