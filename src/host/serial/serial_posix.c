/* POSIX serial port: open, configure, exclusive lock, poll-based I/O. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#if defined(__linux__)
#include <linux/serial.h>
#endif
#if defined(__APPLE__)
#include <IOKit/serial/ioss.h>
#endif

#include "errmsg.h"
#include "leptrino/error.h"
#include "leptrino/serial.h"
#include "struct_api.h"
#include "fd_write.h"
#include "posix_clock.h"

/* How long a write may wait for room in the port's output buffer. */
#define WRITE_STALL_MS 2000

struct lep_serial {
    int fd;
    bool dead; /* the port vanished: every call says so */
    bool have_saved;
    bool serial_changed; /* low-latency flag set by us */
#if defined(__linux__)
    struct serial_struct saved_serial;
#endif
    struct termios saved;
    lep_serial_info info;
    int ftdi_saved_ms; /* value to restore at close, or -1 */
    char ftdi_attr[PATH_MAX];
    char path[PATH_MAX];
    lep_client_rx rx; /* read buffer of the blocking client calls */
};

static int open_error(int e, const char *path, char *err, size_t errlen)
{
    switch (e) {
    case ENOENT:
    case ENOTDIR:
    case ELOOP:
    case ENAMETOOLONG:
        lep_priv_set_err(err, errlen, "%s: no such port", path);
        return LEP_E_NOT_FOUND;
    case ENXIO:
    case ENODEV:
        lep_priv_set_err(err, errlen, "%s: no device behind this port (unplugged?)", path);
        return LEP_E_NOT_FOUND;
    case EACCES:
    case EPERM:
    case EROFS:
        lep_priv_set_err(err, errlen,
                         "%s: permission denied (add yourself to the port's group, e.g. dialout, "
                         "or use a udev rule)",
                         path);
        return LEP_E_PERMISSION;
    case EBUSY:
        lep_priv_set_err(err, errlen, "%s: in use by another program", path);
        return LEP_E_BUSY;
    case EISDIR:
        lep_priv_set_err(err, errlen, "%s: not a terminal device (a directory)", path);
        return LEP_E_NOT_TTY;
    default:
        lep_priv_set_err(err, errlen, "%s: cannot open: %s", path, strerror(e));
        return LEP_E_IO;
    }
}

