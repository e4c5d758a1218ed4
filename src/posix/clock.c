/* Monotonic clock of the POSIX layer (CLOCK_MONOTONIC). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <limits.h>
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

int lep_priv_ms_left(int64_t deadline_ns)
{
    int64_t left = deadline_ns - lep_priv_monotonic_ns();
    if (left <= 0)
        return 0;
    left = (left + 999999) / 1000000;
    return left > INT_MAX ? INT_MAX : (int)left;
}
