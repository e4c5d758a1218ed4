/* The streaming baselines of leptrino-bench: a host program read loop the way
 * field programs for this sensor stream (../shared/DESIGN.md, "Practices to
 * avoid"), written for this benchmark from that description. The port is
 * opened raw 8N1 at 460800 baud with VMIN=0/VTIME=0, so read() never blocks;
 * the loop asks read() for ONE byte per call and hands it to the plain
 * byte-at-a-time decoder (plain_decoder.c). When a read returns 0, the
 * "sleep" variant sleeps a fixed 1 ms (relative, usleep-style) and tries
 * again; the "busy" variant tries again at once. The start and stop commands
 * are framed with leptrino's encoder (not what is measured). */
#define _DEFAULT_SOURCE
#include "e2e.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "leptrino/leptrino.h"

#define FIELD_IDLE_SLEEP_NS 1000000L /* the fixed 1 ms a sleeping loop waits after an empty read */

static double mono_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

int field_open(field_port *f, const char *port, int sleep_when_idle)
{
    struct termios t;
    memset(f, 0, sizeof(*f));
    f->sleep_when_idle = sleep_when_idle;
    plain_init(&f->dec);
    f->fd = open(port, O_RDWR | O_NOCTTY);
    if (f->fd < 0) {
        return LEP_E_NOT_FOUND;
    }
    if (tcgetattr(f->fd, &t) != 0) {
        close(f->fd);
        f->fd = -1;
        return LEP_E_NOT_TTY;
    }
    cfmakeraw(&t); /* 8 data bits, no parity, no echo, no translation */
    t.c_cflag &= (tcflag_t) ~(CSTOPB | PARENB | CRTSCTS);
    t.c_cflag |= CS8 | CLOCAL | CREAD;
    t.c_cc[VMIN] = 0; /* read() returns at once, with whatever is there (maybe nothing) */
    t.c_cc[VTIME] = 0;
    if (cfsetispeed(&t, B460800) != 0 || cfsetospeed(&t, B460800) != 0 ||
        tcsetattr(f->fd, TCSANOW, &t) != 0) {
        close(f->fd);
        f->fd = -1;
        return LEP_E_IO;
    }
    (void)tcflush(f->fd, TCIOFLUSH);
    return LEP_OK;
}

int field_send(field_port *f, uint8_t code)
{
    lep_command cmd;
    uint8_t frame[32];
    size_t len = 0;
    cmd.code = code;
    cmd.filter = 0;
    if (lep_command_frame(&cmd, frame, sizeof frame, &len) != LEP_OK) {
        return LEP_E_ARG;
    }
    return write(f->fd, frame, len) == (ssize_t)len ? LEP_OK : LEP_E_IO;
}

/* One byte per read(); a message the plain decoder completes with code `want`
 * and `want_len` bytes ends the loop, its message left in f->dec.buf. */
static int read_until(field_port *f, uint8_t want, size_t want_len, int timeout_ms)
{
    double give_up = mono_s() + timeout_ms / 1e3;
    for (;;) {
        uint8_t b;
        ssize_t got = read(f->fd, &b, 1);
        if (got == 1) {
            if (plain_step(&f->dec, b) && f->dec.n == want_len && f->dec.buf[2] == want) {
                return LEP_OK;
            }
            continue;
        }
        if (got < 0 && errno != EAGAIN && errno != EINTR) {
            return LEP_E_IO;
        }
        if (mono_s() >= give_up) {
            return LEP_E_TIMEOUT;
        }
        if (f->sleep_when_idle) {
            struct timespec ts = { 0, FIELD_IDLE_SLEEP_NS };
            (void)nanosleep(&ts, NULL);
            f->sleeps++;
        }
    }
}

int field_next(field_port *f, uint16_t *seq, int timeout_ms)
{
    int rc = read_until(f, LEP_CMD_START, LEP_LEN_SAMPLE, timeout_ms);
    if (rc == LEP_OK) {
        *seq = (uint16_t)(f->dec.buf[16] | (unsigned)f->dec.buf[17] << 8); /* reserved bytes, LE */
    }
    return rc;
}

void field_close(field_port *f)
{
    if (f->fd < 0) {
        return;
    }
    /* Stop, then wait (bounded) for its answer so the sensor has taken it in
     * before the port closes; the data still in flight is read and dropped. */
    if (field_send(f, LEP_CMD_STOP) == LEP_OK) {
        (void)read_until(f, LEP_CMD_STOP, LEP_LEN_HEADER, 500);
    }
    close(f->fd);
    f->fd = -1;
}
