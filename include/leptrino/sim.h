/* Virtual sensor: a pseudo-terminal that behaves like a Leptrino sensor.
 *
 * Built on the device side of the core (leptrino/device.h). Runs on a thread
 * of its own (which blocks all signals); its port is a real tty that any
 * program can open. The functions below are thread-safe.
 *
 * Simulator feature: the two reserved bytes of every continuous data message
 * carry a sequence number (little-endian uint16): 0 for the first sample
 * after a start command, +1 per sample period, wrapping at 65536. Samples
 * lost to faults (p_drop, a stall) leave a gap, so a host can count losses
 * exactly. Handshake (0x30) answers carry 0 there. See docs/simulator.md. */
#ifndef LEPTRINO_SIM_H
#define LEPTRINO_SIM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "export.h"
#include "message.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lep_sim lep_sim;

/* Sizes of the string fields of lep_sim_options (each includes the NUL). */
#define LEP_SIM_MODEL_SIZE 32u
#define LEP_SIM_SERIAL_SIZE 16u
#define LEP_SIM_FIRMWARE_SIZE 8u
#define LEP_SIM_PATH_SIZE 512u

/* Options of a virtual sensor. Start from lep_sim_options_init() (the
 * defaults), then set fields directly or by name from text with
 * lep_sim_option_set(). The struct owns its strings (NUL-terminated char
 * arrays): nothing it holds points elsewhere, so it may be copied, kept or
 * filled through an FFI freely. Every option is described once, in the
 * table read by lep_sim_option_at()/lep_sim_option_find(): leptrino-sim's
 * options, the leptrino tool's --sim-* options and Python's
 * Simulator(**options) are derived from it. The name of each option in that
 * table is given in brackets. */
typedef struct lep_sim_options {
    char model[LEP_SIM_MODEL_SIZE];   /* [model] preset: CFS018CA201U, CFS034CA301U,
                                             PFS055YA501U6 (default), PFS080YS102U6 */
    char serial[LEP_SIM_SERIAL_SIZE]; /* [serial] 1..8 ASCII digits, default "00000001" */
    char
        firmware[LEP_SIM_FIRMWARE_SIZE]; /* [firmware] 1..4 printable ASCII chars, default "1.13" */
    bool output_rate_field; /* [output-rate-field] answer product info in the 38-byte form */
    double rate_hz;         /* [rate] continuous output rate, 1..10000 Hz, default 1200 */
    uint8_t filter;         /* [filter] filter code in effect at power-on, 0..3, default 0 */
    uint64_t seed;          /* [seed] waveform and fault randomness, default 1 */
    double amplitude; /* [amplitude] sine amplitude as a fraction of rated, 0..4, default 0.2 */
    double noise;     /* [noise] uniform noise amplitude as a fraction of rated, 0..1,
                               default 0.005 */
    bool constant;    /* [constant] hold a constant load (amplitude as the level), no noise */
    char replay_csv[LEP_SIM_PATH_SIZE]; /* [replay] replay raw counts from this CSV file,
                                           looping; "" (default): the waveform */
    double overload_every_s;    /* [overload-every] an overload episode every N s of a stream,
                                   0 (default) = never: one axis at 4x rated, saturated at
                                   +/-32000, status bit 2 */
    double overload_duration_s; /* [overload-duration] length of an episode, > 0 and
                                   < overload_every_s, default 0.1 */
    double p_nak;               /* [nak] probability of NAKing a valid command (not executed) */
    double p_corrupt;      /* [corrupt] probability of flipping one bit of an outgoing message */
    double p_garbage;      /* [garbage] probability of 1..8 garbage bytes (never DLE) before
                               an outgoing message */
    double p_drop;         /* [drop] probability of dropping a continuous data message */
    int stall_ms;          /* [stall] stall (send nothing, answer nothing) for N ms ... */
    double stall_after_s;  /* [stall-after] ... starting this long after start (needs stall_ms) */
    double hangup_after_s; /* [hangup-after] hang up (close the pty) once, N s after start,
                               0 (default) = never */
    int reopen_after_ms;   /* [reopen-after] after a hang-up, open a new pty after N ms and
                               re-point link (needs link; the sensor comes back powered up,
                               idle), -1 (default) = never */
    bool start_streaming;  /* [start-streaming] power up already streaming (a stream left by
                               an earlier program) */
    char link[LEP_SIM_PATH_SIZE]; /* [link] also make a symlink at this path to the port;
                                     "" (default): none. Replaces only a symlink to a
                                     pseudo-terminal that no running virtual sensor owns */
    /* added with payload compensation (leptrino/payload.h: the model): */
    double payload[4]; /* [payload] a tool on the sensor: mass kg (>= 0), centre of mass
                          x, y, z m in the sensor frame; default 0,0,0,0 (none) */
    double gravity[3]; /* [gravity] gravity in the sensor frame, m/s^2, default
                          0,0,-9.80665 (z up): the sensor reads the payload's gravity
                          wrench at it on top of the waveform */
} lep_sim_options;

