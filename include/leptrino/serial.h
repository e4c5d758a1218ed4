/* POSIX serial backend: open a sensor's port and hand the client its I/O.
 *
 * termios raw mode, 460800 8N1, no flow control, exclusive access (TIOCEXCL
 * and flock). Reads wait with poll() and honour the timeout; a vanished port
 * gives LEP_E_DISCONNECTED. Linux and macOS. Not thread-safe per port. */
#ifndef LEPTRINO_SERIAL_H
#define LEPTRINO_SERIAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "client.h"
#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LEP_BAUD 460800

/* An open port. Allocated by lep_serial_open, freed by lep_serial_close. */
typedef struct lep_serial lep_serial;

/* What lep_serial_open could apply for latency (never a failure if not). */
typedef struct lep_serial_info {
    bool low_latency;    /* ASYNC_LOW_LATENCY flag set on the port */
    int ftdi_latency_ms; /* FTDI latency timer now in force, or -1 if not FTDI/unknown */
    bool ftdi_lowered;   /* the timer was lowered by this open */
} lep_serial_info;

/* Open path. On failure returns LEP_E_NOT_FOUND, LEP_E_PERMISSION,
 * LEP_E_NOT_TTY, LEP_E_BUSY or LEP_E_IO and, when err is not NULL, writes a
 * one-line message naming the path into err[0..errlen). */
LEP_API int lep_serial_open(const char *path, lep_serial **out, char *err, size_t errlen);

/* Restore the port's settings, release the lock, close, free. NULL is fine. */
LEP_API void lep_serial_close(lep_serial *s);

/* The I/O table for lep_client_init; valid until lep_serial_close. */
LEP_API void lep_serial_get_io(lep_serial *s, lep_io *io);

/* lep_client_init(c, io of s), with the port's read buffer for the blocking calls
 * (lep_client_set_rx); one client per port. */
LEP_API int lep_serial_client_init(lep_client *c, lep_serial *s);

LEP_API void lep_serial_get_info(const lep_serial *s, lep_serial_info *info);
LEP_API const char *lep_serial_path(const lep_serial *s);
/* The file descriptor, for callers that poll several ports. */
LEP_API int lep_serial_fd(const lep_serial *s);

/* Milliseconds of a monotonic clock (the io.now_ms of this backend). */
LEP_API uint32_t lep_monotonic_ms(void);
/* Seconds of the same monotonic clock, with sub-microsecond resolution. */
LEP_API double lep_monotonic_seconds(void);

/* A serial port found on this machine. */
typedef struct lep_port_info {
    char path[256];        /* /dev/ttyACM0 */
    char by_id[256];       /* /dev/serial/by-id/... or empty */
    char description[128]; /* USB product/manufacturer when known */
    uint16_t vid;          /* USB vendor id, 0 if unknown */
    uint16_t pid;          /* USB product id, 0 if unknown */
    bool likely_sensor;    /* STM VCP 0483:5740 or FTDI 0403:6001 */
} lep_port_info;

/* List serial ports into out[0..max); *n gets how many exist (may exceed max). */
LEP_API int lep_serial_list(lep_port_info *out, size_t max, size_t *n);

#ifdef __cplusplus
}
#endif

#endif
