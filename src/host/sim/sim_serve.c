/* Virtual sensor: the serving thread (wait for input, deadlines and requests;
 * hang-up and reopen) and publishing counters to callers. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _GNU_SOURCE /* ppoll, ptsname_r */
#endif

#include <errno.h>
#include <poll.h>
#if defined(__linux__)
#include <sys/prctl.h>
#endif
#include <time.h>
#include <unistd.h>

#include "leptrino/error.h"
#include "posix_clock.h"
#include "sim_priv.h"

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

static int wait_events(lep_sim *s, struct pollfd *p, nfds_t n, int64_t until)
{
#if defined(__linux__)
    struct timespec ts, *tp = NULL;
    if (until != 0) {
        int64_t left = until - lep_priv_monotonic_ns();
        if (left < 0)
            left = 0;
        ts.tv_sec = (time_t)(left / 1000000000);
        ts.tv_nsec = (long)(left % 1000000000);
        tp = &ts;
    }
    (void)s;
    return ppoll(p, n, tp, NULL);
#else
    int ms = -1;
    (void)s;
    if (until != 0) {
        int64_t left = until - lep_priv_monotonic_ns();
        ms = left <= 0 ? 0 : (int)((left + 999999) / 1000000);
    }
    return poll(p, n, ms);
#endif
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
#if defined(__linux__) && defined(PR_SET_TIMERSLACK)
    /* Wake at each deadline, not up to 50 us after it (the default slack of
     * a thread's timers; this thread's only, the host program keeps its own). */
    (void)prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
#endif
    for (;;) {
        struct pollfd p[2];
        nfds_t n = 1;
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
        if (!s->hung && !stalled && !held)
            lep_priv_sim_flush_out(s);

        p[0].fd = s->wake[0];
        p[0].events = POLLIN;
        p[0].revents = 0;
        if (!s->hung && !stalled) {
            p[1].fd = s->master;
            p[1].events = (short)(POLLIN | (s->out_len > 0 && !held ? POLLOUT : 0));
            p[1].revents = 0;
            n = 2;
            /* The next sample's deadline, unless the queue is full (nobody
             * reads): then wait for room (POLLOUT), waking every
             * BLOCKED_WAKE_NS instead of each sample to count the samples
             * due meanwhile as blocked. */
            if (s->streaming && !lep_priv_sim_queue_full(s))
                until = lep_priv_sim_deadline(s, s->k);
            else if (s->streaming)
                until = now + BLOCKED_WAKE_NS;
        }
        if (stalled)
            until = earliest(until, s->stall_until);
        if (held)
            until = earliest(until, s->hold_until);
        until = earliest(until, s->stall_at);
        until = earliest(until, s->hangup_at);
        if (s->hung)
            until = earliest(until, s->reopen_at);

        /* Streaming with nothing queued: this period's write is done. Look
         * at the requests and the pty's input now (a read that does not
         * wait) and, with neither, sleep to the next deadline: one
         * clock_nanosleep and one read per period instead of a ppoll on
         * two descriptors, which costs more on every wake-up. */
        quiet = n == 2 && s->streaming && s->out_len == 0 && until != 0 &&
                until - now <= QUIET_WAIT_MAX_NS && !lep_priv_sim_queue_full(s);
        idle = quiet;
        if (quiet) {
            p[0].revents = requests_pending(s) ? POLLIN : 0;
            p[1].revents = POLLIN;
        } else if (wait_events(s, p, n, until) < 0 && errno != EINTR) {
            break;
        }

        stop = cycle = hangup = false;
        stall_ms = hold_ms = -1;
        if (p[0].revents & POLLIN) {
            idle = false;
            /* a request: callers set it under the lock, then write the pipe */
            uint8_t junk[64];
            while (read(s->wake[0], junk, sizeof junk) > 0) {
            }
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
        if (n == 2 && !s->hung && (p[1].revents & (POLLIN | POLLHUP | POLLERR))) {
            uint8_t buf[1024];
            ssize_t r = read(s->master, buf, sizeof buf);
            if (r > 0) {
                idle = false;
                s->st.bytes_received += (uint64_t)r;
                lep_priv_sim_handle_input(s, buf, (size_t)r);
            } else if (r < 0 && errno == EIO) {
                /* no slave open (cannot happen while we hold one): wait a little */
                struct timespec ts = { 0, 10000000 };
                idle = false;
                nanosleep(&ts, NULL);
            }
        }
        if (idle)
            lep_priv_sleep_until_ns(until);
    }
    if (s->trace_was_streaming || s->streaming) /* a stream running at lep_sim_stop */
        lep_priv_sim_trace_mark(s->trace, LEP_SIM_TRACE_END, lep_priv_monotonic_ns());
    lep_priv_sim_publish(s);
    return NULL;
}
