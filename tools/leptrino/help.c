/* The help text every command ends with: the sensor options and the exit
 * codes (the codes of LEP_E_* errors themselves: lep_exit_code, leptrino/process.h). */
#include "cli.h"

void cli_print_exit_codes(FILE *f)
{
    fputs("Exit codes:\n"
          "  0  success (also: stream stopped by Ctrl-C or SIGTERM)\n"
          "  1  other failure (I/O error, output file, protocol error)\n"
          "  2  bad command line\n"
          "  3  timeout: the sensor did not answer, or data stopped arriving\n"
          "  4  disconnected: the port went away\n"
          "  5  sensor error: the sensor refused a command (result code, or NAKs)\n"
          "  6  port not found, or not a serial port\n"
          "  7  port busy: in use by another program\n"
          "  8  permission denied on the port\n"
          "  9  stream --stop-on-limit: a limit was exceeded\n"
          "  10..15  check: the first criterion that failed: 10 status bits, 11 frame\n"
          "          errors, 12 samples lost, 13 rate, 14 overload, 15 noise\n",
          f);
}

void cli_print_help_end(FILE *f, int sensors)
{
    if (sensors > 0) {
        cli_port_help(f, sensors > 1);
        fputc('\n', f);
    }
    cli_print_exit_codes(f);
}
