/* The process-level helpers of leptrino/process.h: the one table from
 * LEP_E_* codes to exit statuses (the process's CPU time is in
 * cpu_time_posix.c / cpu_time_win32.c). */
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
