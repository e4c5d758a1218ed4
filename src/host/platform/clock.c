/* Monotonic clock of the POSIX layer (CLOCK_MONOTONIC). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <limits.h>
#include <time.h>

#include "leptrino/serial.h"
#include "struct_api.h"
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

void lep_priv_sleep_until_ns(int64_t until_ns)
{
    struct timespec ts;
#if defined(__linux__)
    ts.tv_sec = (time_t)(until_ns / 1000000000);
    ts.tv_nsec = (long)(until_ns % 1000000000);
    (void)clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL);
#else
    int64_t left = until_ns - lep_priv_monotonic_ns();
    if (left <= 0)
        return;
    ts.tv_sec = (time_t)(left / 1000000000);
    ts.tv_nsec = (long)(left % 1000000000);
    (void)nanosleep(&ts, NULL);
#endif
}
