/* Monotonic clock of the host layer on Windows: QueryPerformanceCounter, the
 * monotonic high-resolution counter Microsoft recommends for time stamps
 * ("Acquiring high-resolution time stamps"); its frequency is fixed at boot.
 * Sleeping is Sleep() in whole milliseconds (its resolution is the system
 * timer's, 1 to 15.6 ms): callers look at the clock again after it. */
#include <limits.h>
#include <windows.h>

#include "leptrino/serial.h"
#include "struct_api.h"
#include "posix_clock.h"

int64_t lep_priv_monotonic_ns(void)
{
    LARGE_INTEGER f, c;
    int64_t sec, rem;
    if (!QueryPerformanceFrequency(&f) || f.QuadPart <= 0 || !QueryPerformanceCounter(&c))
        return 0;
    /* Split so that counter * 1e9 never overflows. */
    sec = c.QuadPart / f.QuadPart;
    rem = c.QuadPart % f.QuadPart;
    return sec * 1000000000 + rem * 1000000000 / f.QuadPart;
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
    int ms = lep_priv_ms_left(until_ns);
    if (ms > 0)
        Sleep((DWORD)ms);
}
