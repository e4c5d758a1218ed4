/* Host session, clocks: the UTC offset of the monotonic clock samples are
 * stamped with, the cheap check that it may have moved, and waits in ms. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <math.h>
#include <time.h>

#include "session_clock.h"

double lep_priv_utc_offset_within(double *width)
{
    /* The wall clock read between two monotonic reads; the try with the
     * narrowest bracket wins, so a thread descheduled between the reads
     * (which skews a try by the time it lost) does not move the offset:
     * UTC intervals then equal monotonic ones to well under 1 ms. */
    double best = 0.0, best_width = -1.0;
    int i;
    for (i = 0; i < SESSION_UTC_TRIES && (i < 3 || best_width >= SESSION_UTC_BRACKET_S); ++i) {
        struct timespec a, r, b;
        double ma, mb, rt;
        (void)clock_gettime(CLOCK_MONOTONIC, &a);
        (void)clock_gettime(CLOCK_REALTIME, &r);
        (void)clock_gettime(CLOCK_MONOTONIC, &b);
        ma = (double)a.tv_sec + (double)a.tv_nsec / 1e9;
        mb = (double)b.tv_sec + (double)b.tv_nsec / 1e9;
        rt = (double)r.tv_sec + (double)r.tv_nsec / 1e9;
        if (best_width < 0.0 || mb - ma < best_width) {
            best_width = mb - ma;
            best = rt - (ma + mb) / 2.0;
        }
    }
    if (width != NULL)
        *width = best_width;
    return best;
}

double lep_priv_utc_offset(void)
{
    return lep_priv_utc_offset_within(NULL);
}

/* One CLOCK_REALTIME read happened at a monotonic instant between t_before
 * (a monotonic time taken earlier) and a monotonic read just after it, so the
 * true offset lies in that bracket. Two clock reads instead of
 * lep_priv_utc_offset's nine; only when the bracket leaves
 * utc_off +- SESSION_UTC_STEP_S (a step, or this thread lost the CPU in
 * between) does the caller measure the offset properly. */
bool lep_priv_utc_may_have_moved(double utc_off, double t_before)
{
    struct timespec r, b;
    double rt, lo, hi;
    (void)clock_gettime(CLOCK_REALTIME, &r);
    (void)clock_gettime(CLOCK_MONOTONIC, &b);
    rt = (double)r.tv_sec + (double)r.tv_nsec / 1e9;
    lo = rt - ((double)b.tv_sec + (double)b.tv_nsec / 1e9);
    hi = rt - t_before;
    return lo < utc_off - SESSION_UTC_STEP_S || hi > utc_off + SESSION_UTC_STEP_S;
}

int lep_priv_ms_until(double t, double now)
{
    double ms;
    if (isinf(t))
        return -1;
    ms = ceil((t - now) * 1000.0);
    if (ms <= 0.0)
        return 0;
    return ms > 2147483647.0 ? 2147483647 : (int)ms;
}
