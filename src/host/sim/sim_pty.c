/* Virtual sensor on POSIX: its port, a pseudo-terminal (open, raw mode,
 * close); the requests' wake-up pipe; waiting on both (ppoll); the output
 * queue written to the master side; the serving thread's start. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _GNU_SOURCE /* ppoll, ptsname_r */
#endif

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#if defined(__linux__)
#include <sys/prctl.h>
#endif

#include "errmsg.h"
#include "leptrino/error.h"
#include "posix_clock.h"
#include "sim_priv.h"

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

void lep_priv_sim_port_init(lep_sim *s)
{
    s->master = s->slave = -1;
    s->wake[0] = s->wake[1] = -1;
}

int lep_priv_sim_wake_open(lep_sim *s, char *err, size_t errlen)
{
    if (pipe(s->wake) != 0 || set_flags(s->wake[0]) != 0 || set_flags(s->wake[1]) != 0) {
        lep_priv_set_err(err, errlen, "cannot create a pipe: %s", strerror(errno));
        return LEP_E_IO;
    }
    return LEP_OK;
}

void lep_priv_sim_wake(lep_sim *s)
{
    static const uint8_t one = 1;
    if (s->wake[1] >= 0)
        (void)!write(s->wake[1], &one, 1);
}

void lep_priv_sim_wake_drain(lep_sim *s)
{
    uint8_t junk[64];
    while (read(s->wake[0], junk, sizeof junk) > 0) {
    }
}

void lep_priv_sim_wake_close(lep_sim *s)
{
    if (s->wake[0] >= 0)
        close(s->wake[0]);
    if (s->wake[1] >= 0)
        close(s->wake[1]);
    s->wake[0] = s->wake[1] = -1;
}

/* Open a new pty: master non-blocking, slave raw and held open by us so the
 * master never sees EIO when the client closes its side. */
int lep_priv_sim_open_pty(lep_sim *s, char *err, size_t errlen)
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
    if (s->link[0] != '\0') {
        int rc = lep_priv_sim_relink(s, err, errlen);
        if (rc != LEP_OK) {
            close(s->slave);
            close(s->master);
            s->slave = s->master = -1;
            return rc;
        }
    }
    return LEP_OK;
}

void lep_priv_sim_close_pty(lep_sim *s)
{
    if (s->master >= 0)
        close(s->master);
    if (s->slave >= 0)
        close(s->slave);
    s->master = s->slave = -1;
}

void lep_priv_sim_flush_out(lep_sim *s)
{
    size_t ready;
    while ((ready = lep_priv_sim_queue_ready(s)) > 0 && s->master >= 0) {
        int64_t t_call = s->trace != NULL ? lep_priv_monotonic_ns() : 0;
        ssize_t n = write(s->master, s->out, ready);
        if (n > 0) {
            if (s->trace != NULL)
                lep_priv_sim_trace_written(s->trace, (size_t)n, t_call, lep_priv_monotonic_ns());
            lep_priv_sim_queue_written(s, (size_t)n);
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        break; /* EAGAIN: nobody reads now; keep it queued */
    }
}

int lep_priv_sim_wait(lep_sim *s, bool port, bool want_out, int64_t until, unsigned *ready)
{
    struct pollfd p[2];
    nfds_t n = port ? 2 : 1;
    int rc;
    p[0].fd = s->wake[0];
    p[0].events = POLLIN;
    p[0].revents = 0;
    p[1].fd = s->master;
    p[1].events = (short)(POLLIN | (want_out ? POLLOUT : 0));
    p[1].revents = 0;
    *ready = 0;
#if defined(__linux__)
    {
        struct timespec ts, *tp = NULL;
        if (until != 0) {
            int64_t left = until - lep_priv_monotonic_ns();
            if (left < 0)
                left = 0;
            ts.tv_sec = (time_t)(left / 1000000000);
            ts.tv_nsec = (long)(left % 1000000000);
            tp = &ts;
        }
        rc = ppoll(p, n, tp, NULL);
    }
#else
    {
        int ms = -1;
        if (until != 0) {
            int64_t left = until - lep_priv_monotonic_ns();
            ms = left <= 0 ? 0 : (int)((left + 999999) / 1000000);
        }
        rc = poll(p, n, ms);
    }
#endif
    if (rc < 0)
        return errno == EINTR ? 0 : -1;
    if (p[0].revents & POLLIN)
        *ready |= LEP_SIM_READY_WAKE;
    if (port && (p[1].revents & (POLLIN | POLLHUP | POLLERR)))
        *ready |= LEP_SIM_READY_PORT;
    return 0;
}

long lep_priv_sim_read_port(lep_sim *s, uint8_t *buf, size_t cap)
{
    ssize_t r = read(s->master, buf, cap);
    if (r > 0)
        return (long)r;
    /* EIO: no slave open (cannot happen while we hold one) */
    return r < 0 && errno == EIO ? -1 : 0;
}

int lep_priv_sim_start_thread(lep_sim *s, void *(*fn)(void *))
{
    sigset_t all, old;
    int rc;
    /* The thread takes no signals: they belong to the application. */
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    rc = pthread_create(&s->thread, NULL, fn, s);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    return rc;
}

void lep_priv_sim_thread_init(void)
{
#if defined(__linux__) && defined(PR_SET_TIMERSLACK)
    /* Wake at each deadline, not up to 50 us after it (the default slack of
     * a thread's timers; this thread's only, the host program keeps its own). */
    (void)prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
#endif
}
