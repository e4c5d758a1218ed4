/* lep_cpu_seconds (leptrino/process.h) on Windows: GetProcessTimes, whose
 * kernel and user times count 100-nanosecond intervals (Microsoft docs,
 * "GetProcessTimes function (processthreadsapi.h)"). */
#include <windows.h>

#include "leptrino/process.h"

static double filetime_seconds(const FILETIME *t)
{
    ULARGE_INTEGER u;
    u.LowPart = t->dwLowDateTime;
    u.HighPart = t->dwHighDateTime;
    return (double)u.QuadPart * 1e-7;
}

double lep_cpu_seconds(void)
{
    FILETIME created, exited, kernel, user;
    if (!GetProcessTimes(GetCurrentProcess(), &created, &exited, &kernel, &user))
        return 0.0;
    return filetime_seconds(&kernel) + filetime_seconds(&user);
}
