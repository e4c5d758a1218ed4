/* leptrino-bench end to end: the client over a pty against leptrino-sim
 * running as another process, plus the Python per-sample costs. */
#ifndef LEPTRINO_BENCH_E2E_H
#define LEPTRINO_BENCH_E2E_H

#include <stdint.h>

#include "bench.h"

typedef struct e2e_options {
    const char *self;   /* this program (re-run under strace for syscall counts) */
    const char *sim;    /* leptrino-sim */
    const char *python; /* interpreter for the Python bench */
    const char *source; /* source tree (bindings/python/bench_record.py) */
    int smoke;          /* short runs */
} e2e_options;

void e2e_defaults(e2e_options *o, const char *self);
/* Writes the "end_to_end" and "python" members of the open JSON object. */
void e2e_report(const e2e_options *o);
/* `--e2e-child MODE PORT SECONDS`: stream from PORT, for strace. */
int e2e_child_main(int argc, char **argv);

/* ---- field_stream.c: the field-style streaming baselines ---- */
typedef struct field_port {
    int fd;              /* -1 when closed */
    int sleep_when_idle; /* 1: sleep a fixed 1 ms after a read() that returned 0; 0: busy loop */
    long long sleeps;    /* nanosleep calls so far */
    plain_decoder dec;
} field_port;

/* Open port raw 8N1 at 460800 baud with VMIN=0/VTIME=0 (read() never
 * blocks), input flushed. LEP_OK, or LEP_E_NOT_FOUND / LEP_E_NOT_TTY /
 * LEP_E_IO (f->fd is then -1). */
int field_open(field_port *f, const char *port, int sleep_when_idle);
/* Write the framed command `code` (LEP_CMD_START, LEP_CMD_STOP). LEP_OK or LEP_E_IO. */
int field_send(field_port *f, uint8_t code);
/* Read one byte per read() call into the plain decoder until a good stream
 * data message completes; its reserved bytes (the sim's sequence number) into
 * *seq. Blocks (sleeping or spinning as opened) up to timeout_ms without one:
 * LEP_E_TIMEOUT; a failed read: LEP_E_IO. */
int field_next(field_port *f, uint16_t *seq, int timeout_ms);
/* Send stop, drop what arrives until its answer (at most 500 ms), close. */
void field_close(field_port *f);

#endif
