/* POSIX serial backend: open a sensor's port and hand the client its I/O.
 *
 * termios raw mode, 460800 8N1, no flow control, exclusive access (TIOCEXCL
 * and flock). Reads wait with poll() and honour the timeout; a vanished port
 * gives LEP_E_DISCONNECTED. Linux and macOS. Not thread-safe per port. */
#ifndef LEPTRINO_SERIAL_H
#define LEPTRINO_SERIAL_H

#include <stddef.h>
#include <stdint.h>

#include "client.h"
#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

enum lep_serial_constants {
    LEP_BAUD = 460800 /* the sensor's line rate, 8N1 */
};

/* An open port. Allocated by lep_serial_open, freed by lep_serial_close. */
typedef struct lep_serial lep_serial;

/* What lep_serial_open could apply for latency (never a failure if not),
 * as indices into the array lep_serial_get_info fills. */
enum lep_serial_info_field {
    LEP_SERIAL_LOW_LATENCY = 0,     /* 1 when the ASYNC_LOW_LATENCY flag was set on the port */
    LEP_SERIAL_FTDI_LATENCY_MS = 1, /* FTDI latency timer now in force, -1 not FTDI/unknown */
    LEP_SERIAL_FTDI_LOWERED = 2,    /* 1 when the timer was lowered by this open */
    LEP_SERIAL_INFO_COUNT = 3
};

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

/* The first min(n, LEP_SERIAL_INFO_COUNT) fields into out. LEP_E_ARG for NULL. */
LEP_API int lep_serial_get_info(const lep_serial *s, int *out, size_t n);
LEP_API const char *lep_serial_path(const lep_serial *s);
/* The file descriptor, for callers that poll several ports. */
LEP_API int lep_serial_fd(const lep_serial *s);

/* Milliseconds of a monotonic clock (the io.now_ms of this backend). */
LEP_API uint32_t lep_monotonic_ms(void);
/* Seconds of the same monotonic clock, with sub-microsecond resolution. */
LEP_API double lep_monotonic_seconds(void);

/* The serial ports found on this machine: a snapshot taken by
 * lep_port_list_new, read by index (0 .. lep_port_list_count - 1), freed by
 * lep_port_list_free. The strings belong to the list (valid until it is
 * freed); an index past the end gives "" or 0. Not thread-safe per list. */
typedef struct lep_port_list lep_port_list;

/* Scan now. LEP_OK, LEP_E_ARG (NULL out), LEP_E_IO (out of memory). A
 * machine without serial ports gives an empty list, not an error. */
LEP_API int lep_port_list_new(lep_port_list **out);
LEP_API void lep_port_list_free(lep_port_list *l);
LEP_API size_t lep_port_list_count(const lep_port_list *l);
/* The device path (/dev/ttyACM0). */
LEP_API const char *lep_port_list_path(const lep_port_list *l, size_t i);
/* A stable path (/dev/serial/by-id/...), or "". */
LEP_API const char *lep_port_list_by_id(const lep_port_list *l, size_t i);
/* The USB product/manufacturer when known, or "". */
LEP_API const char *lep_port_list_description(const lep_port_list *l, size_t i);
/* USB vendor and product ids, 0 when unknown. */
LEP_API int lep_port_list_vid(const lep_port_list *l, size_t i);
LEP_API int lep_port_list_pid(const lep_port_list *l, size_t i);
/* 1 for a port that is likely a sensor: STM VCP 0483:5740 or FTDI 0403:6001. */
LEP_API int lep_port_list_likely_sensor(const lep_port_list *l, size_t i);

#ifdef __cplusplus
}
#endif

#endif
