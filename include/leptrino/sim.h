/* Virtual sensor: a pseudo-terminal that behaves like a Leptrino sensor.
 *
 * Built on the device side of the core (leptrino/device.h). Runs on a thread
 * of its own (which blocks all signals); its port is a real tty that any
 * program can open. The functions below are thread-safe.
 *
 * Configured by the "sim-*" options of an options handle
 * (leptrino/options.h: lep_option_count() and the lep_option_* table give
 * each one's name, type, range, default and help; docs/simulator.md).
 *
 * Simulator feature: the two reserved bytes of every continuous data message
 * carry a sequence number (little-endian uint16): 0 for the first sample
 * after a start command, +1 per sample period, wrapping at 65536. Samples
 * lost to faults ("sim-drop", a stall) leave a gap, so a host can count
 * losses exactly. Handshake (0x30) answers carry 0 there. */
#ifndef LEPTRINO_SIM_H
#define LEPTRINO_SIM_H

#include <stddef.h>
#include <stdint.h>

#include "export.h"
#include "options.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lep_sim lep_sim;

/* Counters of what the virtual sensor did (since lep_sim_start), as indices
 * into the array lep_sim_stats fills. */
enum lep_sim_stat {
    LEP_SIMST_SAMPLES_SENT = 0,    /* continuous data messages queued to the port */
    LEP_SIMST_SAMPLES_DROPPED = 1, /* data messages dropped by the drop fault */
    LEP_SIMST_COMMANDS = 2,        /* commands answered (any result code) */
    LEP_SIMST_NAKS = 3,            /* DLE NAK sent (bad BCC, or the nak fault) */
    LEP_SIMST_BYTES_CORRUPTED = 4, /* messages with a byte flipped by the corrupt fault */
    LEP_SIMST_HANGUPS = 5,
    LEP_SIMST_STREAMING = 6,        /* 1 while streaming */
    LEP_SIMST_FILTER = 7,           /* filter code in effect */
    LEP_SIMST_FILTER_PENDING = 8,   /* takes effect at the next power cycle */
    LEP_SIMST_HUNG_UP = 9,          /* 1 while the pty is closed (after a hang-up) */
    LEP_SIMST_SEQUENCE = 10,        /* sequence number the next stream sample will carry */
    LEP_SIMST_RESPONSES = 11,       /* answers to commands queued to the port */
    LEP_SIMST_FAKED_NAKS = 12,      /* of naks: those sent by the nak fault */
    LEP_SIMST_SAMPLES_SKIPPED = 13, /* sample periods with nothing sent: a stall, or late */
    LEP_SIMST_SAMPLES_BLOCKED = 14, /* data messages not sent because nobody read the port */
    LEP_SIMST_GARBAGE_BYTES = 15,   /* bytes added by the garbage fault */
    LEP_SIMST_BYTES_RECEIVED = 16,  /* bytes read from the host */
    LEP_SIMST_REOPENS = 17,         /* new ptys opened after a hang-up */
    LEP_SIMST_POWER_CYCLES = 18,    /* lep_sim_power_cycle / SIGUSR1 applied */
    LEP_SIMST_STALLS = 19,          /* stalls begun */
    LEP_SIMST_COUNT = 20
};

/* Number of counters this library fills. */
LEP_API size_t lep_sim_stats_fields(void);
/* Name of counter i ("samples_sent", ...), NULL past the end. */
LEP_API const char *lep_sim_stats_field_name(size_t i);
/* One consistent snapshot of the first min(n, lep_sim_stats_fields())
 * counters into out. LEP_OK, LEP_E_ARG for NULL. */
LEP_API int lep_sim_stats(lep_sim *s, uint64_t *out, size_t n);

/* The model presets: how many, and the name of preset i (NULL past the end). */
LEP_API size_t lep_sim_model_count(void);
LEP_API const char *lep_sim_model_name(size_t i);
/* Rated values of a preset into rated[6] (N, N m); LEP_E_ARG for an
 * unknown model. */
LEP_API int lep_sim_model_rated(const char *model, double rated[6]);

