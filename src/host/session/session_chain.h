/* The session's processing chain: each stamped sample through overload
 * episodes, tare (averaged in raw counts), the host low-pass, SI units,
 * payload compensation, rotation and moment-point shift, limits and
 * decimation, to a row; the end of a run (duration or count).
 *
 * Owns:   session_chain (the tare, the low-pass, the frame, decimation,
 *         the run's end; session_load: payload, gravity, limits).
 * Reads:  its own configuration (session_chain_config, set at open).
 * Given:  each sample with its stamps and flags (by the timing, the stage
 *         before it); the sink, into which it writes its rows and events
 *         (through the sink's functions).
 * Files:  session_chain.c, session_chain_load.c (the payload and the limits).
 * Threads: [mu]: every function is called with the session's mutex held
 *         (the any-thread setters change it while the stream runs). */
#ifndef LEPTRINO_HOST_SESSION_CHAIN_H
#define LEPTRINO_HOST_SESSION_CHAIN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/client.h"
#include "leptrino/payload.h"
#include "session_sink.h"
#include "struct_api.h"

/* 2nd-order Butterworth low-pass, one section per axis (direct form II
 * transposed), run on raw counts. */
typedef struct session_lowpass {
    double cutoff_hz; /* 0: off */
    double b0, b1, b2, a1, a2;
    double z1[LEP_AXES], z2[LEP_AXES];
    bool primed;       /* state set from a sample (steady state) */
    uint32_t settle;   /* samples left flagged LEP_SF_SETTLING */
    uint32_t settle_n; /* samples of one settling period */
    double delay_s;    /* group delay at 0 Hz */
} session_lowpass;

/* The payload's gravity wrench removed from the SI values, and the limits
 * on what is left. */
typedef struct session_load {
    lep_payload payload;     /* mass 0: none */
    double gravity[3];       /* sensor frame, m/s^2 */
    double wrench[LEP_AXES]; /* the payload's gravity wrench at gravity (N, N m, sensor frame) */
    double limit[LEP_AXES];  /* N, N m on the output SI values; 0: none */
    bool beyond;             /* in a limit episode */
} session_load;

/* What the chain is told once, at open. */
typedef struct session_chain_config {
    lep_rated rated;
    int16_t saturation;
    unsigned tare_samples; /* the start-up tare, 0: none */
    double duration_s;     /* 0: none */
    uint64_t count;        /* 0: none */
} session_chain_config;

typedef struct session_chain {
    session_chain_config cfg;
    double tare[LEP_AXES];
    bool tared;
    bool taring;
    bool tare_hold;       /* the start-up tare: its samples are not delivered */
    uint32_t tare_n_goal; /* samples to average (0: by time) */
    double tare_until;    /* by time: stamp that ends it (set at its first sample) */
    double tare_duration;
    double tare_sum[LEP_AXES];
    uint32_t tare_n;
    session_lowpass lp;
    double rot[9];
    double shift[3];
    unsigned decimate;
    uint32_t dec_phase;
    uint8_t carry_flags; /* LEP_SF_GAP of a sample that decimation dropped */
    bool overloaded;
    bool ended; /* duration or count reached */
    double first_delivered_t;
    session_load load;
} session_chain;

/* ---- session_chain.c ---- */
/* From checked options (lep_priv_load_check) and the sensor's identity. */
void lep_priv_chain_init(session_chain *ch, const lep_session_options *o,
                         const session_chain_config *cfg);
/* A new stream: the start-up tare when asked, the low-pass restarted, no
 * episode, decimation and the run's end from the start. */
void lep_priv_chain_start(session_chain *ch);
/* The stream stopped: a tare in progress ends without a result. */
void lep_priv_chain_stop(session_chain *ch);
/* The next sample sets the low-pass state again (a reconnect). */
void lep_priv_chain_restart_filter(session_chain *ch);
/* A hole in the data: the low-pass's output after it is a transient again. */
void lep_priv_chain_hole(session_chain *ch);
/* The run's duration or count is reached. */
bool lep_priv_chain_ended(const session_chain *ch);
/* Process one sample stamped t (t_utc), brought by a read that returned at
 * arrived, with the flags the timing gave it: its row, when delivered (not
 * the start-up tare's, decimation's or after the end), and its events go
 * into sk. Call only when the sink has room (lep_priv_sink_received). */
void lep_priv_chain_sample(session_chain *ch, session_sink *sk, const lep_sample *smp, double t,
                           double t_utc, double arrived, uint8_t flags);
/* A handshake sample (outside the stream) into row: the tare offsets, SI
 * units and output frame in force; LEP_SF_OVERLOAD when overloaded. No
 * low-pass, decimation or tare averaging (they are the stream's), no event. */
void lep_priv_chain_one(const session_chain *ch, const lep_sample *smp, double t, double t_utc,
                        session_row *row);
/* The low-pass's cut-off at sample rate fs: LEP_E_VALUE beyond 0.45 fs. */
int lep_priv_chain_set_lowpass(session_chain *ch, double cutoff_hz, double fs);
/* The output frame (NULL: identity, no shift): LEP_E_VALUE when not finite
 * or not orthonormal. */
int lep_priv_chain_set_rotation(session_chain *ch, const double rotation[9],
                                const double shift_m[3]);
/* Average the next n samples (n > 0), or those of duration_s, into the tare. */
void lep_priv_chain_tare(session_chain *ch, unsigned n, double duration_s);
/* Set the tare offsets (NULL: none) at once; the event before row `sample`. */
void lep_priv_chain_set_tare(session_chain *ch, session_sink *sk, const double offset[LEP_AXES],
                             double t, uint64_t sample);
/* The tare offsets into offset (may be NULL); whether tared. */
bool lep_priv_chain_tared(const session_chain *ch, double offset[LEP_AXES]);
bool lep_priv_chain_taring(const session_chain *ch);
/* The processing part of the metadata. */
void lep_priv_chain_meta(const session_chain *ch, lep_session_meta *out);
void lep_priv_lowpass_design(session_lowpass *lp, double cutoff_hz, double fs);

/* ---- session_chain_load.c ---- */
/* Check the payload, gravity and limits of options o (one line in err). */
int lep_priv_load_check(const lep_session_options *o, char *err, size_t errlen);
/* From checked options. */
void lep_priv_load_init(session_load *l, const lep_session_options *o);
/* A new stream: no limit episode. */
void lep_priv_load_start(session_load *l);
/* Remove the payload's gravity wrench from si (N, N m, sensor frame). */
void lep_priv_load_compensate(const session_load *l, double si[LEP_AXES]);
/* The payload's gravity wrench in counts through rated (for a tare's offset). */
void lep_priv_load_counts(const session_load *l, const lep_rated *rated, double counts[LEP_AXES]);
/* Check a row's SI values (output frame) against the limits: the
 * LEP_SF_LIMIT flag or 0; an episode's begin and end go into sk as events
 * (before row number `sample`, at t). */
uint8_t lep_priv_load_limits(session_load *l, session_sink *sk, const double si[LEP_AXES], double t,
                             uint64_t sample);
/* The payload (NULL: none), the gravity, the limits (NULL: none):
 * LEP_E_ARG for a negative mass or limit, or numbers not finite. */
int lep_priv_chain_set_payload(session_chain *ch, const lep_payload *p);
int lep_priv_chain_set_gravity(session_chain *ch, const double gravity[3]);
int lep_priv_chain_set_limits(session_chain *ch, const double limit[LEP_AXES]);
/* The load's part of the metadata. */
void lep_priv_load_meta(const session_load *l, lep_session_meta *out);

#endif