/* Raw 8N1, no flow control, no echo, no signals, no translation. */
static void make_raw(struct termios *t)
{
    t->c_iflag &= ~(tcflag_t)(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON |
                              IXOFF | IXANY | INPCK);
    t->c_oflag &= ~(tcflag_t)OPOST;
    t->c_lflag &= ~(tcflag_t)(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    t->c_cflag &= ~(tcflag_t)(CSIZE | PARENB | CSTOPB);
#ifdef CRTSCTS
    t->c_cflag &= ~(tcflag_t)CRTSCTS;
#endif
    t->c_cflag |= (tcflag_t)(CS8 | CREAD | CLOCAL);
    t->c_cc[VMIN] = 1;
    t->c_cc[VTIME] = 0;
}

static int configure(lep_serial *s, char *err, size_t errlen)
{
    struct termios t;
    if (tcgetattr(s->fd, &t) != 0) {
        lep_priv_set_err(err, errlen, "%s: cannot read the port settings: %s", s->path,
                         strerror(errno));
        return LEP_E_IO;
    }
    s->saved = t;
    s->have_saved = true;
    make_raw(&t);
#if defined(__APPLE__)
    /* No B460800 on macOS: set a standard speed, then the real one by ioctl. */
    cfsetispeed(&t, B230400);
    cfsetospeed(&t, B230400);
#else
    cfsetispeed(&t, B460800);
    cfsetospeed(&t, B460800);
#endif
    if (tcsetattr(s->fd, TCSANOW, &t) != 0) {
        lep_priv_set_err(err, errlen, "%s: cannot set 460800 8N1 raw mode: %s", s->path,
                         strerror(errno));
        return LEP_E_IO;
    }
#if defined(__APPLE__)
    {
        speed_t speed = LEP_BAUD;
        if (ioctl(s->fd, IOSSIOSPEED, &speed) != 0) {
            lep_priv_set_err(err, errlen, "%s: cannot set 460800 baud: %s", s->path,
                             strerror(errno));
            return LEP_E_IO;
        }
    }
#endif
    /* Forget whatever an earlier program left in the buffers. */
    tcflush(s->fd, TCIOFLUSH);
    return LEP_OK;
}

static void set_low_latency(lep_serial *s)
{
#if defined(__linux__) && defined(TIOCGSERIAL) && defined(ASYNC_LOW_LATENCY)
    struct serial_struct ss;
    if (ioctl(s->fd, TIOCGSERIAL, &ss) != 0)
        return;
    if ((unsigned)ss.flags & (unsigned)ASYNC_LOW_LATENCY) {
        s->info.low_latency = true;
        return;
    }
    s->saved_serial = ss;
    ss.flags = (int)((unsigned)ss.flags | (unsigned)ASYNC_LOW_LATENCY);
    if (ioctl(s->fd, TIOCSSERIAL, &ss) == 0) {
        s->info.low_latency = true;
        s->serial_changed = true;
    }
#else
    (void)s;
#endif
}

static int read_int_file(const char *path, int *value)
{
    char buf[32];
    size_t n;
    FILE *f = fopen(path, "re");
    if (f == NULL)
        return -1;
    n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    {
        char *end;
        long v = strtol(buf, &end, 10);
        if (end == buf || v < 0 || v > 10000)
            return -1;
        *value = (int)v;
    }
    return 0;
}

static int write_int_file(const char *path, int value)
{
    int ok;
    FILE *f = fopen(path, "we");
    if (f == NULL)
        return -1;
    ok = fprintf(f, "%d\n", value) > 0;
    if (fclose(f) != 0)
        ok = 0;
    return ok ? 0 : -1;
}

/* FTDI adapters hold received bytes up to latency_timer ms (16 by default):
 * lower it to 1 ms when the sysfs attribute is writable. */
static void lower_ftdi_latency(lep_serial *s)
{
    static const char *const forms[] = { "/sys/class/tty/%s/device/latency_timer",
                                         "/sys/class/tty/%s/device/../latency_timer" };
    char real[PATH_MAX];
    const char *name;
    size_t i;
    if (realpath(s->path, real) == NULL)
        return;
    name = strrchr(real, '/');
    name = name ? name + 1 : real;
    for (i = 0; i < sizeof forms / sizeof forms[0]; i++) {
        char attr[PATH_MAX];
        int ms;
        int n = snprintf(attr, sizeof attr, forms[i], name);
        if (n < 0 || (size_t)n >= sizeof attr)
            continue;
        if (read_int_file(attr, &ms) != 0)
            continue;
        s->info.ftdi_latency_ms = ms;
        if (ms > 1 && write_int_file(attr, 1) == 0) {
            int was = ms;
            if (read_int_file(attr, &ms) == 0 && ms == 1) {
                s->info.ftdi_latency_ms = 1;
                s->info.ftdi_lowered = true;
                s->ftdi_saved_ms = was;
                memcpy(s->ftdi_attr, attr, sizeof attr);
            }
        }
        return;
    }
}

int lep_serial_open(const char *path, lep_serial **out, char *err, size_t errlen)
{
    lep_serial *s;
    int fd, rc;
    if (err != NULL && errlen > 0)
        err[0] = '\0';
    if (out != NULL)
        *out = NULL;
    if (path == NULL || out == NULL || path[0] == '\0') {
        lep_priv_set_err(err, errlen, "no port given");
        return LEP_E_ARG;
    }
    if (strlen(path) >= PATH_MAX) {
        lep_priv_set_err(err, errlen, "%.64s...: path too long", path);
        return LEP_E_NOT_FOUND;
    }
    fd = open(path, O_RDWR | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0)
        return open_error(errno, path, err, errlen);
    if (!isatty(fd)) {
        struct stat st;
        const char *what = "";
        if (fstat(fd, &st) == 0) {
            if (S_ISREG(st.st_mode))
                what = " (a regular file)";
            else if (S_ISCHR(st.st_mode))
                what = " (a character device that is not a tty)";
        }
        lep_priv_set_err(err, errlen, "%s: not a terminal device%s", path, what);
        close(fd);
        return LEP_E_NOT_TTY;
    }
    /* flock first: TIOCEXCL does not stop root, the lock stops everyone. */
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        int e = errno;
        close(fd);
        if (e == EWOULDBLOCK || e == EAGAIN) {
            lep_priv_set_err(err, errlen, "%s: in use by another program", path);
            return LEP_E_BUSY;
        }
        lep_priv_set_err(err, errlen, "%s: cannot lock: %s", path, strerror(e));
        return LEP_E_IO;
    }
    s = calloc(1, sizeof *s);
    if (s == NULL) {
        close(fd);
        lep_priv_set_err(err, errlen, "%s: out of memory", path);
        return LEP_E_IO;
    }
    s->fd = fd;
    s->info.ftdi_latency_ms = -1;
    s->ftdi_saved_ms = -1;
    memcpy(s->path, path, strlen(path) + 1);
#ifdef TIOCEXCL
    (void)ioctl(fd, TIOCEXCL);
#endif
    rc = configure(s, err, errlen);
    if (rc != LEP_OK) {
        lep_serial_close(s);
        return rc;
    }
    set_low_latency(s);
    lower_ftdi_latency(s);
    *out = s;
    return LEP_OK;
}

