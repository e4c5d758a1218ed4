/* Win32 serial port: open, configure, exclusive access, timed reads.
 *
 * The same private interface as serial_posix.c (leptrino/serial.h): a port is
 * "COM5" or "\\.\COM5" (the device namespace, which COM10 and above need;
 * Microsoft docs: "Naming Files, Paths, and Namespaces"), opened with
 * CreateFile and no sharing (a second opener fails: exclusive, as flock +
 * TIOCEXCL on POSIX), 460800 8N1, no flow control (DCB, SetCommState).
 *
 * Reads (the client's contract: wait at most timeout_ms, < 0 forever, 0 poll;
 * return what is there at once): ClearCommError gives the bytes queued; if
 * there are some they are read (a ReadFile of queued bytes returns at once
 * whatever the timeouts); if none, one byte is read with
 * ReadTotalTimeoutConstant = timeout_ms (interval and multiplier 0: the call
 * returns as soon as that byte is there, or after the constant), then what
 * queued behind it. COMMTIMEOUTS' "return on first byte" mode (MAXDWORD
 * interval and multiplier) is not used: Wine 8.0 waits its whole constant.
 * WaitCommEvent is not used either (unusable on a Wine pty). A failed read,
 * write or ClearCommError means the device went away (an unplugged USB port
 * fails them with ERROR_ACCESS_DENIED, ERROR_GEN_FAILURE,
 * ERROR_DEVICE_NOT_CONNECTED ...): LEP_E_DISCONNECTED from then on.
 *
 * A name a virtual sensor of this program lists ("sim:1", or its link
 * option) is opened as its in-process loopback port instead
 * (serial_loopback_win32.c), with the same read and write contract. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <winsock2.h> /* before windows.h (serial_loopback.h) */
#include <windows.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "leptrino/serial.h"
#include "struct_api.h"
#include "posix_clock.h"
#include "serial_loopback.h"

/* How long a write may wait for the port to take its bytes. */
#define WRITE_STALL_MS 2000
#define PORT_NAME_MAX 260
/* Driver queue sizes asked for (SetupComm): a quarter second of stream. */
#define IN_QUEUE 16384
#define OUT_QUEUE 4096

struct lep_serial {
    HANDLE h;                /* the COM port, or INVALID_HANDLE_VALUE with loop */
    lep_loopback_port *loop; /* a virtual sensor's port, or NULL */
    bool dead;               /* the port vanished: every call says so */
    bool have_saved;
    DCB saved_dcb;
    COMMTIMEOUTS saved_timeouts;
    DWORD read_timeout; /* ReadTotalTimeoutConstant now set, MAXDWORD: none yet */
    lep_serial_info info;
    char path[PORT_NAME_MAX]; /* as given, for messages and lep_serial_path */
    lep_client_rx rx;         /* read buffer of the blocking client calls */
};

/* "COM5" -> "\\.\COM5"; anything else (already "\\.\COM5", or another
 * device name) as given. */
static void device_name(const char *path, char *out, size_t cap)
{
    bool com = (path[0] == 'C' || path[0] == 'c') && (path[1] == 'O' || path[1] == 'o') &&
               (path[2] == 'M' || path[2] == 'm') && path[3] >= '0' && path[3] <= '9';
    (void)snprintf(out, cap, "%s%s", com ? "\\\\.\\" : "", path);
}

static int open_error(DWORD e, const char *path, char *err, size_t errlen)
{
    switch (e) {
    case ERROR_FILE_NOT_FOUND:
    case ERROR_PATH_NOT_FOUND:
    case ERROR_INVALID_NAME:
    case ERROR_BAD_PATHNAME:
    case ERROR_BAD_NETPATH:
        lep_priv_set_err(err, errlen, "%s: no such port", path);
        return LEP_E_NOT_FOUND;
    case ERROR_GEN_FAILURE:
    case ERROR_DEVICE_NOT_CONNECTED:
    case ERROR_NOT_READY:
        lep_priv_set_err(err, errlen, "%s: no device behind this port (unplugged?)", path);
        return LEP_E_NOT_FOUND;
    case ERROR_SHARING_VIOLATION:
        lep_priv_set_err(err, errlen, "%s: in use by another program", path);
        return LEP_E_BUSY;
    case ERROR_ACCESS_DENIED:
        /* What CreateFile gives for a COM port another program holds open
         * (serial ports are not shareable); a real permission problem is rare. */
        lep_priv_set_err(err, errlen, "%s: in use by another program (or access denied)", path);
        return LEP_E_BUSY;
    default:
        lep_priv_set_err(err, errlen, "%s: cannot open: Windows error %lu", path, (unsigned long)e);
        return LEP_E_IO;
    }
}

