/* The sensors a command talks to: serial PORTs and virtual sensors (--sim),
 * each opened as a session (leptrino/session.h), which does the start-up
 * recovery, identity, rated values and filter query in one place. Also the
 * mapping of library errors to exit codes.
 *
 * Virtual sensor options are not listed here: `--sim-NAME VALUE` is looked
 * up in the simulator's own option table (lep_sim_option_find), which
 * parses and range-checks the value; help comes from the same table. Each
 * --sim adds a virtual sensor; a --sim-* option applies to the virtual
 * sensor of the last --sim before it, or to every one when it comes before
 * the first --sim. */
#define _POSIX_C_SOURCE 200809L

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

#define SIM_PREFIX "--sim-"

void cli_port_opts_init(cli_port_opts *po, bool several)
{
    memset(po, 0, sizeof *po);
    po->several = several;
    lep_sim_options_init(&po->sim_defaults);
    /* Longer than the library's 100 ms: a loaded gateway or a USB hub can be
     * slow to answer, and the wait only matters when no sensor answers. */
    po->timeout_ms = 500;
}

static cli_sensor *add_sensor(cli_port_opts *po, cli_args *a)
{
    cli_sensor *s;
    if (po->n > 0 && !po->several) {
        if (a->positional && po->sensor[0].port != NULL)
            cli_args_error(a, "unexpected argument '%s' (one PORT or --sim)", a->cur);
        else if (!a->positional && po->sensor[0].port == NULL)
            cli_args_error(a, "--sim given twice (this command takes one sensor)");
        else
            cli_args_error(a, "give either PORT or --sim, not both");
        return NULL;
    }
    if (po->n == CLI_MAX_SENSORS) {
        cli_args_error(a, "at most %d sensors at once", CLI_MAX_SENSORS);
        return NULL;
    }
    s = &po->sensor[po->n++];
    memset(s, 0, sizeof *s);
    return s;
}

/* The virtual sensor a --sim-* option applies to (NULL: the defaults). */
static lep_sim_options *sim_target(cli_port_opts *po)
{
    size_t i = po->n;
    while (i > 0) {
        --i;
        if (po->sensor[i].port == NULL)
            return &po->sensor[i].sim;
    }
    return NULL;
}

static bool sim_option(cli_port_opts *po, cli_args *a)
{
    const lep_sim_option_info *info;
    const char *value;
    lep_sim_options *target;
    char err[256];

    if (a->positional || strncmp(a->name, SIM_PREFIX, strlen(SIM_PREFIX)) != 0)
        return false;
    info = lep_sim_option_find(a->name + strlen(SIM_PREFIX));
    if (info == NULL || strcmp(info->name, a->name + strlen(SIM_PREFIX)) != 0)
        return false; /* reported as an unknown option (only the dashed name is one) */
    a->matched = true;
    if (info->type == LEP_SIM_OPT_FLAG) {
        cli_args_flag(a);
        value = "true";
    } else {
        value = cli_args_value(a);
    }
    if (a->failed)
        return true;
    if (po->sim_option == NULL)
        po->sim_option = info->name;
    target = sim_target(po);
    err[0] = '\0';
    /* Before the first --sim: check it on the defaults, which every later
     * --sim starts from; after one: that virtual sensor only. */
    if (lep_sim_option_set(target != NULL ? target : &po->sim_defaults, info->name, value, err,
                           sizeof err) != LEP_OK) {
        cli_args_error(a, "option %s: %s", a->name, err[0] != '\0' ? err : "invalid value");
        return true;
    }
    return true;
}

bool cli_port_option(cli_port_opts *po, cli_args *a)
{
    cli_sensor *s;
    if (cli_args_is(a, NULL, "--sim")) {
        cli_args_flag(a);
        if (a->failed || (s = add_sensor(po, a)) == NULL)
            return true;
        s->sim = po->sim_defaults;
        po->sims++;
        snprintf(s->name, sizeof s->name, "sim%lu", (unsigned long)po->sims);
        if (po->sims > 1) {
            /* Two virtual sensors with one seed would send the same data:
             * each further one starts from the next seed and serial (its own
             * --sim-seed / --sim-serial after it still set them). */
            char serial[24];
            snprintf(serial, sizeof serial, "%08lu", (unsigned long)po->sims);
            s->sim.seed += po->sims - 1;
            if (strcmp(s->sim.serial, "00000001") == 0)
                (void)lep_sim_option_set(&s->sim, "serial", serial, NULL, 0);
        }
        return true;
    }
    if (cli_args_is(a, "-t", "--timeout")) {
        po->timeout_ms = (int)cli_args_uint(a, 1, 60000);
        return true;
    }
    if (sim_option(po, a))
        return true;
    if (a->positional) {
        cli_port_add(po, a, a->cur);
        return true;
    }
    return false;
}

