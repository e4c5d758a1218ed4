/* `leptrino watch` on Windows: not there yet. Its full-screen view drives a
 * POSIX terminal (termios keys, SIGWINCH); a Windows console port is future
 * work (docs/windows.md). It says so and points at `leptrino stream`. */
#include <stdio.h>

#include "cli.h"

int cli_cmd_watch(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "leptrino: watch: not available on Windows yet (the live view needs a POSIX "
                    "terminal); use `leptrino stream PORT` (docs/windows.md)\n");
    return CLI_FAIL;
}
