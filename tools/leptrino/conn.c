/* The sensor a command talks to: a real port (PORT) or the in-process
 * virtual sensor (--sim and its --sim-* options), opened with the start-up
 * recovery sequence, and the mapping of library errors to exit codes. */
#define _POSIX_C_SOURCE 200809L

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

/* Quiet time that ends the start-up drain of a stale stream. */
#define CLI_SYNC_QUIET_MS 30

void cli_port_opts_init(cli_port_opts *po)
{
    memset(po, 0, sizeof *po);
    lep_sim_options_init(&po->sim_opts);
    /* Longer than the library's 100 ms: a loaded gateway or a USB hub can be
     * slow to answer, and the wait only matters when no sensor answers. */
    po->timeout_ms = 500;
}

static bool model_known(const char *name)
{
    const char *const *m;
    for (m = lep_sim_models(); *m != NULL; ++m)
        if (strcmp(*m, name) == 0)
            return true;
    return false;
}

static void list_models(char *buf, size_t cap)
{
    const char *const *m;
    size_t used = 0;
    buf[0] = '\0';
    for (m = lep_sim_models(); *m != NULL; ++m) {
        size_t n = strlen(*m);
        if (used + n + 3 >= cap)
            break;
        if (used > 0) {
            memcpy(buf + used, ", ", 2);
            used += 2;
        }
        memcpy(buf + used, *m, n);
        used += n;
        buf[used] = '\0';
    }
}

/* --sim-* options: a table keeps the names, help and parsing in one place. */
enum sim_kind { K_FLAG, K_STR, K_DOUBLE, K_PROB, K_MS, K_U64, K_FILTER, K_MODEL };

typedef struct sim_opt {
    const char *name;
    enum sim_kind kind;
    const char *arg;
    const char *help;
} sim_opt;

static const sim_opt SIM_OPTS[] = {
    {"--sim-model", K_MODEL, "NAME", "model preset (default PFS055YA501U6)"},
    {"--sim-rate", K_DOUBLE, "HZ", "continuous output rate (default 1200)"},
    {"--sim-seed", K_U64, "N", "seed of the waveform and of the faults (default 1)"},
    {"--sim-serial", K_STR, "DIGITS", "serial number, 1..8 digits (default 00000001)"},
    {"--sim-firmware", K_STR, "VER", "firmware version, 1..4 characters (default 1.13)"},
    {"--sim-output-rate-field", K_FLAG, NULL, "product info in the 38-byte form with output rate"},
    {"--sim-filter", K_FILTER, "CODE", "filter code in effect at power-on, 0..3 (default 0)"},
    {"--sim-amplitude", K_DOUBLE, "F", "sine amplitude (or constant level) as a fraction of rated"},
    {"--sim-noise", K_DOUBLE, "F", "noise amplitude as a fraction of rated (default 0.005)"},
    {"--sim-constant", K_FLAG, NULL, "hold a constant load (the amplitude) with no noise"},
    {"--sim-replay", K_STR, "CSV", "replay raw counts fx,fy,fz,mx,my,mz per line, looping"},
    {"--sim-overload-every", K_DOUBLE, "S", "start an overload episode every S seconds"},
    {"--sim-overload-duration", K_DOUBLE, "S", "length of an overload episode (default 0.1)"},
    {"--sim-nak", K_PROB, "P", "fault: probability of NAKing a valid command"},
    {"--sim-corrupt", K_PROB, "P", "fault: probability of corrupting a byte of a message"},
    {"--sim-garbage", K_PROB, "P", "fault: probability of garbage between messages"},
    {"--sim-drop", K_PROB, "P", "fault: probability of dropping a message"},
    {"--sim-stall", K_MS, "MS", "fault: stall (send and answer nothing) for MS ms ..."},
    {"--sim-stall-after", K_DOUBLE, "S", "... starting S seconds after start"},
    {"--sim-hangup-after", K_DOUBLE, "S", "fault: hang up the port (like a pulled cable) after S s"},
    {"--sim-reopen-after", K_MS, "MS", "after a hang-up, bring the port back after MS ms"},
    {"--sim-start-streaming", K_FLAG, NULL, "power up already streaming (a stale stream)"},
    {"--sim-link", K_STR, "PATH", "also make a symlink PATH to the virtual port"},
};

