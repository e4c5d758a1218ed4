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

/* Options; start from lep_sim_options_init(). Strings are copied at start. */
typedef struct lep_sim_options {
    const char *model;      /* preset: CFS018CA201U, CFS034CA301U, PFS055YA501U6 (default), PFS080YS102U6 */
    const char *serial;     /* 1..8 ASCII digits, default "00000001" */
    const char *firmware;   /* 1..4 printable ASCII chars, default "1.13" */
    bool output_rate_field; /* answer product info in the 38-byte form */
    double rate_hz;         /* continuous output rate, 1..10000, default 1200 */
    uint8_t filter;         /* filter code in effect at power-on, default 0 */
    uint64_t seed;          /* waveform and fault randomness, default 1 */
    double amplitude;       /* sine amplitude as a fraction of rated (0..4), default 0.2 */
    double noise;           /* uniform noise amplitude as a fraction of rated (0..1), default 0.005 */
    bool constant;          /* hold a constant load (amplitude as the level), no noise */
    const char *replay_csv; /* replay raw counts fx,fy,fz,mx,my,mz[,status] per line, looping; NULL: waveform */
    double overload_every_s;    /* an overload episode every N s of a stream, 0 = never: one axis
                                   at 4x rated, saturated at +/-32000, status bit 2 */
    double overload_duration_s; /* length of an episode, default 0.1 (< overload_every_s) */
    double p_nak;           /* probability of NAKing a valid command (the command is not executed) */
    double p_corrupt;       /* probability of flipping one bit of an outgoing message */
    double p_garbage;       /* probability of 1..8 garbage bytes (never DLE) before an outgoing message */
    double p_drop;          /* probability of dropping a continuous data message */
    int stall_ms;           /* stall (send nothing, answer nothing) for N ms ... */
    double stall_after_s;   /* ... starting this long after start (with stall_ms > 0) */
    double hangup_after_s;  /* hang up (close the pty) once, N s after start, 0 = never */
    int reopen_after_ms;    /* after a hang-up, open a new pty after N ms and re-point link
                               (needs link; the sensor comes back powered up, idle), -1 = never */
    bool start_streaming;   /* power up already streaming (a stream left by an earlier program) */
    const char *link;       /* also make a symlink at this path to the port (replaced if it exists) */
} lep_sim_options;

/* Counters of what the virtual sensor did (since lep_sim_start). */
typedef struct lep_sim_stats {
    uint64_t samples_sent;    /* continuous data messages queued to the port */
    uint64_t samples_dropped; /* data messages dropped by the p_drop fault */
    uint64_t commands;        /* commands answered (any result code) */
    uint64_t naks;            /* DLE NAK sent (bad BCC, or the p_nak fault) */
    uint64_t bytes_corrupted; /* messages with a byte flipped by the p_corrupt fault */
    uint64_t hangups;
    bool streaming;
    uint8_t filter;           /* in effect */
    uint8_t filter_pending;   /* takes effect at the next power cycle */
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

LEP_API void lep_sim_options_init(lep_sim_options *o);

/* Names of the model presets, NULL-terminated static array. */
LEP_API const char *const *lep_sim_models(void);

/* Rated values of a preset; LEP_E_ARG for an unknown model. */
LEP_API int lep_sim_model_rated(const char *model, lep_rated *out);

/* Create the pty and start serving on a thread. On failure returns a
 * LEP_E_* code and writes a one-line message into err when not NULL. */
LEP_API int lep_sim_start(const lep_sim_options *o, lep_sim **out, char *err, size_t errlen);

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

LEP_API void lep_sim_get_stats(lep_sim *s, lep_sim_stats *out);

/* Stop the thread, close the pty, remove the link, free. NULL is fine. */
LEP_API void lep_sim_stop(lep_sim *s);

#ifdef __cplusplus
}
#endif

#endif