static int configure(lep_serial *s, char *err, size_t errlen)
{
    DCB d;
    COMMTIMEOUTS t;
    memset(&d, 0, sizeof d);
    d.DCBlength = sizeof d;
    if (!GetCommState(s->h, &d) || !GetCommTimeouts(s->h, &t)) {
        lep_priv_set_err(err, errlen, "%s: not a serial port (cannot read its settings)", s->path);
        return LEP_E_NOT_TTY;
    }
    s->saved_dcb = d;
    s->saved_timeouts = t;
    s->have_saved = true;
    (void)SetupComm(s->h, IN_QUEUE, OUT_QUEUE);
    d.BaudRate = LEP_BAUD;
    d.ByteSize = 8;
    d.Parity = NOPARITY;
    d.StopBits = ONESTOPBIT;
    d.fBinary = TRUE;
    d.fParity = FALSE;
    d.fOutxCtsFlow = FALSE;
    d.fOutxDsrFlow = FALSE;
    d.fDtrControl = DTR_CONTROL_ENABLE;
    d.fDsrSensitivity = FALSE;
    d.fTXContinueOnXoff = TRUE;
    d.fOutX = FALSE;
    d.fInX = FALSE;
    d.fErrorChar = FALSE;
    d.fNull = FALSE;
    d.fRtsControl = RTS_CONTROL_ENABLE;
    d.fAbortOnError = FALSE;
    if (!SetCommState(s->h, &d)) {
        lep_priv_set_err(err, errlen, "%s: cannot set 460800 8N1: Windows error %lu", s->path,
                         (unsigned long)GetLastError());
        return LEP_E_IO;
    }
    /* A driver may take a rate it cannot do without an error (Wine reads a
     * non-standard one back as 38400): look. */
    memset(&d, 0, sizeof d);
    d.DCBlength = sizeof d;
    if (GetCommState(s->h, &d) && d.BaudRate != LEP_BAUD) {
        lep_priv_set_err(err, errlen, "%s: the port does not take 460800 baud (it says %lu)",
                         s->path, (unsigned long)d.BaudRate);
        return LEP_E_IO;
    }
    memset(&t, 0, sizeof t);
    t.ReadIntervalTimeout = 0;
    t.ReadTotalTimeoutMultiplier = 0;
    t.ReadTotalTimeoutConstant = 0;
    t.WriteTotalTimeoutMultiplier = 0;
    t.WriteTotalTimeoutConstant = WRITE_STALL_MS;
    if (!SetCommTimeouts(s->h, &t)) {
        lep_priv_set_err(err, errlen, "%s: cannot set the timeouts: Windows error %lu", s->path,
                         (unsigned long)GetLastError());
        return LEP_E_IO;
    }
    s->read_timeout = 0;
    /* Forget whatever an earlier program left in the buffers. */
    (void)PurgeComm(s->h, PURGE_RXABORT | PURGE_RXCLEAR | PURGE_TXABORT | PURGE_TXCLEAR);
    return LEP_OK;
}

int lep_serial_open(const char *path, lep_serial **out, char *err, size_t errlen)
{
    char dev[PORT_NAME_MAX + 4];
    lep_loopback_port *loop = NULL;
    lep_serial *s;
    HANDLE h;
    int rc;
    if (err != NULL && errlen > 0)
        err[0] = '\0';
    if (out != NULL)
        *out = NULL;
    if (path == NULL || out == NULL || path[0] == '\0') {
        lep_priv_set_err(err, errlen, "no port given");
        return LEP_E_ARG;
    }
    if (strlen(path) >= PORT_NAME_MAX) {
        lep_priv_set_err(err, errlen, "%.64s...: path too long", path);
        return LEP_E_NOT_FOUND;
    }
    rc = lep_priv_loopback_open(path, &loop, err, errlen);
    if (rc != LEP_OK)
        return rc;
    if (loop != NULL) {
        s = calloc(1, sizeof *s);
        if (s == NULL) {
            lep_priv_loopback_close(loop);
            lep_priv_set_err(err, errlen, "%s: out of memory", path);
            return LEP_E_IO;
        }
        s->h = INVALID_HANDLE_VALUE;
        s->loop = loop;
        s->info.ftdi_latency_ms = -1;
        memcpy(s->path, path, strlen(path) + 1);
        *out = s;
        return LEP_OK;
    }
    device_name(path, dev, sizeof dev);
    /* dwShareMode 0: nobody else may open the port while we hold it. */
    h = CreateFileA(dev, GENERIC_READ | GENERIC_WRITE, 0, NULL, OPEN_EXISTING,
                    FILE_ATTRIBUTE_NORMAL, NULL);
    if (h == INVALID_HANDLE_VALUE)
        return open_error(GetLastError(), path, err, errlen);
    if (GetFileType(h) != FILE_TYPE_CHAR) {
        lep_priv_set_err(err, errlen, "%s: not a serial port", path);
        CloseHandle(h);
        return LEP_E_NOT_TTY;
    }
    s = calloc(1, sizeof *s);
    if (s == NULL) {
        CloseHandle(h);
        lep_priv_set_err(err, errlen, "%s: out of memory", path);
        return LEP_E_IO;
    }
    s->h = h;
    s->info.ftdi_latency_ms = -1; /* the FTDI driver's own setting (docs/windows.md) */
    s->read_timeout = MAXDWORD;
    memcpy(s->path, path, strlen(path) + 1);
    rc = configure(s, err, errlen);
    if (rc != LEP_OK) {
        lep_serial_close(s);
        return rc;
    }
    *out = s;
    return LEP_OK;
}

