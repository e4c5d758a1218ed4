/* Monotonic clock of the POSIX layer (CLOCK_MONOTONIC). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <time.h>

#include "leptrino/serial.h"
#include "posix_clock.h"

int64_t lep_priv_monotonic_ns(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0)
        return 0;
    return (int64_t)ts.tv_sec * 1000000000 + (int64_t)ts.tv_nsec;
}

uint32_t lep_monotonic_ms(void)
{
    return (uint32_t)((uint64_t)lep_priv_monotonic_ns() / 1000000u);
}

double lep_monotonic_seconds(void)
{
    return (double)lep_priv_monotonic_ns() / 1e9;
}
