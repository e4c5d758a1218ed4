/* The session's timeline (private, sans-I/O): a model of the sensor's clock
 * fed by what each port read saw, the stamps of the samples on it, and the
 * gaps decided from the same model.
 *
 * Like the frame decoder, it is state and rules in one struct: it calls no
 * clock, does no I/O, allocates nothing, includes no OS header. Times are
 * seconds of one monotonic clock, given by the caller.
 *
 * Fed:
 *   lep_priv_timeline_read   a read returned at t with n samples (n > 0);
 *                            lost samples known to be missing before them
 *                            (from sequence numbers; 0 on a real port)
 *   lep_priv_timeline_empty  a read found the port empty at t
 *   lep_priv_timeline_restart a new stream (start, loss, reconnect): the
 *                            model starts over, the learned period is kept
 *
 * The model: the sensor's count k (samples received plus samples lost) and
 * a line L(k) = offset + period * k on the monotonic clock, the earliest a
 * sample could have arrived. Every read gives a point (count of its newest
 * sample, the read's return time), which is never earlier than that sample's
 * emission plus the transport's delay; the line is a lower bound of those
 * points: the lower convex hull of one point per TIMELINE_BLOCK_S (the
 * earliest, over the last TIMELINE_BLOCKS blocks: drift is followed, a
 * sensor crystal is off by up to a few hundred ppm), its slope the hull's
 * edge across the middle of that window (once the points span
 * TIMELINE_MIN_SPAN_S, within TIMELINE_MAX_PPM of the nominal period; else
 * the nominal or learned period), its offset so that no point lies below it.
 * This is one-way clock translation as robotics drivers do it (the convex
 * hull idea of ETH ASL's cuckoo_time_translator; no code taken).
 *
 * Stamps (lep_priv_timeline_stamp): sample j of the last read (j counts its
 * lost samples too) gets L(its count), but never earlier than the stamp of
 * the sample before it and never later than the read's return: stamps are
 * monotonic and no sample is stamped after it arrived.
 *
 * Gaps (arrival_gaps, on a port without sequence numbers): the lateness of a
 * read is t - L(count of its newest sample). Transit jitter makes it rise and
 * fall back; a hole makes it rise and stay. A read later than gap_periods
 * periods is suspected: its rows are held back (verdict.hold) until a read
 * TIMELINE_JUDGE_S or more after it, and not the first after it, judges (the
 * rows of a read before that, still late and not later again, are held back
 * with them, verdict.extend: a sender running late, a machine under load,
 * catches up within that, and a hole judged on the reads of its catching up
 * is a false gap). The judge takes the least lateness of the held reads and
 * its own (a read held up on the way is late once, a hole every time):
 * still late and not a catching-up read (one that brought more
 * than was due since the suspected read, beyond TIMELINE_BURST; after a
 * silence the reader saw, only when the suspected read took at least
 * TIMELINE_LAG_READ samples, most of a tty piece) -- a gap of lost =
 * lateness / period before the held rows (verdict.gap: flag the first, an
 * event from..to; the count moves on by lost, so the held rows' stamps move
 * by verdict.shift, each capped at its own read's return; the window of
 * points starts over from this read, the period learned kept as the prior,
 * so a hole judged wrongly does not bend the line for a whole window);
 * caught up -- the held rows are released as they are. A judging read later
 * again by more than gap_periods (a silence since the suspected read)
 * releases the held rows as they are and is suspected with the whole
 * lateness: the suspected read may have been late by a silence at its end (a
 * budgeted read some time into a stall), not by a hole before it. Known
 * losses (sequence numbers) just move the count on.
 *
 * No field of another unit is written: the verdict says what to do with the
 * rows; the session applies it.
 *
 * A recorder (tap) may be given what the timeline is fed, as it is fed
 * (init, restart, each read and empty read), to record read traces that
 * replay deterministically (leptrino-stamp-error --record-reads;
 * test/vectors/timeline). It is private, set through session_tap.h; without
 * one (NULL, the default) a feed costs one test of a pointer. */
#ifndef LEPTRINO_HOST_SESSION_TIMELINE_H
#define LEPTRINO_HOST_SESSION_TIMELINE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define TIMELINE_BLOCKS 64
#define TIMELINE_BLOCK_S 0.125
#define TIMELINE_MIN_SPAN_S 0.5
#define TIMELINE_MAX_PPM 1000.0
/* A USB adapter's burst: samples a read may bring beyond what was due. */
#define TIMELINE_BURST 32.0
/* A suspected hole is judged by a read at least this long after it, and
 * not before the second read after it (the first one's rows are held too). */
