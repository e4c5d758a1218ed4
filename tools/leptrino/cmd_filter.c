/* `leptrino filter`: show the digital filter, or set it (effective after a
 * power cycle of the sensor). */
#include <string.h>

#include "cli.h"

static void help(void)
{
    fputs("Usage: leptrino filter PORT|--sim [off|0|1|2|3] [options]\n"
          "\n"
          "Without a code: show the filter code and its label. With a code: set it.\n"
          "The sensor applies a new setting only after its power is switched off and\n"
          "on again (unplug and replug it). Codes per spec v1.13: 0 off, 1 10 Hz,\n"
          "2 100 Hz, 3 200 Hz (FIR cut-off); some models use other cut-offs for the\n"
          "same codes: the code is the truth, the label a guide.\n"
          "\n"
          "Options:\n"
          "  -h, --help              show this help\n",
          stdout);
    cli_port_help(stdout);
    fputc('\n', stdout);
    cli_print_exit_codes(stdout);
}

static bool parse_code(const char *s, uint8_t *code)
{
    if (strcmp(s, "off") == 0) {
        *code = 0;
        return true;
    }
    if (s[0] >= '0' && s[0] <= '0' + (int)LEP_FILTER_MAX && s[1] == '\0') {
        *code = (uint8_t)(s[0] - '0');
        return true;
    }
    return false;
}

int cli_cmd_filter(int argc, char **argv)
{
    cli_args a;
    cli_port_opts po;
    cli_conn c;
    const char *setting = NULL;
    const char *pos[2] = {NULL, NULL};
    int npos = 0;
    uint8_t code = 0;
    int rc, exit_code;

    cli_args_init(&a, argc, argv, "filter");
    cli_port_opts_init(&po);
    while (cli_args_next(&a)) {
        if (cli_args_is(&a, "-h", "--help")) {
            cli_args_flag(&a);
            if (a.failed)
                break;
            help();
            return CLI_OK;
        } else if (cli_port_option(&po, &a)) {
        } else if (a.positional && npos < 2) {
            pos[npos++] = a.cur;
        } else {
            cli_args_unknown(&a);
        }
    }
    if (a.failed)
        return CLI_USAGE;
    /* PORT comes first unless --sim; the code is the last positional. */
    if (!po.sim && npos >= 1)
        po.port = pos[0];
    if (npos == 2 || (po.sim && npos == 1))
        setting = pos[npos - 1];
    if (po.sim && npos == 2) {
        cli_args_error(&a, "give either PORT or --sim, not both");
        return CLI_USAGE;
    }
    if (setting != NULL && !parse_code(setting, &code)) {
        cli_args_error(&a, "invalid filter code '%s' (off, 0, 1, 2 or 3)", setting);
        return CLI_USAGE;
    }
    if (!cli_port_check(&po, &a))
        return CLI_USAGE;

    exit_code = cli_conn_open(&c, &po, "filter");
    if (exit_code != CLI_OK)
        return exit_code;
    if (setting == NULL) {
        rc = lep_client_filter_get(&c.client, &code);
        if (rc != LEP_OK) {
            exit_code = cli_conn_fail(&c, "filter query", rc);
        } else {
            printf("filter: %u (%s)\n", (unsigned)code, lep_filter_label(code));
        }
    } else {
        rc = lep_client_filter_set(&c.client, code);
        if (rc != LEP_OK) {
            exit_code = cli_conn_fail(&c, "filter set", rc);
        } else {
            printf("filter set to %u (%s)\n", (unsigned)code, lep_filter_label(code));
            fprintf(stderr, "leptrino: filter: the new setting takes effect after the sensor is "
                            "power-cycled (unplug and replug it)\n");
        }
    }
    cli_conn_close(&c);
    return exit_code;
}
