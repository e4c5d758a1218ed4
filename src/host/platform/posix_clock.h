/* Private: the monotonic clock shared by the POSIX backends. */
#ifndef LEPTRINO_POSIX_CLOCK_H
#define LEPTRINO_POSIX_CLOCK_H

#include <stdint.h>

/* Nanoseconds of CLOCK_MONOTONIC. */
int64_t lep_priv_monotonic_ns(void);

/* Milliseconds from now until deadline_ns (CLOCK_MONOTONIC), rounded up so a
 * poll() given them never returns early; 0 once it has passed, at most INT_MAX. */
int lep_priv_ms_left(int64_t deadline_ns);

/* Sleep until the CLOCK_MONOTONIC time until_ns (returns at once if it has
 * passed). A signal ends the sleep early: callers look at the clock again. */
void lep_priv_sleep_until_ns(int64_t until_ns);

#endif
