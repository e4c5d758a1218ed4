/* Private: the monotonic clock shared by the POSIX backends. */
#ifndef LEPTRINO_POSIX_CLOCK_H
#define LEPTRINO_POSIX_CLOCK_H

#include <stdint.h>

/* Nanoseconds of CLOCK_MONOTONIC. */
int64_t lep_priv_monotonic_ns(void);

#endif
