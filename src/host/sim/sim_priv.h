/* Private: the virtual sensor's state and the functions its files share.
 *
 * Each file calls only the files listed after it (test/checks/depgraph.py
 * fails the build on a cycle):
 *
 *   sim_flat.c      the flat public functions over the struct ones (no state)
 *   sim_api.c       lep_sim_start/stop, requests from callers, stats (public)
 *   sim_serve.c     the serving thread: waits for input, deadlines and
 *                   requests; stalls, hang-up and reopen; publishing counters
 *   sim_schedule.c  when stream samples are due; sending or skipping them
 *   sim_device.c    the core's device fed with the commands that reach it,
 *                   the start of a stream, power cycles, set-up from options
 *   sim_faults.c    faults on the way out (drop, garbage, corrupt) and the
 *                   input's NAK fault
 *   sim_pty.c       the port (a pty), the requests' wake-up pipe, waiting on
 *                   both, writing the output queue to the port (POSIX)
 *   sim_link.c      ownership of the link path (POSIX)
 *   sim_link_win32.c  on Windows, instead of sim_pty.c and sim_link.c: the port
 *                   is one end of a loopback TCP connection whose other end the
 *                   Win32 serial backend opens by name (serial_loopback.h)
 *   sim_queue.c     the output queue, and the transport between it and the
 *                   port (sim_transport.c: the packetising rule, sans-I/O);
 *                   sim_trace.c the write trace
 *   sim_filter.c, sim_signal.c, sim_replay.c, sim_models.c, sim_options.c:
 *                   the signal, the sensor's filter, the options (no state here)
 *
 * struct lep_sim is shared; each field group below says which file writes it. */
#ifndef LEPTRINO_SIM_PRIV_H
#define LEPTRINO_SIM_PRIV_H

#include <limits.h>
#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/device.h"
#include "leptrino/frame.h"
#include "leptrino/sim.h"
#include "struct_api.h"
#include "sim_filter.h"
#include "sim_signal.h"
#include "sim_transport.h"

#define OUTQ_SIZE 32768u
#define PEND_SIZE 1024u
/* Room for the largest message the sensor sends: a frame and its garbage. */
#define LEP_SIM_FRAME_ROOM (LEP_MAX_FRAME + 16u)
/* Beyond this lag behind schedule (the process was not scheduled), samples
 * are skipped instead of sent in a burst. A stall skips what it covered. */
#define MAX_LAG_NS 500000000
#define NS_PER_S 1000000000.0
/* Write-trace records buffered before one write to the trace file. */
#define LEP_SIM_TRACE_BUF 256u

typedef struct lep_sim_trace lep_sim_trace;

struct lep_sim {
    /* shared with callers, under lock */
    pthread_mutex_t lock;
    bool req_stop, req_power_cycle, req_hangup;
    int req_stall_ms;         /* -1: none */
    int req_hold_ms;          /* -1: none */
    lep_sim_trace *req_trace; /* lep_sim_trace_writes: handed to the serving thread */
    bool trace_requested;     /* lep_sim_trace_writes was called (once only) */
    lep_sim_counters stats;
    int wake[2];      /* POSIX: the requests' pipe (sim_pty.c) */
    uintptr_t wake_s; /* Windows: the requests' UDP socket (sim_link_win32.c) */
    pthread_t thread;
    bool thread_started;

    /* set at start, read-only afterwards */
    lep_sim_options opt;
    const char *link; /* opt.link, "" for none */
    int lock_fd;      /* flock held on lock_path while we own the link, or -1 */
    char lock_path[PATH_MAX];
    char port[PATH_MAX]; /* what lep_sim_port returns: the link, or the pty */
    lep_product_info info;
    lep_rated rated;
    lep_sim_signal sig;
    lep_sim_fir fir[LEP_FILTER_MAX + 1]; /* the sensor's filter, per code */
    double period_ns;

