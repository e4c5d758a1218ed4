/* The session's clock helpers: stateless, owning nothing. */
#ifndef LEPTRINO_HOST_SESSION_CLOCK_H
#define LEPTRINO_HOST_SESSION_CLOCK_H

#include <stdbool.h>

/* A wall-clock step smaller than this is measurement jitter, not a step. */
#define SESSION_UTC_STEP_S 1e-3
/* The offset is measured again until its bracket is this narrow, at most
 * SESSION_UTC_TRIES times (a thread that loses the CPU between its clock
 * reads, to the scheduler or to valgrind's one-thread-at-a-time, widens it). */
#define SESSION_UTC_BRACKET_S 50e-6
#define SESSION_UTC_TRIES 20

/* ---- session_clock.c ---- */
/* UTC - monotonic offset, measured: the wall clock read between two
 * monotonic reads, at least three times and until a bracket is narrower
 * than SESSION_UTC_BRACKET_S (at most SESSION_UTC_TRIES); the narrowest
 * wins. *width (NULL: not wanted) gets its bracket: the true offset lies
 * within half of it of the value returned. */
double lep_priv_utc_offset_within(double *width);
/* The same, its bracket not wanted. */
double lep_priv_utc_offset(void);
/* Whether the wall clock may have left utc_off +- SESSION_UTC_STEP_S, from
 * one read bracketed by t_before (monotonic) and now. */
bool lep_priv_utc_may_have_moved(double utc_off, double t_before);
/* Milliseconds from now until t, rounded up, clipped to int; -1 for infinity. */
int lep_priv_ms_until(double t, double now);

#endif
