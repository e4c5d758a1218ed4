/* leptrino: command-line tool for Leptrino 6-axis force/torque sensors.
 * Entry point: global options (--help, --version) and command dispatch. */
#include <string.h>

#include "cli.h"

typedef struct cli_command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} cli_command;

static const cli_command COMMANDS[] = {
    { "list", cli_cmd_list, "list serial ports, marking likely sensors" },
    { "info", cli_cmd_info, "show model, serial, firmware, rated values, filter" },
    { "read", cli_cmd_read, "read N samples one by one (handshake mode)" },
    { "stream", cli_cmd_stream, "record one or more sensors to CSV or JSON lines" },
    { "watch", cli_cmd_watch, "live view in the terminal: bars, rate, errors; keys t, u, q" },
    { "filter", cli_cmd_filter, "show or set the digital filter" },
    { "check", cli_cmd_check,
      "commissioning: judge a sensor's health, an exit code per criterion" },
    { "payload", cli_cmd_payload, "identify a tool's mass and centre of mass from recorded poses" },
};

#define N_COMMANDS (sizeof COMMANDS / sizeof COMMANDS[0])

static void usage(FILE *f)
{
    size_t i;
    fputs("Usage: leptrino COMMAND [options]\n"
          "  or:  leptrino --version | --help | help COMMAND | help sim\n"
          "\n"
          "Talk to Leptrino 6-axis force/torque sensors over a serial port, or to a\n"
          "built-in virtual sensor (--sim) when there is no hardware.\n"
          "\n"
          "Commands:\n",
          f);
    for (i = 0; i < N_COMMANDS; ++i)
        fprintf(f, "  %-8s %s\n", COMMANDS[i].name, COMMANDS[i].summary);
    fputs("\n"
          "Examples:\n"
          "  leptrino stream --sim --duration 3\n"
          "  leptrino info /dev/ttyACM0\n"
          "  leptrino stream /dev/ttyACM0 --tare 100 -o forces.csv\n"
          "  leptrino watch --sim\n"
          "\n"
          "'leptrino COMMAND --help' shows the options of a command, 'leptrino help sim'\n"
          "those of the virtual sensor (--sim-NAME VALUE).\n"
          "\n",
          f);
    cli_print_exit_codes(f);
}

static const cli_command *find_command(const char *name)
{
    size_t i;
    for (i = 0; i < N_COMMANDS; ++i)
        if (strcmp(COMMANDS[i].name, name) == 0)
            return &COMMANDS[i];
    return NULL;
}

int main(int argc, char **argv)
{
    const cli_command *cmd;
    bool help;
    if (argc < 2) {
        fprintf(stderr, "leptrino: missing command (see 'leptrino --help')\n");
        return CLI_USAGE;
    }
    help = strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0;
    if (help || strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "-V") == 0) {
        if (argc > 2) {
            fprintf(stderr, "leptrino: unexpected argument '%s' after %s (see 'leptrino --help')\n",
                    argv[2], argv[1]);
            return CLI_USAGE;
        }
        if (help)
            usage(stdout);
        else
            printf("leptrino %s\n", lep_version());
        return CLI_OK;
    }
    if (strcmp(argv[1], "help") == 0) {
        char help_flag[] = "--help";
        char *sub[3];
        if (argc < 3) {
            usage(stdout);
            return CLI_OK;
        }
        if (argc > 3) {
            fprintf(stderr, "leptrino: help: unexpected argument '%s'\n", argv[3]);
            return CLI_USAGE;
        }
        if (strcmp(argv[2], "sim") == 0) {
            cli_sim_help(stdout);
            return CLI_OK;
        }
        cmd = find_command(argv[2]);
        if (cmd == NULL) {
            fprintf(stderr, "leptrino: help: unknown command '%s' (see 'leptrino --help')\n",
                    argv[2]);
            return CLI_USAGE;
        }
        sub[0] = argv[2];
        sub[1] = help_flag;
        sub[2] = NULL;
        return cmd->run(2, sub);
    }
    if (argv[1][0] == '-') {
        fprintf(stderr,
                "leptrino: unknown option '%s' before the command (see 'leptrino --help')\n",
                argv[1]);
        return CLI_USAGE;
    }
    cmd = find_command(argv[1]);
    if (cmd == NULL) {
        fprintf(stderr, "leptrino: unknown command '%s' (see 'leptrino --help')\n", argv[1]);
        return CLI_USAGE;
    }
    return cmd->run(argc - 1, argv + 1);
}