void lep_serial_close(lep_serial *s)
{
    if (s == NULL)
        return;
    if (s->loop != NULL) {
        lep_priv_loopback_close(s->loop);
        free(s);
        return;
    }
    if (!s->dead && s->have_saved) {
        (void)SetCommState(s->h, &s->saved_dcb);
        (void)SetCommTimeouts(s->h, &s->saved_timeouts);
    }
    CloseHandle(s->h);
    free(s);
}

/* Bytes waiting in the driver's input queue, or -1 when the port is gone. */
static long queued(lep_serial *s)
{
    DWORD errors = 0;
    COMSTAT st;
    memset(&st, 0, sizeof st);
    if (!ClearCommError(s->h, &errors, &st))
        return -1;
    return st.cbInQue > (DWORD)LONG_MAX ? LONG_MAX : (long)st.cbInQue;
}

/* ReadFile of up to cap bytes under the timeouts in force: the count, or -1. */
static long read_some(lep_serial *s, uint8_t *buf, size_t cap)
{
    DWORD got = 0;
    if (cap > (size_t)INT_MAX)
        cap = (size_t)INT_MAX;
    if (!ReadFile(s->h, buf, (DWORD)cap, &got, NULL))
        return -1;
    return (long)got;
}

static int set_read_timeout(lep_serial *s, DWORD ms)
{
    COMMTIMEOUTS t;
    if (s->read_timeout == ms)
        return 0;
    memset(&t, 0, sizeof t);
    /* All read fields 0 but the constant: the read ends when the bytes asked
     * for are there or after the constant; 0 everywhere waits without end. */
    t.ReadTotalTimeoutConstant = ms;
    t.WriteTotalTimeoutConstant = WRITE_STALL_MS;
    if (!SetCommTimeouts(s->h, &t))
        return -1;
    s->read_timeout = ms;
    return 0;
}

static int gone(lep_serial *s)
{
    s->dead = true;
    return LEP_E_DISCONNECTED;
}

static int serial_read(void *user, uint8_t *buf, size_t cap, int timeout_ms)
{
    lep_serial *s = user;
    int64_t deadline = 0;
    long n, more;
    if (s == NULL || (buf == NULL && cap > 0))
        return LEP_E_ARG;
    if (s->dead)
        return LEP_E_DISCONNECTED;
    if (cap == 0)
        return 0;
    if (timeout_ms > 0)
        deadline = lep_priv_monotonic_ns() + (int64_t)timeout_ms * 1000000;
    for (;;) {
        DWORD wait;
        n = queued(s);
        if (n < 0)
            return gone(s);
        if (n > 0) {
            n = read_some(s, buf, (size_t)n < cap ? (size_t)n : cap);
            if (n < 0)
                return gone(s);
            if (n > 0)
                return (int)n;
        }
        if (timeout_ms == 0)
            return 0;
        /* Nothing queued: wait for one byte, at most what is left. */
        if (timeout_ms < 0) {
            wait = 0; /* no total timeout: until a byte comes */
        } else {
            int left = lep_priv_ms_left(deadline);
            if (left <= 0)
                return 0;
            wait = (DWORD)left;
        }
        if (set_read_timeout(s, wait) != 0)
            return gone(s);
        n = read_some(s, buf, 1);
        if (n < 0)
            return gone(s);
        if (n == 0)
            continue; /* the constant passed (or a spurious return): look again */
        /* Whatever queued behind that byte comes at once. */
        more = cap > 1 ? queued(s) : 0;
        if (more > 0) {
            more = read_some(s, buf + 1, (size_t)more < cap - 1 ? (size_t)more : cap - 1);
            if (more < 0)
                return gone(s);
            n += more;
        }
        return (int)n;
    }
}

static int serial_write(void *user, const uint8_t *data, size_t len)
{
    lep_serial *s = user;
    size_t off = 0;
    if (s == NULL || (data == NULL && len > 0))
        return LEP_E_ARG;
    if (s->dead)
        return LEP_E_DISCONNECTED;
    while (off < len) {
        DWORD put = 0, chunk = (DWORD)(len - off > 65536u ? 65536u : len - off);
        if (!WriteFile(s->h, data + off, chunk, &put, NULL))
            return gone(s);
        if (put == 0)
            return LEP_E_TIMEOUT; /* WriteTotalTimeoutConstant passed */
        off += put;
    }
    return LEP_OK;
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
    if (s != NULL && s->loop != NULL) {
        io->write = lep_priv_loopback_write;
        io->read = lep_priv_loopback_read;
        io->user = s->loop;
    }
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
    (void)s;
    return -1; /* a HANDLE, not a file descriptor: nothing to poll() */
}