#define N_SIM_OPTS (sizeof SIM_OPTS / sizeof SIM_OPTS[0])

static void apply_sim_option(cli_port_opts *po, cli_args *a, const sim_opt *o)
{
    lep_sim_options *so = &po->sim_opts;
    const char *n = o->name;
    const char *s = NULL;
    double d = 0.0;
    uint64_t u = 0;

    switch (o->kind) {
    case K_FLAG:
        cli_args_flag(a);
        break;
    case K_STR:
        s = cli_args_value(a);
        break;
    case K_DOUBLE:
        if (strcmp(n, "--sim-rate") == 0)
            d = cli_args_double(a, 0.0, 10000.0, true);
        else if (strcmp(n, "--sim-amplitude") == 0)
            d = cli_args_double(a, 0.0, 3.2, false);
        else if (strcmp(n, "--sim-noise") == 0)
            d = cli_args_double(a, 0.0, 1.0, false);
        else if (strcmp(n, "--sim-overload-duration") == 0 || strcmp(n, "--sim-hangup-after") == 0)
            d = cli_args_double(a, 0.0, 1e6, true);
        else
            d = cli_args_double(a, 0.0, 1e6, false);
        break;
    case K_PROB:
        d = cli_args_double(a, 0.0, 1.0, false);
        break;
    case K_MS:
        u = cli_args_uint(a, 0, 3600000);
        break;
    case K_U64:
        u = cli_args_uint(a, 0, UINT64_MAX);
        break;
    case K_FILTER:
        u = cli_args_uint(a, 0, LEP_FILTER_MAX);
        break;
    case K_MODEL:
        s = cli_args_value(a);
        if (s != NULL && !model_known(s)) {
            char models[256];
            list_models(models, sizeof models);
            cli_args_error(a, "unknown model '%s' for %s (known: %s)", s, n, models);
        }
        break;
    }
    if (a->failed)
        return;
    if (po->sim_option == NULL)
        po->sim_option = n;

    if (strcmp(n, "--sim-model") == 0) snprintf(so->model, sizeof so->model, "%s", s);
    else if (strcmp(n, "--sim-rate") == 0) so->rate_hz = d;
    else if (strcmp(n, "--sim-seed") == 0) so->seed = u;
    else if (strcmp(n, "--sim-serial") == 0) {
        size_t i, len = strlen(s);
        bool ok = len >= 1 && len <= LEP_SERIAL_LEN;
        for (i = 0; ok && i < len; ++i)
            ok = s[i] >= '0' && s[i] <= '9';
        if (!ok)
            cli_args_error(a, "option %s: '%s' is not 1 to 8 digits", n, s);
        snprintf(so->serial, sizeof so->serial, "%s", s);
    } else if (strcmp(n, "--sim-firmware") == 0) {
        if (strlen(s) > LEP_FIRMWARE_LEN)
            cli_args_error(a, "option %s: '%s' is longer than 4 characters", n, s);
        snprintf(so->firmware, sizeof so->firmware, "%s", s);
    } else if (strcmp(n, "--sim-output-rate-field") == 0) so->output_rate_field = true;
    else if (strcmp(n, "--sim-filter") == 0) so->filter = (uint8_t)u;
    else if (strcmp(n, "--sim-amplitude") == 0) so->amplitude = d;
    else if (strcmp(n, "--sim-noise") == 0) so->noise = d;
    else if (strcmp(n, "--sim-constant") == 0) so->constant = true;
    else if (strcmp(n, "--sim-replay") == 0) snprintf(so->replay_csv, sizeof so->replay_csv, "%s", s);
    else if (strcmp(n, "--sim-overload-every") == 0) so->overload_every_s = d;
    else if (strcmp(n, "--sim-overload-duration") == 0) so->overload_duration_s = d;
    else if (strcmp(n, "--sim-nak") == 0) so->p_nak = d;
    else if (strcmp(n, "--sim-corrupt") == 0) so->p_corrupt = d;
    else if (strcmp(n, "--sim-garbage") == 0) so->p_garbage = d;
    else if (strcmp(n, "--sim-drop") == 0) so->p_drop = d;
    else if (strcmp(n, "--sim-stall") == 0) so->stall_ms = (int)u;
    else if (strcmp(n, "--sim-stall-after") == 0) so->stall_after_s = d;
    else if (strcmp(n, "--sim-hangup-after") == 0) so->hangup_after_s = d;
    else if (strcmp(n, "--sim-reopen-after") == 0) {
        so->reopen_after_ms = (int)u;
        po->sim_reopen = true;
    }
    else if (strcmp(n, "--sim-start-streaming") == 0) so->start_streaming = true;
    else if (strcmp(n, "--sim-link") == 0) snprintf(so->link, sizeof so->link, "%s", s);
}

