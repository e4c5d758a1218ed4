/* What a program built on the library needs of its own process: the exit
 * status for a LEP_E_* code, and the CPU time it has used.
 *
 * The exit statuses are those of the `leptrino` tool (documented in
 * `leptrino --help` and docs/cli.md); `python -m leptrino` and any other front
 * end take them from lep_exit_code, so a given error ends every front end with
 * the same status. POSIX layer; every function is re-entrant. */
#ifndef LEPTRINO_PROCESS_H
#define LEPTRINO_PROCESS_H

#include "error.h"
#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Exit statuses for errors. A program's own outcomes take the statuses above
 * LEP_EXIT_PERMISSION (the leptrino tool's: 9 a limit exceeded, 10-15 the
 * criteria of `leptrino check`). */
enum lep_exit {
    LEP_EXIT_OK = 0,           /* success (a session that reached its end too) */
    LEP_EXIT_FAIL = 1,         /* any other failure (I/O error, output file, protocol) */
    LEP_EXIT_USAGE = 2,        /* bad command line (never returned by lep_exit_code) */
    LEP_EXIT_TIMEOUT = 3,      /* the sensor did not answer / data stopped arriving */
    LEP_EXIT_DISCONNECTED = 4, /* the port went away */
    LEP_EXIT_SENSOR = 5,       /* the sensor refused a command (result code or NAKs) */
    LEP_EXIT_NOT_FOUND = 6,    /* no such port, or not a serial port */
    LEP_EXIT_BUSY = 7,         /* the port is in use by another program */
    LEP_EXIT_PERMISSION = 8    /* no permission to open the port */
};

/* The exit status (LEP_EXIT_*) for err, a LEP_OK or LEP_E_* code: LEP_EXIT_OK
 * for LEP_OK and LEP_E_END (a session that reached its duration or count),
 * LEP_EXIT_FAIL for codes without a status of their own, including any value
 * that is not a LEP_E_* code. Never fails. */
LEP_API int lep_exit_code(int err);

/* CPU time used by the calling process so far (user + system), in seconds;
 * 0 if the system cannot tell. */
LEP_API double lep_cpu_seconds(void);

#ifdef __cplusplus
}
#endif

#endif