bool cli_port_add(cli_port_opts *po, cli_args *a, const char *port)
{
    cli_sensor *s;
    if ((s = add_sensor(po, a)) == NULL)
        return false;
    if (port[0] == '\0') {
        cli_args_error(a, "PORT is empty (a serial device such as /dev/ttyACM0)");
        return false;
    }
    s->port = port;
    snprintf(s->name, sizeof s->name, "%s", port);
    return true;
}

bool cli_port_check(cli_port_opts *po, cli_args *a)
{
    size_t i, j;
    if (a->failed)
        return false;
    if (po->n == 0) {
        cli_args_error(a, "missing PORT (a serial device such as /dev/ttyACM0) or --sim");
        return false;
    }
    if (po->sims == 0 && po->sim_option != NULL) {
        cli_args_error(a, "option --sim-%s needs --sim", po->sim_option);
        return false;
    }
    for (i = 0; i < po->n; ++i) {
        cli_sensor *s = &po->sensor[i];
        for (j = 0; j < i; ++j) {
            if (s->port != NULL && po->sensor[j].port != NULL &&
                strcmp(s->port, po->sensor[j].port) == 0) {
                cli_args_error(a, "PORT %s is given twice", s->port);
                return false;
            }
        }
    }
    return true;
}

/* "  LEFT   TEXT" with TEXT wrapped at 79 columns under column 27 (LEFT on
 * a line of its own when it is too wide), as help2man expects options. */
static void help_line(FILE *f, const char *left, const char *text)
{
    const int col = 27, width = 79;
    const char *p = text;
    bool first = true;
    if ((int)strlen(left) > col - 4) {
        fprintf(f, "  %s\n", left);
        first = false;
    }
    while (*p != '\0') {
        int room = width - col, len = (int)strlen(p), cut = len;
        if (len > room) {
            for (cut = room; cut > 0 && p[cut] != ' '; --cut) {
            }
            if (cut == 0)
                cut = room; /* one long word: cut it */
        }
        if (first)
            fprintf(f, "  %-*s%.*s\n", col - 2, left, cut, p);
        else
            fprintf(f, "%*s%.*s\n", col, "", cut, p);
        first = false;
        p += cut;
        while (*p == ' ')
            p++;
    }
}

void cli_port_help(FILE *f, bool several)
{
    if (several)
        fputs("Sensors (one or more; each PORT and each --sim adds one):\n"
              "  PORT                     serial device, e.g. /dev/ttyACM0 or\n"
              "                           /dev/serial/by-id/...\n"
              "  --sim                    a built-in virtual sensor (may be repeated)\n",
              f);
    else
        fputs("Sensor:\n"
              "  PORT                     serial device, e.g. /dev/ttyACM0 or\n"
              "                           /dev/serial/by-id/...\n"
              "  --sim                    a built-in virtual sensor instead of a port\n",
              f);
    fputs("  -t, --timeout MS         answer timeout per command in ms (default 500)\n"
          "  --sim-NAME VALUE         an option of the virtual sensor (model, rate, noise,\n"
          "                           replay, faults, ...): 'leptrino help sim' lists them\n",
          f);
}

