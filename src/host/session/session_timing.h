/* The session's timing: the stamps of the samples and the gaps before them.
 * The model of the sensor's clock, the stamps and the gaps decided from
 * arrival times are the timeline's (session_timeline.h, sans-I/O), which
 * this unit owns; here its verdicts are applied to the rows held back in the
 * sink, and the gaps it cannot see are found: after a reconnect, and from
 * the virtual sensor's sequence numbers. It also holds the UTC offset the
 * samples are stamped with.
 *
 * A stage of the pipeline: fed a read's samples, it stamps each and hands
 * it to the next stage, the chain, which keeps its row in the sink.
 *
 * Owns:   session_timing (the timeline in it).
 * Reads:  the sink's counts (rows pending, held, processed).
 * Given:  each read's samples and return time; the chain (each sample, and
 *         a hole: its low-pass settles again) and the sink, whose held rows
 *         it judges and into which it queues gap events and counts the
 *         samples received, each through its unit's functions.
 * Threads: the driving thread's; the functions given the sink are [mu]. */
#ifndef LEPTRINO_HOST_SESSION_TIMING_H
#define LEPTRINO_HOST_SESSION_TIMING_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/client.h"
#include "session_chain.h"
#include "session_sink.h"
#include "session_timeline.h"

typedef struct session_timing {
    session_timeline tl;
    double hz;            /* nominal rate */
    bool numbered;        /* the samples carry sequence numbers (the virtual sensor) */
    double last_sample_t; /* stamp of the last sample */
    bool have_seq;
    uint16_t last_seq;
    bool gap_next; /* the next sample follows a gap (reconnect) */
    double gap_from;
    int gap_error;          /* what caused the disconnect before a reconnect */
    uint64_t suspect_index; /* row number of the first row held back */
    /* UTC - monotonic offset the samples are stamped with: held between
     * batches so UTC intervals equal monotonic ones, and moved only when the
     * wall clock steps by more than SESSION_UTC_STEP_S. */
    double utc_off;
} session_timing;

/* ---- session_timing.c ---- */
/* A stream starts at nominal_hz: gaps start over, the UTC offset is
 * measured; gaps come from sequence numbers when numbered (the in-process
 * virtual sensor), else the timeline decides them from arrival times. */
void lep_priv_timing_start(session_timing *tm, double nominal_hz, double gap_periods,
                           bool numbered);
/* The stream (re)starts at now: no stamp after it. */
void lep_priv_timing_resume(session_timing *tm, double now);
/* From now on, tap (NULL: none) is given every feed of the timeline
 * (session_tap.h). */
void lep_priv_timing_tap(session_timing *tm, const timeline_tap *tap);
/* A loss: a suspected hole ends in it (the held rows go), the timeline
 * starts over. [mu] */
void lep_priv_timing_lost(session_timing *tm, session_sink *sk);
/* The next sample follows a reconnect: a gap from the last sample, caused
 * by error. */
void lep_priv_timing_reconnected(session_timing *tm, int error);
/* A read found the port empty at t. */
void lep_priv_timing_empty(session_timing *tm, double t);
/* The UTC offset for samples read at t_read (measured again when the wall
 * clock may have stepped). */
double lep_priv_timing_utc(session_timing *tm, double t_read);
/* The UTC offset in force. */
double lep_priv_timing_utc_offset(const session_timing *tm);
/* Stamp of the last sample (before any: far in the past). */
double lep_priv_timing_last(const session_timing *tm);
/* A read returned at t_read with got[0..n) (n > 0): the rows held back at
 * the previous read judged; each sample stamped (UTC: the offset of
 * lep_priv_timing_utc), a gap before it queued in sk (flag LEP_SF_GAP),
 * counted as received, and processed by the chain into sk while the sink
 * has room; this read's rows held back as the timeline says. [mu] */
void lep_priv_timing_feed(session_timing *tm, session_chain *ch, session_sink *sk,
                          const lep_sample *got, size_t n, double t_read);
/* The run ended: when only held rows wait, nothing comes to judge them
 * by: they go (true); false while other rows wait to be delivered. */
bool lep_priv_timing_end(session_timing *tm, session_sink *sk);

#endif
