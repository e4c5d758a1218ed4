/* Virtual sensor: its pseudo-terminal (open, raw mode, close) and the output
 * queue written to the master side. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _GNU_SOURCE /* ppoll, ptsname_r */
#endif

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

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

int lep_priv_sim_set_flags(int fd)
{
    int fl = fcntl(fd, F_GETFL);
    if (fl < 0 || fcntl(fd, F_SETFL, fl | O_NONBLOCK) != 0)
        return -1;
    fl = fcntl(fd, F_GETFD);
    if (fl < 0 || fcntl(fd, F_SETFD, fl | FD_CLOEXEC) != 0)
        return -1;
    return 0;
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
    if (grantpt(m) != 0 || unlockpt(m) != 0 || lep_priv_sim_set_flags(m) != 0) {
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
    while (s->out_len > 0 && s->master >= 0) {
        int64_t t_call = s->trace != NULL ? lep_priv_monotonic_ns() : 0;
        ssize_t n = write(s->master, s->out, s->out_len);
        if (n > 0) {
            if (s->trace != NULL)
                lep_priv_sim_trace_written(s->trace, (size_t)n, t_call, lep_priv_monotonic_ns());
            memmove(s->out, s->out + n, s->out_len - (size_t)n);
            s->out_len -= (size_t)n;
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        break; /* EAGAIN: nobody reads now; keep it queued */
    }
}

bool lep_priv_sim_queue_full(const lep_sim *s)
{
    return s->out_len + LEP_SIM_FRAME_ROOM > OUTQ_SIZE;
}

bool lep_priv_sim_queue(lep_sim *s, const uint8_t *b, size_t n)
{
    if (s->out_len + n > OUTQ_SIZE)
        return false;
    memcpy(s->out + s->out_len, b, n);
    s->out_len += n;
    return true;
}
