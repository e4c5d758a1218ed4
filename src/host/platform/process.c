/* The process-level helpers of leptrino/process.h: the one table from
 * LEP_E_* codes to exit statuses, and the process's CPU time. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <sys/resource.h>

#include "leptrino/process.h"

int lep_exit_code(int err)
{
    switch (err) {
    case LEP_OK:
    case LEP_E_END:
        return LEP_EXIT_OK;
    case LEP_E_TIMEOUT:
    case LEP_E_NO_SYNC:
    case LEP_E_STALLED:
    case LEP_E_LOST:
        return LEP_EXIT_TIMEOUT;
    case LEP_E_DISCONNECTED:
        return LEP_EXIT_DISCONNECTED;
    case LEP_E_SENSOR:
    case LEP_E_NAK:
        return LEP_EXIT_SENSOR;
    case LEP_E_NOT_FOUND:
    case LEP_E_NOT_TTY:
        return LEP_EXIT_NOT_FOUND;
    case LEP_E_BUSY:
        return LEP_EXIT_BUSY;
    case LEP_E_PERMISSION:
        return LEP_EXIT_PERMISSION;
    default:
        return LEP_EXIT_FAIL;
    }
}

double lep_cpu_seconds(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0)
        return 0.0;
    return (double)ru.ru_utime.tv_sec + (double)ru.ru_utime.tv_usec * 1e-6 +
           (double)ru.ru_stime.tv_sec + (double)ru.ru_stime.tv_usec * 1e-6;
}