void cli_sim_help(FILE *f)
{
    size_t i, n = lep_sim_option_count();
    fputs("Usage: leptrino COMMAND --sim [--sim-NAME VALUE ...] [options]\n"
          "\n"
          "Virtual sensor options (with --sim; after a --sim they apply to that virtual\n"
          "sensor, before the first --sim to all of them). The same options as\n"
          "leptrino-sim's, with a sim- prefix:\n",
          f);
    for (i = 0; i < n; ++i) {
        const lep_sim_option_info *o = lep_sim_option_at(i);
        char left[80], text[512], range[80] = "", dflt[80] = "";
        bool number = o->type == LEP_SIM_OPT_INT || o->type == LEP_SIM_OPT_UINT ||
                      o->type == LEP_SIM_OPT_DOUBLE;
        const char *num = o->type == LEP_SIM_OPT_DOUBLE ? "%s%g..%g" : "%s%.0f..%.0f";
        snprintf(left, sizeof left, "--sim-%s%s%s", o->name, o->arg != NULL ? " " : "",
                 o->arg != NULL ? o->arg : "");
        if (number && o->type != LEP_SIM_OPT_DOUBLE && o->max >= 9007199254740992.0)
            snprintf(range, sizeof range, "%.0f or more", o->min); /* a 64-bit whole number */
        else if (number)
            snprintf(range, sizeof range, num, o->min_exclusive ? ">" : "", o->min, o->max);
        if (o->default_text != NULL && o->default_text[0] != '\0')
            snprintf(dflt, sizeof dflt, "%sdefault %s", number ? ", " : "", o->default_text);
        if (range[0] != '\0' || dflt[0] != '\0')
            snprintf(text, sizeof text, "%s (%s%s)", o->help, range, dflt);
        else
            snprintf(text, sizeof text, "%s", o->help);
        help_line(f, left, text);
    }
}

int cli_session_fail(lep_session *s, const char *cmd, const char *port, const char *what, int err)
{
    lep_client *c = s != NULL ? lep_session_client(s) : NULL;
    if (err == LEP_E_SENSOR && c != NULL) {
        uint8_t r = lep_client_last_result(c);
        fprintf(stderr, "leptrino: %s: %s: %s: the sensor answered result 0x%02X (%s)\n", cmd, port,
                what, (unsigned)r, lep_result_str(r));
    } else if (err == LEP_E_DISCONNECTED) {
        fprintf(stderr, "leptrino: %s: %s: %s: disconnected (the port went away)\n", cmd, port,
                what);
    } else if (err == LEP_E_LOST) {
        fprintf(stderr,
                "leptrino: %s: %s: %s: stream lost: no data within --data-timeout "
                "(--reconnect waits for the sensor to come back)\n",
                cmd, port, what);
    } else if (err == LEP_E_TIMEOUT) {
        fprintf(stderr,
                "leptrino: %s: %s: %s: the sensor did not answer (-t/--timeout MS is the wait for "
                "each try)\n",
                cmd, port, what);
    } else {
        fprintf(stderr, "leptrino: %s: %s: %s: %s\n", cmd, port, what, lep_strerror(err));
    }
    return lep_exit_code(err) == CLI_OK ? CLI_FAIL : lep_exit_code(err);
}

int cli_sensors_open(cli_port_opts *po, const lep_session_options *o, const char *cmd)
{
    size_t i;
    for (i = 0; i < po->n; ++i) {
        cli_sensor *s = &po->sensor[i];
        lep_session_options so = *o;
        char err[512];
        int rc;
        so.timeout_ms = po->timeout_ms;
        so.port = s->port;
        so.use_sim = s->port == NULL;
        if (so.use_sim)
            so.sim = s->sim;
        err[0] = '\0';
        rc = lep_session_open_so(&so, &s->session, err, sizeof err);
        if (rc != LEP_OK) {
            int code = lep_exit_code(rc);
            s->session = NULL;
            if (so.use_sim && code == CLI_NOT_FOUND)
                code = CLI_FAIL; /* e.g. a missing --sim-replay file: not a port problem */
            if (rc == LEP_E_ARG || rc == LEP_E_VALUE)
                code = CLI_USAGE; /* options that do not go together, a cut-off too high */
            fprintf(stderr, "leptrino: %s: %s\n", cmd, err[0] != '\0' ? err : lep_strerror(rc));
            cli_sensors_close(po);
            return code == CLI_OK ? CLI_FAIL : code;
        }
        if (err[0] != '\0') /* opened, with a warning (a replay file cut short) */
            fprintf(stderr, "leptrino: %s: warning: %s\n", cmd, err);
    }
    return CLI_OK;
}

void cli_sensors_close(cli_port_opts *po)
{
    size_t i;
    for (i = 0; i < po->n; ++i) {
        lep_session_close(po->sensor[i].session);
        po->sensor[i].session = NULL;
    }
}