/* ---- The option table ----
 *
 * One row per field of lep_sim_options. Front ends print their own help line
 * from a row: e.g. "--sim-" name, arg, help, the range [min, max] and
 * "(default " default_text ")". All functions below are re-entrant (the table
 * is constant), never block and never allocate. */
enum lep_sim_option_type {
    LEP_SIM_OPT_FLAG = 0, /* bool; takes no argument on a command line */
    LEP_SIM_OPT_INT,      /* integer in [min, max] */
    LEP_SIM_OPT_UINT,     /* non-negative integer in [min, max] (decimal) */
    LEP_SIM_OPT_DOUBLE,   /* finite number in [min, max] (or (min, max] with min_exclusive) */
    LEP_SIM_OPT_STRING,   /* text of min..max bytes (a path, a serial, a version) */
    LEP_SIM_OPT_CHOICE,   /* one of a fixed set of names (model: lep_sim_models()) */
    LEP_SIM_OPT_NUMBERS   /* comma-separated finite numbers, as many as arg names
                             ("M,CX,CY,CZ"), each in [min, max] */
};

typedef struct lep_sim_option_info {
    const char *name; /* dash-separated, e.g. "amplitude", "output-rate-field" */
    int type;         /* enum lep_sim_option_type */
    const char *arg;  /* name of the argument for help ("F", "HZ", "PATH"); NULL for flags */
    const char *help; /* one line, no trailing period, without range or default */
    const char *default_text; /* the default as lep_sim_option_set accepts it; NULL when the
                                 option is off/empty by default (flags, replay, link) */
    double min, max;          /* numbers: the allowed range; STRING: its length in bytes;
                                 FLAG, CHOICE: 0 */
    bool min_exclusive;       /* the value must be > min (not >=) */
} lep_sim_option_info;

/* Number of options in the table. */
LEP_API size_t lep_sim_option_count(void);

/* Row i of the table, for i < lep_sim_option_count(); NULL otherwise. The
 * pointer is to static data, valid for the life of the program. */
LEP_API const lep_sim_option_info *lep_sim_option_at(size_t i);

/* The row named name, or NULL. Accepts the dash-separated name, the same
 * with underscores ("output_rate_field", so Python keyword arguments map
 * directly) and the lep_sim_options field name ("rate_hz", "p_nak",
 * "replay_csv", "stall_after_s", ...). */
LEP_API const lep_sim_option_info *lep_sim_option_find(const char *name);

/* Parse value (text) for the option called name (any form lep_sim_option_find
 * accepts), range-check it and store it in o. Flags take NULL (on), "1",
 * "0", "true" or "false". Numbers must be finite and parse completely.
 * On error returns LEP_E_ARG, leaves o unchanged and writes one line into err
 * (when not NULL) naming the option and what is allowed, e.g.
 * "amplitude '5': expected a number from 0 to 4". Re-entrant. */
LEP_API int lep_sim_option_set(lep_sim_options *o, const char *name, const char *value, char *err,
                               size_t errlen);

/* Write the current value of an option in o as text that lep_sim_option_set
 * accepts (flags: "1"/"0") into buf. LEP_E_ARG for an unknown name or a NULL
 * argument, LEP_E_BUFFER when buf is too small (buf then holds ""). */
LEP_API int lep_sim_option_get(const lep_sim_options *o, const char *name, char *buf,
                               size_t buflen);

/* Check every option of o and how they combine (overload duration < every,
 * reopen needs a link, stall-after needs a stall): the one validation
 * lep_sim_start() uses too. LEP_OK, or LEP_E_ARG with one line in err naming
 * the option. Checks values only (not whether a replay file exists or the
 * link may be replaced: lep_sim_start() does that). Re-entrant. */
LEP_API int lep_sim_options_check(const lep_sim_options *o, char *err, size_t errlen);

/* Counters of what the virtual sensor did (since lep_sim_start). */
typedef struct lep_sim_stats {
    uint64_t samples_sent;    /* continuous data messages queued to the port */
    uint64_t samples_dropped; /* data messages dropped by the p_drop fault */
    uint64_t commands;        /* commands answered (any result code) */
    uint64_t naks;            /* DLE NAK sent (bad BCC, or the p_nak fault) */
    uint64_t bytes_corrupted; /* messages with a byte flipped by the p_corrupt fault */
    uint64_t hangups;
    bool streaming;
    uint8_t filter;         /* in effect */
    uint8_t filter_pending; /* takes effect at the next power cycle */
    /* added after the first draft of this header: */
    bool hung_up;             /* the pty is closed now (after a hang-up, before a reopen) */
    uint16_t sequence;        /* sequence number the next stream sample will carry */
    uint64_t responses;       /* answers to commands queued to the port */
    uint64_t faked_naks;      /* of naks: those sent by the p_nak fault */
    uint64_t samples_skipped; /* sample periods with nothing sent: a stall, or > 500 ms late */
    uint64_t samples_blocked; /* data messages not sent because nobody read the port */
    uint64_t garbage_bytes;   /* bytes added by the p_garbage fault */
    uint64_t bytes_received;  /* bytes read from the host */
    uint64_t reopens;         /* new ptys opened after a hang-up */
    uint64_t power_cycles;    /* lep_sim_power_cycle / SIGUSR1 applied */
    uint64_t stalls;          /* stalls begun */
} lep_sim_stats;

