/* Virtual sensor: a pseudo-terminal served by lep_device on a thread of its own. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _GNU_SOURCE /* ppoll, ptsname_r */
#endif

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "errmsg.h"
#include "leptrino/device.h"
#include "leptrino/error.h"
#include "leptrino/frame.h"
#include "leptrino/sim.h"
#include "posix_clock.h"
#include "sim_signal.h"

#define OUTQ_SIZE 32768u
#define PEND_SIZE 1024u
/* Beyond this lag behind schedule (the process was not scheduled), samples
 * are skipped instead of sent in a burst. A stall skips what it covered. */
#define MAX_LAG_NS 500000000
#define NS_PER_S 1000000000.0

struct lep_sim {
    /* shared with callers, under lock */
    pthread_mutex_t lock;
    bool req_stop, req_power_cycle, req_hangup;
    int req_stall_ms; /* -1: none */
    lep_sim_stats stats;
    int wake[2];
    pthread_t thread;
    bool thread_started;

    /* set at start, read-only afterwards */
    lep_sim_options opt;
    const char *link; /* opt.link, "" for none */
    char port[PATH_MAX]; /* what lep_sim_port returns: the link, or the pty */
    lep_product_info info;
    lep_rated rated;
    lep_sim_signal sig;
    double period_ns;

    /* owned by the serving thread */
    lep_sim_stats st; /* working copy, published under lock */
    lep_device dev;
    lep_frame_decoder shadow; /* sees frames first, so a NAK fault can withhold one */
    uint8_t pend[PEND_SIZE];
    size_t pend_len;
    int master, slave;
    char pty[PATH_MAX];
    uint64_t rng;
    uint8_t out[OUTQ_SIZE];
    size_t out_len;
    bool streaming;
    int64_t t0;  /* stream start */
    uint64_t k;  /* index of the next stream sample */
    int64_t power_on;
    int64_t stall_until, stall_at, hangup_at, reopen_at; /* 0: none */
    bool hung;
};

/* ---- pty ---- */

static void raw_termios(int fd)
{
    struct termios t;
    if (tcgetattr(fd, &t) != 0)
        return;
    t.c_iflag = 0;
    t.c_oflag = 0;
    t.c_lflag = 0;
    t.c_cflag = (tcflag_t)(CS8 | CREAD | CLOCAL);
    t.c_cc[VMIN] = 1;
    t.c_cc[VTIME] = 0;
#if defined(B460800)
    cfsetispeed(&t, B460800);
    cfsetospeed(&t, B460800);
#endif
    (void)tcsetattr(fd, TCSANOW, &t);
}

static int set_flags(int fd)
{
    int fl = fcntl(fd, F_GETFL);
    if (fl < 0 || fcntl(fd, F_SETFL, fl | O_NONBLOCK) != 0)
        return -1;
    fl = fcntl(fd, F_GETFD);
    if (fl < 0 || fcntl(fd, F_SETFD, fl | FD_CLOEXEC) != 0)
        return -1;
    return 0;
}

/* Point link at target atomically (a new symlink renamed over the old). */
static int relink(const char *link, const char *target)
{
    char tmp[PATH_MAX + 32];
    int n = snprintf(tmp, sizeof tmp, "%s.%ld.tmp", link, (long)getpid());
    if (n < 0 || (size_t)n >= sizeof tmp)
        return -1;
    (void)unlink(tmp);
    if (symlink(target, tmp) != 0)
        return -1;
    if (rename(tmp, link) != 0) {
        (void)unlink(tmp);
        return -1;
    }
    return 0;
}

/* Open a new pty: master non-blocking, slave raw and held open by us so the
 * master never sees EIO when the client closes its side. */