#define TIMELINE_JUDGE_S 0.015
#define TIMELINE_JUDGE_READS 1u
/* Samples held at most while a hole is judged (the session's rows keep this
 * many and one read more). */
#define TIMELINE_HOLD_MAX 512u
/* Most of a 4 KiB tty piece, in samples of the smallest frame. */
#define TIMELINE_LAG_READ 128u

typedef struct timeline_point {
    double k, t;   /* count of a read's newest sample, the read's return */
    int64_t block; /* TIMELINE_BLOCK_S since the stream's first read */
} timeline_point;

/* What the session does after a read. */
typedef struct timeline_verdict {
    /* the rows held back at the previous read */
    bool release;  /* release them (after the gap, when there is one) */
    bool gap;      /* a hole before them: flag the first, queue a gap event */
    uint32_t lost; /* gap: samples lost (estimated) */
    double from;   /* gap: stamp of the sample before the hole */
    double to;     /* gap: stamp of the first held sample, after the shift */
    double shift;  /* gap: add to each held row's stamp, then no later than
                      the return of the read that brought it */
    /* this read's rows */
    bool hold;   /* hold them back: a suspected hole before them */
    bool extend; /* with hold: too soon to judge; they join the rows held */
} timeline_verdict;

/* One feed, for a recorder. */
typedef struct timeline_fed {
    char what;          /* 'i' init, 's' restart, 'r' read, 'e' empty read */
    double t;           /* r, e: the time given */
    size_t n;           /* r: samples */
    uint64_t lost;      /* r: lost samples known before them */
    double nominal;     /* i: nominal period, s */
    double gap_periods; /* i */
    bool arrival_gaps;  /* i */
} timeline_fed;

typedef struct timeline_tap {
    void (*fed)(void *user, const timeline_fed *f);
    void *user;
} timeline_tap;

typedef struct session_timeline {
    const timeline_tap *tap; /* a recorder, or NULL; kept by init (start zeroed) */
    double nominal;          /* nominal period, s */
    double thr;              /* gap threshold, s */
    bool arrival_gaps;       /* decide gaps from arrival times */
    double prior;            /* the period until the hull spans enough: nominal or learned */
    double period, offset;
    bool started;
    double t0;        /* the stream's first read */
    uint64_t k;       /* the sensor's count of the next sample */
    uint64_t read_k0; /* count at the start of the last read */
    double read_t;    /* its return */
    double floor;     /* stamp of the sample before the last read (-1e300: none) */
    double last;      /* stamp of the newest sample */
    timeline_point pts[TIMELINE_BLOCKS];
    size_t head, len;
    double empty_t; /* a read last found the port empty */
    /* the suspected hole */
    bool held;
    uint64_t susp_k; /* count of the first held sample */
    size_t susp_n;
    double susp_t, susp_late, susp_from, susp_first, susp_last;
    double susp_last_t;   /* return of the last read whose rows are held */
    size_t susp_held;     /* samples held (an extension stops at TIMELINE_HOLD_MAX) */
    unsigned susp_reads;  /* reads since the suspected one, their rows held too */
    double susp_min_late; /* the least lateness of the held reads */
    bool susp_silent;
} session_timeline;

void lep_priv_timeline_init(session_timeline *tl, double nominal_period_s, double gap_periods,
                            bool arrival_gaps);
void lep_priv_timeline_restart(session_timeline *tl);
void lep_priv_timeline_empty(session_timeline *tl, double t);
void lep_priv_timeline_read(session_timeline *tl, double t, size_t n, uint64_t lost,
                            timeline_verdict *v);
/* Stamp of sample j (counted from the read's start, lost ones included) of
 * the last read. */
double lep_priv_timeline_stamp(const session_timeline *tl, uint64_t j);
/* Stamp of the newest sample (-1e300 before any). */
double lep_priv_timeline_last(const session_timeline *tl);
/* Whether rows are held back awaiting the next read's judgement. */
bool lep_priv_timeline_holding(const session_timeline *tl);
/* The session let the held rows go by itself (end of run): forget them. */
void lep_priv_timeline_forget_held(session_timeline *tl);

#endif
