/* The session's clock helpers: stateless, owning nothing. */
#ifndef LEPTRINO_HOST_SESSION_CLOCK_H
#define LEPTRINO_HOST_SESSION_CLOCK_H

#include <stdbool.h>

/* A wall-clock step smaller than this is measurement jitter, not a step. */
#define SESSION_UTC_STEP_S 1e-3

/* ---- session_clock.c ---- */
/* UTC - monotonic offset, measured (the narrowest of three brackets). */
double lep_priv_utc_offset(void);
/* Whether the wall clock may have left utc_off +- SESSION_UTC_STEP_S, from
 * one read bracketed by t_before (monotonic) and now. */
bool lep_priv_utc_may_have_moved(double utc_off, double t_before);
/* Milliseconds from now until t, rounded up, clipped to int; -1 for infinity. */
int lep_priv_ms_until(double t, double now);

#endif