static int open_pty(lep_sim *s, char *err, size_t errlen)
{
    int m = posix_openpt(O_RDWR | O_NOCTTY);
    const char *name;
    if (m < 0) {
        lep_priv_set_err(err, errlen, "cannot open a pseudo-terminal: %s", strerror(errno));
        return LEP_E_IO;
    }
    if (grantpt(m) != 0 || unlockpt(m) != 0 || set_flags(m) != 0) {
        lep_priv_set_err(err, errlen, "cannot set up the pseudo-terminal: %s", strerror(errno));
        close(m);
        return LEP_E_IO;
    }
#if defined(__linux__)
    if (ptsname_r(m, s->pty, sizeof s->pty) != 0) {
        lep_priv_set_err(err, errlen, "cannot name the pseudo-terminal: %s", strerror(errno));
        close(m);
        return LEP_E_IO;
    }
    name = s->pty;
#else
    name = ptsname(m);
    if (name == NULL || strlen(name) >= sizeof s->pty) {
        lep_priv_set_err(err, errlen, "cannot name the pseudo-terminal");
        close(m);
        return LEP_E_IO;
    }
    memmove(s->pty, name, strlen(name) + 1);
#endif
    (void)name;
    s->slave = open(s->pty, O_RDWR | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
    if (s->slave < 0) {
        lep_priv_set_err(err, errlen, "%s: cannot open: %s", s->pty, strerror(errno));
        close(m);
        return LEP_E_IO;
    }
    raw_termios(s->slave);
    s->master = m;
    if (s->link[0] != '\0' && relink(s->link, s->pty) != 0) {
        lep_priv_set_err(err, errlen, "%s: cannot make the link: %s", s->link, strerror(errno));
        close(s->slave);
        close(s->master);
        s->slave = s->master = -1;
        return LEP_E_IO;
    }
    return LEP_OK;
}

static void close_pty(lep_sim *s)
{
    if (s->master >= 0)
        close(s->master);
    if (s->slave >= 0)
        close(s->slave);
    s->master = s->slave = -1;
}

static void publish(lep_sim *s);

/* ---- faults ---- */

static bool roll(lep_sim *s, double p)
{
    return p > 0 && lep_priv_uniform(&s->rng) < p;
}

/* ---- output ---- */

static void flush_out(lep_sim *s)
{
    while (s->out_len > 0 && s->master >= 0) {
        ssize_t n = write(s->master, s->out, s->out_len);
        if (n > 0) {
            memmove(s->out, s->out + n, s->out_len - (size_t)n);
            s->out_len -= (size_t)n;
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        break; /* EAGAIN: nobody reads now; keep it queued */
    }
}

static bool queue(lep_sim *s, const uint8_t *b, size_t n)
{
    if (s->out_len + n > OUTQ_SIZE)
        return false;
    memcpy(s->out + s->out_len, b, n);
    s->out_len += n;
    return true;
}

/* Send a message frame, through the garbage/corrupt/drop faults. */
static void emit(lep_sim *s, const uint8_t *frame, size_t len, bool data)
{
    uint8_t buf[LEP_MAX_FRAME + 16];
    size_t n = 0;
    if (data && roll(s, s->opt.p_drop)) {
        s->st.samples_dropped++;
        return;
    }
    if (roll(s, s->opt.p_garbage)) {
        /* 1..8 bytes, never DLE, so they cannot swallow the frame that follows */
        size_t g = 1u + (size_t)(lep_priv_splitmix64(&s->rng) % 8u);
        while (n < g) {
            uint8_t b = (uint8_t)lep_priv_splitmix64(&s->rng);
            if (b != LEP_DLE)
                buf[n++] = b;
        }
    }
    memcpy(buf + n, frame, len);
    if (roll(s, s->opt.p_corrupt)) {
        size_t at = n + (size_t)(lep_priv_splitmix64(&s->rng) % len);
        buf[at] ^= (uint8_t)(1u << (lep_priv_splitmix64(&s->rng) % 8u));
        s->st.bytes_corrupted++;
    }
    if (!queue(s, buf, n + len)) {
        if (data)
            s->st.samples_blocked++;
        return;
    }
    s->st.garbage_bytes += n;
    if (data)
        s->st.samples_sent++;
    else
        s->st.responses++;
}

static void send_nak(lep_sim *s)
{
    static const uint8_t nak[2] = {LEP_DLE, LEP_NAK};
    if (queue(s, nak, sizeof nak))
        s->st.naks++;
}

/* ---- device ---- */

static void stream_begins(lep_sim *s, int64_t now)
{
    s->streaming = true;
    s->t0 = now;
    s->k = 0;
}

static void check_streaming(lep_sim *s)
{
    bool on = lep_device_streaming(&s->dev);
    if (on && !s->streaming)
        stream_begins(s, lep_priv_monotonic_ns());
    s->streaming = on;
}

/* Feed bytes to the device and send what it answers. */
static void feed_device(lep_sim *s, const uint8_t *p, size_t len)
{
    while (len > 0) {
        lep_device_event ev;
        uint8_t ans[LEP_MAX_FRAME];
        size_t ans_len = 0;
        size_t used = lep_device_feed(&s->dev, p, len, &ev, ans, sizeof ans, &ans_len);
        if (used == 0)
            used = len; /* never spin */
        p += used;
        len -= used;
        if (ev.type == LEP_DEVICE_COMMAND) {
            s->st.commands++;
            if (ans_len > 0)
                emit(s, ans, ans_len, false);
            check_streaming(s);
        } else if (ev.type == LEP_DEVICE_NAK) {
            send_nak(s);
        }
    }
}

static void flush_pend(lep_sim *s)
{
    if (s->pend_len > 0)
        feed_device(s, s->pend, s->pend_len);
    s->pend_len = 0;
}

static void handshake_sample(lep_sim *s)
{
    lep_sample smp;
    int64_t since = lep_priv_monotonic_ns() - s->power_on;
    uint64_t n = since > 0 ? (uint64_t)((double)since / s->period_ns) : 0u;
    lep_priv_signal_sample(&s->sig, n, &smp);
    lep_device_set_sample(&s->dev, &smp);
}

static void handle_input(lep_sim *s, const uint8_t *p, size_t len)
{
    while (len > 0) {
        lep_frame_event ev;
        size_t used = lep_frame_decoder_feed(&s->shadow, p, len, &ev);
        if (s->pend_len + used > PEND_SIZE)
            flush_pend(s);
        if (used > PEND_SIZE) { /* cannot happen: frames are bounded */
            feed_device(s, p, used);
        } else {
            memcpy(s->pend + s->pend_len, p, used);
            s->pend_len += used;
        }
        p += used;
        len -= used;
        if (ev.type == LEP_FRAME_MESSAGE) {
            if (ev.len >= 3 && ev.msg[2] == LEP_CMD_SAMPLE)
                handshake_sample(s);
            if (roll(s, s->opt.p_nak)) {
                s->pend_len = 0; /* the device never sees it */
                s->st.faked_naks++;
                send_nak(s);
            } else {
                flush_pend(s);
            }
        } else if (ev.type != LEP_FRAME_NONE || !lep_frame_decoder_busy(&s->shadow)) {
            flush_pend(s);
        }
    }
}

static void power_cycle(lep_sim *s)
{
    lep_device_power_cycle(&s->dev);
    lep_frame_decoder_init(&s->shadow);
    s->pend_len = 0;
    s->streaming = false;
    s->out_len = 0; /* bytes in flight die with the power */
    s->power_on = lep_priv_monotonic_ns();
    s->st.power_cycles++;
    publish(s);
}

/* ---- stream ---- */

static int64_t deadline_of(const lep_sim *s, uint64_t k)
{
    return s->t0 + (int64_t)((double)(k + 1u) * s->period_ns);
}

static void stream_due(lep_sim *s, int64_t now)
{
    while (s->streaming && deadline_of(s, s->k) <= now) {
        lep_sample smp;
        uint8_t frame[LEP_MAX_FRAME];
        size_t len;
        if (now - deadline_of(s, s->k) > MAX_LAG_NS) {
            s->st.samples_skipped++;
            s->k++;
            continue;
        }
        lep_priv_signal_sample(&s->sig, s->k, &smp);
        smp.reserved = (uint16_t)(s->k & 0xFFFFu);
        s->k++;
        if (lep_device_stream_frame(&smp, frame, sizeof frame, &len) == LEP_OK)
            emit(s, frame, len, true);
    }
}

/* Samples due during a stall are not sent later: skip them (a sequence gap). */
static void skip_due(lep_sim *s, int64_t now)
{
    while (s->streaming && deadline_of(s, s->k) <= now) {
        s->st.samples_skipped++;
        s->k++;
    }
}

/* ---- the serving thread ---- */

static void publish(lep_sim *s)
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

/* Remove the link only while it still points at our pty. */
static void remove_link(const lep_sim *s)
{
    char target[PATH_MAX];
    ssize_t n;
    if (s->link == NULL || s->link[0] == '\0')
        return;
    n = readlink(s->link, target, sizeof target - 1);
    if (n < 0)
        return;
    target[n] = '\0';
    if (strcmp(target, s->pty) == 0)
        (void)unlink(s->link);
}

static void hang_up(lep_sim *s, int64_t now)
{
    lep_device_power_cycle(&s->dev); /* unplugged: a USB sensor loses power */
    lep_frame_decoder_init(&s->shadow);
    s->pend_len = 0;
    s->streaming = false;
    s->out_len = 0;
    s->hung = true;
    s->st.hangups++;
    s->reopen_at = s->opt.reopen_after_ms >= 0
                       ? now + (int64_t)s->opt.reopen_after_ms * 1000000 + 1
                       : 0;
    publish(s); /* before the client can notice */
    /* Like udev's by-id link on unplug: the name goes away with the device,
     * so nobody reaches a stranger's pty that reuses the number meanwhile. */
    remove_link(s);
    close_pty(s);
}

static void reopen(lep_sim *s)
{
    char err[160];
    s->reopen_at = 0;
    if (open_pty(s, err, sizeof err) == LEP_OK) {
        s->hung = false;
        s->power_on = lep_priv_monotonic_ns();
        s->st.reopens++;
        publish(s);
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

static void *serve(void *arg)
{
    lep_sim *s = arg;
    for (;;) {
        struct pollfd p[2];
        nfds_t n = 1;
        int64_t now = lep_priv_monotonic_ns(), until = 0;
        bool stalled = s->stall_until != 0 && now < s->stall_until;
        bool stop, cycle, hangup;
        int stall_ms;

        if (s->stall_until != 0 && !stalled) {
            s->stall_until = 0;
            skip_due(s, now);
        }
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
            stream_due(s, now);
        publish(s); /* counters first: a host that got an answer sees them */
        if (!s->hung && !stalled)
            flush_out(s);

        p[0].fd = s->wake[0];
        p[0].events = POLLIN;
        p[0].revents = 0;
        if (!s->hung && !stalled) {
            p[1].fd = s->master;
            p[1].events = (short)(POLLIN | (s->out_len > 0 ? POLLOUT : 0));
            p[1].revents = 0;
            n = 2;
            if (s->streaming)
                until = deadline_of(s, s->k);
        }
        if (stalled)
            until = earliest(until, s->stall_until);
        until = earliest(until, s->stall_at);
        until = earliest(until, s->hangup_at);
        if (s->hung)
            until = earliest(until, s->reopen_at);

        if (wait_events(s, p, n, until) < 0 && errno != EINTR)
            break;

        if (p[0].revents & POLLIN) {
            uint8_t junk[64];
            while (read(s->wake[0], junk, sizeof junk) > 0) {
            }
        }
        pthread_mutex_lock(&s->lock);
        stop = s->req_stop;
        cycle = s->req_power_cycle;
        hangup = s->req_hangup;
        stall_ms = s->req_stall_ms;
        s->req_power_cycle = s->req_hangup = false;
        s->req_stall_ms = -1;
        pthread_mutex_unlock(&s->lock);
        if (stop)
            break;
        now = lep_priv_monotonic_ns();
        if (cycle && !s->hung)
            power_cycle(s);
        if (hangup && !s->hung)
            hang_up(s, now);
        if (stall_ms >= 0) {
            if (s->stall_until != 0 && stall_ms == 0)
                skip_due(s, now);
            s->stall_until = stall_ms > 0 ? now + (int64_t)stall_ms * 1000000 : 0;
            if (stall_ms > 0)
                s->st.stalls++;
            continue;
        }
        if (n == 2 && !s->hung && (p[1].revents & (POLLIN | POLLHUP | POLLERR))) {
            uint8_t buf[1024];
            ssize_t r = read(s->master, buf, sizeof buf);
            if (r > 0) {
                s->st.bytes_received += (uint64_t)r;
                handle_input(s, buf, (size_t)r);
            } else if (r < 0 && errno == EIO) {
                /* no slave open (cannot happen while we hold one): wait a little */
                struct timespec ts = {0, 10000000};
                nanosleep(&ts, NULL);
            }
        }
    }
    publish(s);
    return NULL;
}

/* ---- API ---- */

static void copy_field(char *dst, size_t cap, const char *src)
{
    size_t n = strlen(src);
    if (n >= cap)
        n = cap - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

static int init_device(lep_sim *s, char *err, size_t errlen)
{
    const lep_sim_options *o = &s->opt;
    int rc;
    memset(&s->info, 0, sizeof s->info);
    copy_field(s->info.model, sizeof s->info.model, o->model);
    copy_field(s->info.serial, sizeof s->info.serial, o->serial);
    copy_field(s->info.firmware, sizeof s->info.firmware, o->firmware);
    if (o->output_rate_field) {
        s->info.has_output_rate = true;
        s->info.output_rate_hz = (uint32_t)(o->rate_hz + 0.5);
        snprintf(s->info.output_rate, sizeof s->info.output_rate, "%u",
                 (unsigned)s->info.output_rate_hz);
    }
    rc = lep_device_init(&s->dev, &s->info, &s->rated, o->filter);
    if (rc != LEP_OK) {
        lep_priv_set_err(err, errlen, "cannot set up the device: %s", lep_strerror(rc));
        return rc;
    }
    if (o->start_streaming) {
        /* A stream left running by an earlier program: start it ourselves. */
        static const lep_command start = {LEP_CMD_START, 0};
        uint8_t frame[LEP_MAX_FRAME], ans[LEP_MAX_FRAME];
        size_t len = 0, ans_len = 0, off = 0;
        lep_device_event ev;
        if (lep_command_frame(&start, frame, sizeof frame, &len) == LEP_OK) {
            while (off < len)
                off += lep_device_feed(&s->dev, frame + off, len - off, &ev, ans, sizeof ans,
                                       &ans_len);
        }
        if (lep_device_streaming(&s->dev))
            stream_begins(s, lep_priv_monotonic_ns());
    }
    return LEP_OK;
}

int lep_sim_start(const lep_sim_options *o, lep_sim **out, char *err, size_t errlen)
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
    s->wake[0] = s->wake[1] = -1;
    s->req_stall_ms = -1;
    s->opt = *o;
    s->link = s->opt.link;
    s->period_ns = NS_PER_S / o->rate_hz;
    s->rng = o->seed ^ 0x5EEDF00DCAFEBEEFu;
    (void)lep_sim_model_rated(s->opt.model, &s->rated);
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
    rc = init_device(s, err, errlen);
    if (rc == LEP_OK && (pipe(s->wake) != 0 || set_flags(s->wake[0]) != 0 ||
                         set_flags(s->wake[1]) != 0)) {
        lep_priv_set_err(err, errlen, "cannot create a pipe: %s", strerror(errno));
        rc = LEP_E_IO;
    }
    if (rc == LEP_OK)
        rc = open_pty(s, err, errlen);
    if (rc != LEP_OK) {
        s->link = "";
        lep_sim_stop(s);
        return rc;
    }
    copy_field(s->port, sizeof s->port, s->link[0] ? s->link : s->pty);
    s->power_on = lep_priv_monotonic_ns();
    if (s->streaming)
        s->t0 = s->power_on;
    if (o->stall_ms > 0)
        s->stall_at = s->power_on + (int64_t)(o->stall_after_s * NS_PER_S) + 1;
    if (o->hangup_after_s > 0)
        s->hangup_at = s->power_on + (int64_t)(o->hangup_after_s * NS_PER_S);
    publish(s);
    /* The thread takes no signals: they belong to the application. */
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    rc = pthread_create(&s->thread, NULL, serve, s);
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

const char *lep_sim_port(const lep_sim *s)
{
    return s ? s->port : "";
}

const char *lep_sim_pty_path(const lep_sim *s)
{
    return s ? s->pty : "";
}

static void request(lep_sim *s, bool *flag, int stall_ms)
{
    static const uint8_t one = 1;
    if (s == NULL)
        return;
    pthread_mutex_lock(&s->lock);
    if (flag != NULL)
        *flag = true;
    if (stall_ms >= 0)
        s->req_stall_ms = stall_ms;
    pthread_mutex_unlock(&s->lock);
    if (s->wake[1] >= 0)
        (void)!write(s->wake[1], &one, 1);
}

void lep_sim_power_cycle(lep_sim *s)
{
    if (s != NULL)
        request(s, &s->req_power_cycle, -1);
}

void lep_sim_hangup(lep_sim *s)
{
    if (s != NULL)
        request(s, &s->req_hangup, -1);
}

void lep_sim_stall(lep_sim *s, int ms)
{
    if (s != NULL)
        request(s, NULL, ms < 0 ? 0 : ms);
}

void lep_sim_get_stats(lep_sim *s, lep_sim_stats *out)
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
        request(s, &s->req_stop, -1);
        pthread_join(s->thread, NULL);
    }
    remove_link(s);
    close_pty(s);
    if (s->wake[0] >= 0)
        close(s->wake[0]);
    if (s->wake[1] >= 0)
        close(s->wake[1]);
    lep_priv_signal_free(&s->sig);
    pthread_mutex_destroy(&s->lock);
    free(s);
}