    /* ---- owned by the serving thread ---- */
    lep_sim_counters st; /* working copy, published under lock (every file counts in it) */
    /* sim_schedule.c */
    lep_sim_fir_state fir_state; /* the stream's filter inputs */
    uint8_t fir_code;            /* the code fir_state was filled for */
    uint64_t k;                  /* index of the next stream sample (0 at stream start) */
    /* sim_device.c */
    lep_device dev;
    lep_frame_decoder shadow; /* sees frames first, so a NAK fault can withhold one */
    uint8_t pend[PEND_SIZE];
    size_t pend_len;
    bool streaming;
    int64_t t0;       /* stream start */
    int64_t power_on; /* also set by sim_serve.c's reopen */
    /* sim_faults.c */
    uint64_t rng;
    /* sim_pty.c or sim_link_win32.c: the port; sim_queue.c: the output queue
     * (emptied by sim_device.c's power-off) */
    int master, slave;  /* POSIX: the pty's two sides */
    uintptr_t master_s; /* Windows: the sensor's end of the loopback connection */
    char pty[PATH_MAX]; /* the port's own name (a pty's path; on Windows a loopback name) */
    uint8_t out[OUTQ_SIZE];
    size_t out_len;
    sim_transport tr; /* which of out's bytes the port may have by now */
    /* sim_serve.c */
    int64_t stall_until, stall_at, hangup_at, reopen_at; /* 0: none */
    int64_t hold_until; /* output held (made and queued, not written) until then; 0: none */
    bool hung;
    lep_sim_trace *trace;     /* write trace, or NULL (sim_trace.c) */
    bool trace_was_streaming; /* to mark the end of a stream in the trace */
};

/* sim_pty.c (sim_link_win32.c on Windows): the port, the requests' wake-up
 * channel, waiting on both, the thread. */
/* Nothing open yet (before anything can fail). */
void lep_priv_sim_port_init(lep_sim *s);
/* The wake-up channel callers write a request into: LEP_OK or LEP_E_IO. */
int lep_priv_sim_wake_open(lep_sim *s, char *err, size_t errlen);
/* From any thread: wake the serving thread (a request is set). */
void lep_priv_sim_wake(lep_sim *s);
/* The serving thread: read all the wake-ups out. */
void lep_priv_sim_wake_drain(lep_sim *s);
void lep_priv_sim_wake_close(lep_sim *s);
/* Open a new port (and point the link at it): LEP_OK, or an error with a message. */
int lep_priv_sim_open_pty(lep_sim *s, char *err, size_t errlen);
void lep_priv_sim_close_pty(lep_sim *s);
/* What lep_priv_sim_wait found ready. */
#define LEP_SIM_READY_WAKE 1u /* a request was written */
#define LEP_SIM_READY_PORT 2u /* the port has input (or hung up: a read says) */
/* Wait until the absolute time until (lep_priv_monotonic_ns; 0: no end) for a
 * wake-up and, with port, for input on the port (and room for output with
 * want_out). *ready gets LEP_SIM_READY_*. 0, or -1 when waiting fails. */
int lep_priv_sim_wait(lep_sim *s, bool port, bool want_out, int64_t until, unsigned *ready);
/* Read what the host sent: the count, 0 for nothing now, -1 when the port
 * cannot be read now (the caller waits a little). */
long lep_priv_sim_read_port(lep_sim *s, uint8_t *buf, size_t cap);
/* Write the output queue to the port until it takes no more. */
void lep_priv_sim_flush_out(lep_sim *s);
/* Start the serving thread fn(s) (taking none of the application's signals):
 * pthread_create's result. */
int lep_priv_sim_start_thread(lep_sim *s, void *(*fn)(void *));
/* The serving thread's own settings, from inside it (timer slack). */
void lep_priv_sim_thread_init(void);