bool cli_port_option(cli_port_opts *po, cli_args *a)
{
    size_t i;
    if (cli_args_is(a, NULL, "--sim")) {
        cli_args_flag(a);
        po->sim = true;
        return true;
    }
    if (cli_args_is(a, "-t", "--timeout")) {
        po->timeout_ms = (int)cli_args_uint(a, 1, 60000);
        return true;
    }
    for (i = 0; i < N_SIM_OPTS; ++i) {
        if (cli_args_is(a, NULL, SIM_OPTS[i].name)) {
            apply_sim_option(po, a, &SIM_OPTS[i]);
            return true;
        }
    }
    return false;
}

bool cli_port_check(cli_port_opts *po, cli_args *a)
{
    if (a->failed)
        return false;
    if (po->sim && po->port != NULL) {
        cli_args_error(a, "give either PORT or --sim, not both");
        return false;
    }
    if (!po->sim && po->port == NULL) {
        cli_args_error(a, "missing PORT (a serial device such as /dev/ttyACM0) or --sim");
        return false;
    }
    if (!po->sim && po->port[0] == '\0') {
        cli_args_error(a, "PORT is empty (a serial device such as /dev/ttyACM0)");
        return false;
    }
    if (!po->sim && po->sim_option != NULL) {
        cli_args_error(a, "option %s needs --sim", po->sim_option);
        return false;
    }
    if (po->sim && po->sim_reopen && po->sim_opts.link[0] == '\0') {
        /* The port must come back under the same name: make up a link. */
        const char *dir = getenv("TMPDIR");
        if (dir == NULL || dir[0] == '\0' || strlen(dir) > 64)
            dir = "/tmp";
        snprintf(po->link_buf, sizeof po->link_buf, "%s/leptrino-sim-%ld", dir, (long)getpid());
        snprintf(po->sim_opts.link, sizeof po->sim_opts.link, "%s", po->link_buf);
        po->reopen_link_auto = true;
    }
    return true;
}

void cli_port_help(FILE *f)
{
    size_t i;
    fputs("Port:\n"
          "  PORT                    serial device, e.g. /dev/ttyACM0 or /dev/serial/by-id/...\n"
          "  --sim                   use a built-in virtual sensor instead of a port\n"
          "  -t, --timeout MS        answer timeout per command in ms (default 500)\n"
          "Virtual sensor (with --sim only):\n",
          f);
    for (i = 0; i < N_SIM_OPTS; ++i) {
        char left[64];
        snprintf(left, sizeof left, "%s%s%s", SIM_OPTS[i].name, SIM_OPTS[i].arg ? " " : "",
                 SIM_OPTS[i].arg ? SIM_OPTS[i].arg : "");
        fprintf(f, "  %-27s %s\n", left, SIM_OPTS[i].help);
    }
}