/* Check the "sim-*" options of o, create the pty and start serving on a
 * thread; what it needs of o is copied (NULL: the defaults). On failure
 * returns a LEP_E_* code (LEP_E_ARG for a bad option, LEP_E_NOT_FOUND for a
 * missing replay file, LEP_E_BUSY for a link path that holds someone's file)
 * and writes a one-line message into err when not NULL. On success err
 * holds "" or one warning line to show the user (a replay file whose last
 * line is cut: the whole rows before it are replayed). */
LEP_API int lep_sim_start(const lep_options *o, lep_sim **out, char *err, size_t errlen);

/* The sample s sends as sample k of a stream (k = 0 for the first after a
 * start command; its sequence number k mod 65536 is in *seq) while the
 * filter code filter (0..3, LEP_SIMST_FILTER) is in effect: a pure function
 * of the options, filter and k, so a host can check every sample it
 * receives. raw[6] gets the counts, *status the status bits (each pointer
 * may be NULL). Faults are not applied. Thread-safe, no I/O. LEP_E_ARG for
 * NULL s or filter outside 0..3. */
LEP_API int lep_sim_stream_sample(const lep_sim *s, uint64_t k, int filter, int16_t raw[6],
                                  uint8_t *status, uint16_t *seq);

/* Path of the port (the link when given, else the pty's slave side). Stable
 * for the life of s: a reopen after a hang-up re-points the link. */
LEP_API const char *lep_sim_port(const lep_sim *s);

/* Path of the current pty slave (/dev/pts/N), whatever the link. Changes at a
 * reopen; read it only when no hang-up/reopen can be in progress. */
LEP_API const char *lep_sim_pty_path(const lep_sim *s);

/* Switch the virtual power off and on: the stream stops, a pending filter applies. */
LEP_API void lep_sim_power_cycle(lep_sim *s);

/* Hang up now, as if the USB cable were pulled (reopens per "sim-reopen-after"). */
LEP_API void lep_sim_hangup(lep_sim *s);

/* Stall for ms milliseconds from now: nothing sent, input buffered. */
LEP_API void lep_sim_stall(lep_sim *s, int ms);

/* Hold the output for ms milliseconds from now (0: release now): samples are
 * made at their times and queued, then written together when the hold ends,
 * as from a sender or a USB adapter running late. Input is read and answered
 * meanwhile (the answers wait in the same queue). Samples beyond the queue's
 * room are not made (counted as LEP_SIMST_SAMPLES_BLOCKED). */
LEP_API void lep_sim_hold(lep_sim *s, int ms);

/* ---- Write trace (for benchmarks) ----
 *
 * lep_sim_trace_writes() makes s record, for every continuous data message
 * it writes to the port from then on, one record of 24 bytes, native-endian:
 * uint64 k, the stream index of the sample (k mod 65536 is its sequence
 * number); int64 t_call_ns, CLOCK_MONOTONIC just before the write() that
 * handed the message's last byte to the pty was called; int64 t_return_ns,
 * just after it returned. A stream's start (its start command, t = the t0 of
 * its deadlines t0 + (k+1)/rate) and end (stop, power cycle, hang-up) are
 * records with k = 2^64 - 1 (start) and 2^64 - 2 (end) and both times the
 * event's (an end is also written for a stream still running at
 * lep_sim_stop). With "sim-ppm" the deadlines are at the true rate,
 * rate * (1 + ppm 1e-6); with a transport emulation ("sim-usb-packets",
 * "sim-ftdi-latency") the write is the one that handed the message's last
 * byte to the pty when the transport released it (docs/simulator.md,
 * "Transport and crystal"). Records are in the order written, buffered and
 * written in blocks of 256; the end of a stream writes the buffer out before the stop
 * command is answered, and lep_sim_stop() writes the rest. The file is
 * created (an existing path is never replaced: LEP_E_BUSY) before the call
 * returns; tracing starts before the next input the sensor reads. Call at
 * most once per s (LEP_E_STATE after). Thread-safe. Errors: LEP_E_ARG
 * (NULL), LEP_E_BUSY, LEP_E_IO, with a one-line message in err. A failed
 * write to the file stops tracing. */
LEP_API int lep_sim_trace_writes(lep_sim *s, const char *path, char *err, size_t errlen);

/* Stop the thread, close the pty, remove the link, free. NULL is fine. */
LEP_API void lep_sim_stop(lep_sim *s);

#ifdef __cplusplus
}
#endif

#endif