/* sim_queue.c: the output queue and the transport after it */
/* Empty, the transport as the options say ("usb-packets", "ftdi-latency"). */
void lep_priv_sim_queue_init(lep_sim *s);
/* Queue n bytes that leave the sensor at at (0: now): false when they do not fit. */
bool lep_priv_sim_queue(lep_sim *s, const uint8_t *b, size_t n, int64_t at);
/* True when the output queue cannot take another message. */
bool lep_priv_sim_queue_full(const lep_sim *s);
/* The transport's frame boundaries up to now happen. */
void lep_priv_sim_queue_advance(lep_sim *s, int64_t now);
/* Bytes at the front of the queue the port may take now. */
size_t lep_priv_sim_queue_ready(const lep_sim *s);
/* When the transport releases more of the queue (0: nothing waits for it). */
int64_t lep_priv_sim_queue_next(const lep_sim *s);
/* n of the ready bytes were written to the port. */
void lep_priv_sim_queue_written(lep_sim *s, size_t n);
/* Empty the queue (power off, hang-up): nothing is in flight. */
void lep_priv_sim_queue_clear(lep_sim *s);

/* sim_link.c (sim_link_win32.c on Windows): ownership of the link path (see
 * the file's comment) */
/* Take the link's lock and check what is at the path: LEP_OK (nothing to
 * do without a link), LEP_E_BUSY (owned by a running sensor, or holding
 * something that is not a stale pty link), LEP_E_IO, with a message. */
int lep_priv_sim_link_claim(lep_sim *s, char *err, size_t errlen);
/* Point the link at s->pty, if what is at the path may be replaced. */
int lep_priv_sim_relink(const lep_sim *s, char *err, size_t errlen);
/* Remove the link while it points at our pty. */
void lep_priv_sim_remove_link(const lep_sim *s);
/* Remove the lock file and drop the lock (after remove_link). */
void lep_priv_sim_link_release(lep_sim *s);

/* sim_faults.c */
/* Send a message frame (data: a stream sample) through the garbage, corrupt
 * and drop faults into the output queue; it leaves the sensor at at (0: now;
 * a stream sample's deadline). */
void lep_priv_sim_emit(lep_sim *s, const uint8_t *frame, size_t len, bool data, int64_t at);
void lep_priv_sim_send_nak(lep_sim *s);
/* The input's NAK fault: true when a command is withheld (a NAK was sent). */
bool lep_priv_sim_nak_fault(lep_sim *s);

/* sim_device.c */
/* Bytes from the host: through the shadow decoder and the NAK fault to the
 * device; its answers sent. */
void lep_priv_sim_handle_input(lep_sim *s, const uint8_t *p, size_t len);
/* The device loses power: stream, input and output in flight gone. */
void lep_priv_sim_power_off(lep_sim *s);
/* Power off and on again (counted); the caller publishes. */
void lep_priv_sim_power_cycle(lep_sim *s);
int lep_priv_sim_init_device(lep_sim *s, char *err, size_t errlen);

/* sim_schedule.c */
int64_t lep_priv_sim_deadline(const lep_sim *s, uint64_t k);
void lep_priv_sim_stream_due(lep_sim *s, int64_t now);
void lep_priv_sim_skip_due(lep_sim *s, int64_t now);

/* sim_trace.c: the write trace (lep_sim_trace_writes). Every function
 * takes NULL (no trace) and then does nothing. */
/* Create path (never an existing file) for the trace: LEP_OK, or LEP_E_BUSY /
 * LEP_E_IO with a message. */
int lep_priv_sim_trace_open(const char *path, lep_sim_trace **out, char *err, size_t errlen);
/* Write what is buffered, close, free. */
void lep_priv_sim_trace_close(lep_sim_trace *t);
/* A marker record (LEP_SIM_TRACE_START/END) at time when; END also writes the buffer out. */
void lep_priv_sim_trace_mark(lep_sim_trace *t, uint64_t marker, int64_t when);
/* Data frame k was queued and ends at offset end of the output queue. */
void lep_priv_sim_trace_queued(lep_sim_trace *t, uint64_t k, size_t end);
/* A write() called at t_call returned n > 0 bytes at t_return: record the
 * frames it completed, move the others' offsets down by n. */
void lep_priv_sim_trace_written(lep_sim_trace *t, size_t n, int64_t t_call, int64_t t_return);
/* The output queue was emptied without writing (power cycle, hang-up). */
void lep_priv_sim_trace_discard(lep_sim_trace *t);

/* sim_serve.c */
void lep_priv_sim_publish(lep_sim *s);
void *lep_priv_sim_serve(void *arg);

#endif