int cli_exit_code(int err)
{
    switch (err) {
    case LEP_OK:
        return CLI_OK;
    case LEP_E_TIMEOUT:
    case LEP_E_NO_SYNC:
        return CLI_TIMEOUT;
    case LEP_E_DISCONNECTED:
        return CLI_DISCONNECTED;
    case LEP_E_SENSOR:
    case LEP_E_NAK:
        return CLI_SENSOR;
    case LEP_E_NOT_FOUND:
    case LEP_E_NOT_TTY:
        return CLI_NOT_FOUND;
    case LEP_E_BUSY:
        return CLI_BUSY;
    case LEP_E_PERMISSION:
        return CLI_PERMISSION;
    default:
        return CLI_FAIL;
    }
}

int cli_conn_fail(const cli_conn *c, const char *what, int err)
{
    const char *path = c->path[0] != '\0' ? c->path : "(no port)";
    if (err == LEP_E_SENSOR) {
        uint8_t r = lep_client_last_result(&c->client);
        fprintf(stderr, "leptrino: %s: %s: %s: the sensor answered result 0x%02X (%s)\n", c->cmd,
                path, what, (unsigned)r, lep_result_str(r));
    } else if (err == LEP_E_DISCONNECTED) {
        fprintf(stderr, "leptrino: %s: %s: %s: disconnected (the port went away)\n", c->cmd, path,
                what);
    } else if (err == LEP_E_TIMEOUT) {
        fprintf(stderr, "leptrino: %s: %s: %s: timeout (no answer within %d ms; is a sensor "
                        "connected and powered?)\n",
                c->cmd, path, what, c->timeout_ms);
    } else {
        fprintf(stderr, "leptrino: %s: %s: %s: %s\n", c->cmd, path, what, lep_strerror(err));
    }
    return cli_exit_code(err);
}

static int open_and_sync(cli_conn *c, char *err, size_t errlen)
{
    int rc = lep_serial_open(c->path, &c->serial, err, errlen);
    if (rc != LEP_OK) {
        c->serial = NULL;
        return rc;
    }
    rc = lep_serial_client_init(&c->client, c->serial);
    if (rc == LEP_OK)
        rc = lep_client_set_timeout(&c->client, c->timeout_ms);
    if (rc == LEP_OK)
        rc = lep_client_sync(&c->client, CLI_SYNC_QUIET_MS, &c->info);
    return rc;
}

int cli_conn_open(cli_conn *c, const cli_port_opts *po, const char *cmd)
{
    char err[512];
    int rc;

    memset(c, 0, sizeof *c);
    c->cmd = cmd;
    c->timeout_ms = po->timeout_ms;
    err[0] = '\0';
    if (po->sim) {
        rc = lep_sim_start(&po->sim_opts, &c->sim, err, sizeof err);
        if (rc != LEP_OK) {
            c->sim = NULL;
            fprintf(stderr, "leptrino: %s: cannot start the virtual sensor: %s\n", cmd,
                    err[0] != '\0' ? err : lep_strerror(rc));
            /* Not a port problem (a missing --sim-replay file is not exit 6). */
            return CLI_FAIL;
        }
        snprintf(c->path, sizeof c->path, "%s", lep_sim_port(c->sim));
    } else {
        snprintf(c->path, sizeof c->path, "%s", po->port);
    }
    err[0] = '\0';
    rc = open_and_sync(c, err, sizeof err);
    if (rc != LEP_OK) {
        int code;
        if (c->serial == NULL && err[0] != '\0') {
            fprintf(stderr, "leptrino: %s: %s\n", cmd, err);
            code = cli_exit_code(rc);
        } else {
            code = cli_conn_fail(c, "start-up recovery (stop, drain, product info)", rc);
        }
        cli_conn_close(c);
        return code == CLI_OK ? CLI_FAIL : code;
    }
    return CLI_OK;
}

int cli_conn_reopen(cli_conn *c)
{
    char err[256];
    cli_conn_drop(c);
    return open_and_sync(c, err, sizeof err);
}

void cli_conn_drop(cli_conn *c)
{
    lep_serial_close(c->serial);
    c->serial = NULL;
}

void cli_conn_close(cli_conn *c)
{
    cli_conn_drop(c);
    lep_sim_stop(c->sim);
    c->sim = NULL;
}
