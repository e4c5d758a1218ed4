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
    cli_print_help_end(stdout, 1);
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
    lep_session_options so;
    lep_session *sess;
    const char *setting = NULL;
    const char *pos[2] = { NULL, NULL };
    int npos = 0;
    uint8_t code = 0;
    int rc, exit_code;
    bool sim = false;

    cli_args_init(&a, argc, argv, "filter");
    cli_port_opts_init(&po, false);
    while (cli_args_next(&a)) {
        if (cli_args_help(&a)) {
            help();
            return CLI_OK;
        } else if (cli_args_is(&a, NULL, "--sim")) {
            sim = true;
            cli_port_option(&po, &a);
        } else if (a.positional && npos < 2) {
            pos[npos++] = a.cur;
        } else if (!cli_port_option(&po, &a)) {
            cli_args_unknown(&a);
        }
    }
    if (a.failed)
        return CLI_USAGE;
    /* PORT comes first unless --sim; the code is the last positional. */
    if ((sim && npos == 2) || (!sim && npos == 0)) {
        if (npos == 2)
            cli_args_error(&a, "give either PORT or --sim, not both");
        else
            cli_port_check(&po, &a);
        return CLI_USAGE;
    }
    if (npos == 2 || (sim && npos == 1))
        setting = pos[npos - 1];
    if (setting != NULL && !parse_code(setting, &code)) {
        cli_args_error(&a, "invalid filter code '%s' (off, 0, 1, 2 or 3)", setting);
        return CLI_USAGE;
    }
    if (!sim && !cli_port_add(&po, &a, pos[0]))
        return CLI_USAGE;
    if (!cli_port_check(&po, &a))
        return CLI_USAGE;

    lep_session_options_init(&so);
    exit_code = cli_sensors_open(&po, &so, "filter");
    if (exit_code != CLI_OK)
        return exit_code;
    sess = po.sensor[0].session;
    if (setting == NULL) {
        lep_session_meta m;
        lep_session_get_metadata(sess, &m);
        if (m.sensor_filter >= 0)
            printf("filter: %d (%s)\n", m.sensor_filter, m.sensor_filter_label);
        else
            printf("filter: not supported by this sensor\n");
    } else {
        rc = lep_client_filter_set(lep_session_client(sess), code);
        if (rc != LEP_OK) {
            exit_code = cli_session_fail(sess, "filter", lep_session_port(sess), "filter set", rc);
        } else {
            printf("filter set to %u (%s)\n", (unsigned)code, lep_filter_label(code));
            fprintf(stderr, "leptrino: filter: the new setting takes effect after the sensor is "
                            "power-cycled (unplug and replug it)\n");
        }
    }
    cli_sensors_close(&po);
    return exit_code;
}