void lep_serial_close(lep_serial *s)
{
    if (s == NULL)
        return;
    if (!s->dead) {
#if defined(__linux__) && defined(TIOCSSERIAL)
        if (s->serial_changed)
            (void)ioctl(s->fd, TIOCSSERIAL, &s->saved_serial);
#endif
        if (s->have_saved)
            (void)tcsetattr(s->fd, TCSANOW, &s->saved);
    }
    if (s->ftdi_saved_ms > 1)
        (void)write_int_file(s->ftdi_attr, s->ftdi_saved_ms);
#ifdef TIOCNXCL
    if (!s->dead)
        (void)ioctl(s->fd, TIOCNXCL);
#endif
    (void)flock(s->fd, LOCK_UN);
    close(s->fd);
    free(s);
}

static bool gone_errno(int e)
{
    return e == EIO || e == ENXIO || e == ENODEV || e == EPIPE || e == EBADF;
}

static int serial_read(void *user, uint8_t *buf, size_t cap, int timeout_ms)
{
    lep_serial *s = user;
    int64_t deadline = 0;
    if (s == NULL || (buf == NULL && cap > 0))
        return LEP_E_ARG;
    if (s->dead)
        return LEP_E_DISCONNECTED;
    if (cap > INT_MAX)
        cap = INT_MAX;
    if (timeout_ms > 0)
        deadline = lep_priv_monotonic_ns() + (int64_t)timeout_ms * 1000000;
    for (;;) {
        struct pollfd p;
        int r, wait = timeout_ms < 0 ? -1 : timeout_ms == 0 ? 0 : lep_priv_ms_left(deadline);
        p.fd = s->fd;
        p.events = POLLIN;
        p.revents = 0;
        r = poll(&p, 1, wait);
        if (r < 0) {
            if (errno == EINTR)
                continue;
            return LEP_E_IO;
        }
        if (r == 0) {
            if (timeout_ms < 0 || (timeout_ms > 0 && lep_priv_ms_left(deadline) > 0))
                continue;
            return 0;
        }
        if (p.revents & POLLNVAL)
            return LEP_E_IO;
        if (p.revents & (POLLIN | POLLHUP | POLLERR)) {
            ssize_t n = read(s->fd, buf, cap);
            if (n > 0)
                return (int)n;
            if (n == 0) { /* a hung-up terminal reads as end of file */
                s->dead = true;
                return LEP_E_DISCONNECTED;
            }
            if (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK) {
                if (p.revents & (POLLHUP | POLLERR)) {
                    s->dead = true;
                    return LEP_E_DISCONNECTED;
                }
                continue;
            }
            if (gone_errno(errno)) {
                s->dead = true;
                return LEP_E_DISCONNECTED;
            }
            return LEP_E_IO;
        }
    }
}

static int serial_write(void *user, const uint8_t *data, size_t len)
{
    lep_serial *s = user;
    if (s == NULL || (data == NULL && len > 0))
        return LEP_E_ARG;
    if (s->dead)
        return LEP_E_DISCONNECTED;
    switch (lep_priv_write_all(s->fd, data, len,
                               lep_priv_monotonic_ns() + (int64_t)WRITE_STALL_MS * 1000000)) {
    case LEP_PRIV_WRITE_OK:
        return LEP_OK;
    case LEP_PRIV_WRITE_TIMEOUT:
        return LEP_E_TIMEOUT;
    case LEP_PRIV_WRITE_HANGUP:
        s->dead = true;
        return LEP_E_DISCONNECTED;
    case LEP_PRIV_WRITE_FAILED:
        if (gone_errno(errno)) { /* errno 0 (nothing taken) is not a gone port */
            s->dead = true;
            return LEP_E_DISCONNECTED;
        }
        return LEP_E_IO;
    default: /* poll failed */
        return LEP_E_IO;
    }
}

static uint32_t serial_now_ms(void *user)
{
    (void)user;
    return lep_monotonic_ms();
}

void lep_serial_get_io(lep_serial *s, lep_io *io)
{
    if (io == NULL)
        return;
    io->write = serial_write;
    io->read = serial_read;
    io->now_ms = serial_now_ms;
    io->user = s;
}

int lep_serial_client_init(lep_client *c, lep_serial *s)
{
    lep_io io;
    int rc;
    if (c == NULL || s == NULL)
        return LEP_E_ARG;
    lep_serial_get_io(s, &io);
    rc = lep_client_init(c, &io);
    return rc == LEP_OK ? lep_client_set_rx(c, &s->rx) : rc;
}

void lep_serial_get_latency_info(const lep_serial *s, lep_serial_info *info)
{
    if (info == NULL)
        return;
    if (s == NULL) {
        memset(info, 0, sizeof *info);
        info->ftdi_latency_ms = -1;
        return;
    }
    *info = s->info;
}

const char *lep_serial_path(const lep_serial *s)
{
    return s ? s->path : "";
}

int lep_serial_fd(const lep_serial *s)
{
    return s ? s->fd : -1;
}