/* Fill o with the defaults (every option's default_text). NULL is ignored. */
LEP_API void lep_sim_options_init(lep_sim_options *o);

/* Names of the model presets, NULL-terminated static array. */
LEP_API const char *const *lep_sim_models(void);

/* Rated values of a preset; LEP_E_ARG for an unknown model. */
LEP_API int lep_sim_model_rated(const char *model, lep_rated *out);

/* Check the options (lep_sim_options_check), create the pty and start
 * serving on a thread; o is copied (NULL: the defaults). On failure returns
 * a LEP_E_* code (LEP_E_ARG for a bad option) and writes a one-line message
 * into err when not NULL. On success err holds "" or one warning line to
 * show the user (a replay file whose last line is cut: the whole rows before
 * it are replayed); set err[0] = '\0' before the call to tell them apart. */
LEP_API int lep_sim_start(const lep_sim_options *o, lep_sim **out, char *err, size_t errlen);

/* The sample s sends as sample k of a stream (k = 0 for the first after a
 * start command; its sequence number k mod 65536 is in reserved) while the
 * filter code filter (0..3, lep_sim_stats.filter) is in effect: a pure
 * function of the options, filter and k, so a host can check every sample
 * it receives. Faults are not applied (a corrupted message never passes for
 * this sample). Thread-safe, no I/O; cheap with filter 0, about 2 * rate /
 * cut-off waveform evaluations with a filter. LEP_E_ARG for NULL or
 * filter > 3. */
LEP_API int lep_sim_stream_sample(const lep_sim *s, uint64_t k, uint8_t filter, lep_sample *out);

/* Path of the port (the link when given, else the pty's slave side). Stable
 * for the life of s: a reopen after a hang-up re-points the link. */
LEP_API const char *lep_sim_port(const lep_sim *s);

/* Path of the current pty slave (/dev/pts/N), whatever the link. Changes at a
 * reopen; read it only when no hang-up/reopen can be in progress. */
LEP_API const char *lep_sim_pty_path(const lep_sim *s);

/* Switch the virtual power off and on: the stream stops, a pending filter applies. */
LEP_API void lep_sim_power_cycle(lep_sim *s);

/* Hang up now, as if the USB cable were pulled (reopens per reopen_after_ms). */
LEP_API void lep_sim_hangup(lep_sim *s);

/* Stall for ms milliseconds from now: nothing sent, input buffered. */
LEP_API void lep_sim_stall(lep_sim *s, int ms);

/* Hold the output for ms milliseconds from now (0: release now): samples are
 * made at their times and queued, then written together when the hold ends,
 * as from a sender or a USB adapter running late. Input is read and answered
 * meanwhile (the answers wait in the same queue). Samples beyond the queue's
 * room are not made (counted as samples_blocked). */
LEP_API void lep_sim_hold(lep_sim *s, int ms);

LEP_API void lep_sim_get_stats(lep_sim *s, lep_sim_stats *out);

/* ---- Write trace (for benchmarks; added after the first release) ----
 *
 * lep_sim_trace_writes() makes s record, for every continuous data message
 * it writes to the port from then on, one lep_sim_trace_record: the stream
 * index k of the sample (k mod 65536 is its sequence number) and the
 * CLOCK_MONOTONIC times just before the write() that handed the message's
 * last byte to the pty was called and just after it returned. A stream's
 * start (its start command, t = the t0 of its deadlines t0 + (k+1)/rate) and
 * end (stop, power cycle, hang-up) are records with k = LEP_SIM_TRACE_START
 * and LEP_SIM_TRACE_END (also written for a stream still running at
 * lep_sim_stop). Records are native-endian, 24 bytes, in the order
 * written, buffered and written in blocks of 256; the end of a stream writes
 * the buffer out before the stop command is answered, and lep_sim_stop()
 * writes the rest. The file is created (an existing path is never replaced:
 * LEP_E_BUSY) before the call returns; tracing starts before the next
 * input the sensor reads. Call at most once per s (LEP_E_STATE after).
 * Thread-safe. Errors: LEP_E_ARG (NULL), LEP_E_BUSY, LEP_E_IO, with a
 * one-line message in err. A failed write to the file stops tracing. */
typedef struct lep_sim_trace_record {
    uint64_t k;          /* stream index, or LEP_SIM_TRACE_START / LEP_SIM_TRACE_END */
    int64_t t_call_ns;   /* CLOCK_MONOTONIC before the write() (markers: the event) */
    int64_t t_return_ns; /* CLOCK_MONOTONIC after it returned (markers: the same) */
} lep_sim_trace_record;

#define LEP_SIM_TRACE_START UINT64_MAX
#define LEP_SIM_TRACE_END (UINT64_MAX - 1u)

LEP_API int lep_sim_trace_writes(lep_sim *s, const char *path, char *err, size_t errlen);

/* Stop the thread, close the pty, remove the link, free. NULL is fine. */
LEP_API void lep_sim_stop(lep_sim *s);

#ifdef __cplusplus
}
#endif

#endif
