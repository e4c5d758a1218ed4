/* `leptrino check`: commissioning. Connects, reads what the sensor is and
 * one handshake sample, streams for a while, then judges each criterion and
 * exits with the code of the first that failed. The measuring is the
 * session's (identity, health, flags); this file adds up and judges. */
#include <math.h>
#include <string.h>

#include "cli.h"

#define BATCH 512

static void help(void)
{
    fputs("Usage: leptrino check PORT|--sim [options]\n"
          "\n"
          "Commissioning check of a sensor: connect, read its identity, rated values,\n"
          "filter and status bits, stream for --duration, then judge each criterion\n"
          "and print a report (or --json). Exit 0 when every criterion passes, else\n"
          "the code of the first that failed, in this order:\n"
          "  10 status    a status bit set in any sample: ROM calibration data error\n"
          "               (1) or sensor error (2)\n"
          "  11 errors    frame errors (BCC, framing, invalid messages, timeouts) above\n"
          "               --max-errors\n"
          "  12 loss      samples lost (gaps) above --max-loss\n"
          "  13 rate      measured rate below --min-rate percent of the nominal rate\n"
          "  14 overload  an overload (status bit 4, or an axis at saturation)\n"
          "  15 noise     an axis noisier than --max-noise: the RMS of the differences of\n"
          "               consecutive raw counts over sqrt(2), the white noise of the\n"
          "               signal (a steady load or a slow drift does not count; samples\n"
          "               around a gap or an overload are left out). Check with no load\n"
          "               changing on the sensor.\n"
          "A check ended by Ctrl-C or SIGTERM before --duration is over has no\n"
          "verdict: exit 1.\n"
          "\n"
          "Options:\n"
          "  -d, --duration S         stream for S seconds (default 3)\n"
          "      --min-rate PCT       lowest measured rate, percent of nominal (default 98)\n"
          "      --max-loss N         most samples lost (default 0)\n"
          "      --max-errors N       most frame errors (default 0)\n"
          "      --max-noise COUNTS   most noise per axis, RMS counts (default 50;\n"
          "                           10000 counts = rated)\n"
          "      --json               one JSON object instead of the report\n"
          "  -h, --help               show this help\n"
          "\n",
          stdout);
    cli_print_help_end(stdout, 1);
}

typedef struct check_opts {
    double duration_s, min_rate_pct, max_noise;
    uint64_t max_loss, max_errors;
    bool json;
} check_opts;

/* What the stream showed. */
typedef struct check_data {
    lep_session_meta meta;
    lep_session_health_info h;
    uint8_t status_or; /* every sample's status bits, or'ed (with the handshake sample's) */
    uint64_t samples;
    double sq[LEP_AXES]; /* sums of squared differences of consecutive raw counts */
    uint64_t pairs;
    int16_t prev[LEP_AXES];
    bool have_prev;
    double noise[LEP_AXES];
} check_data;

enum { C_STATUS, C_ERRORS, C_LOSS, C_RATE, C_OVERLOAD, C_NOISE, C_COUNT };

typedef struct criterion {
    const char *name;
    int exit_code;
    bool pass;
    char value[96], limit[64];
} criterion;

static int parse(int argc, char **argv, check_opts *o, cli_port_opts *po)
{
    cli_args a;
    cli_args_init(&a, argc, argv, "check");
    o->duration_s = 3.0;
    o->min_rate_pct = 98.0;
    o->max_noise = 50.0;
    o->max_loss = 0;
    o->max_errors = 0;
    o->json = false;
    cli_port_opts_init(po, false);
    while (cli_args_next(&a)) {
        if (cli_args_help(&a)) {
            help();
            return -1;
        } else if (cli_args_is(&a, "-d", "--duration")) {
            o->duration_s = cli_args_double(&a, 0.0, 86400.0, true);
        } else if (cli_args_is(&a, NULL, "--min-rate")) {
            o->min_rate_pct = cli_args_double(&a, 0.0, 200.0, false);
        } else if (cli_args_is(&a, NULL, "--max-loss")) {
            o->max_loss = cli_args_uint(&a, 0, UINT64_MAX);
        } else if (cli_args_is(&a, NULL, "--max-errors")) {
            o->max_errors = cli_args_uint(&a, 0, UINT64_MAX);
        } else if (cli_args_is(&a, NULL, "--max-noise")) {
            o->max_noise = cli_args_double(&a, 0.0, 32000.0, false);
        } else if (cli_args_is(&a, NULL, "--json")) {
            o->json = cli_args_flag(&a);
        } else if (!cli_port_option(po, &a)) {
            cli_args_unknown(&a);
        }
    }
    if (a.failed || !cli_port_check(po, &a))
        return CLI_USAGE;
    return CLI_OK;
}

/* Add a batch's rows: status bits, and the noise's differences (none across
 * a gap or next to an overloaded sample). */
static void add_rows(check_data *d, const lep_session_batch *b)
{
    size_t i;
    int k;
    for (i = 0; i < b->n; i++) {
        const int16_t *raw = &b->raw[i * LEP_AXES];
        bool usable = (b->flags[i] & (LEP_SF_GAP | LEP_SF_OVERLOAD)) == 0u;
        d->status_or |= b->status[i];
        d->samples++;
        if (usable && d->have_prev) {
            for (k = 0; k < LEP_AXES; k++) {
                double diff = (double)raw[k] - (double)d->prev[k];
                d->sq[k] += diff * diff;
            }
            d->pairs++;
        }
        d->have_prev = (b->flags[i] & LEP_SF_OVERLOAD) == 0u;
        memcpy(d->prev, raw, sizeof d->prev);
    }
}

/* Connect, a handshake sample, stream for the duration. An exit code. */
static int measure(const check_opts *o, cli_port_opts *po, check_data *d)
{
    static double t_mono[BATCH], zeroed[BATCH * LEP_AXES], si[BATCH * LEP_AXES];
    static int16_t raw[BATCH * LEP_AXES];
    static uint8_t status[BATCH], flags[BATCH];
    lep_session_options so;
    lep_session_batch b;
    lep_session *s;
    int code, rc, k;

    lep_session_options_init(&so);
    so.duration_s = o->duration_s;
    code = cli_sensors_open(po, &so, "check");
    if (code != CLI_OK)
        return code;
    s = po->sensor[0].session;
    memset(&b, 0, sizeof b);
    b.cap = BATCH;
    b.t_mono = t_mono;
    b.raw = raw;
    b.zeroed = zeroed;
    b.si = si;
    b.status = status;
    b.flags = flags;
    rc = lep_session_read_one_batch(s, &b); /* the status bits before streaming */
    if (rc != LEP_OK)
        return cli_session_fail(s, "check", po->sensor[0].name, "sample", rc);
    d->status_or |= status[0];
    rc = lep_session_start(s);
    if (rc != LEP_OK)
        return cli_session_fail(s, "check", po->sensor[0].name, "start", rc);
    for (;;) {
        lep_session_event ev;
        b.n = 0;
        rc = lep_session_read_batch(s, &b, 500);
        add_rows(d, &b);
        while (lep_session_pop_event(s, &ev)) {
        }
        if (rc == LEP_E_END)
            break;
        if (cli_stop_requested() || (rc != LEP_OK && rc != LEP_E_TIMEOUT)) {
            if (rc == LEP_OK || rc == LEP_E_TIMEOUT)
                rc = LEP_E_STATE;
            (void)lep_session_stop(s);
            return cli_stop_requested()
                       ? CLI_OK
                       : cli_session_fail(s, "check", po->sensor[0].name, "stream", rc);
        }
    }
    lep_session_get_health(s, &d->h);
    lep_session_get_metadata(s, &d->meta);
    rc = lep_session_stop(s);
    if (rc != LEP_OK)
        return cli_session_fail(s, "check", po->sensor[0].name, "stop", rc);
    for (k = 0; k < LEP_AXES; k++)
        d->noise[k] = d->pairs > 0 ? sqrt(d->sq[k] / (double)d->pairs / 2.0) : 0.0;
    return CLI_OK;
}

static void judge(const check_opts *o, const check_data *d, criterion c[C_COUNT])
{
    static const char *const axis[LEP_AXES] = { "fx", "fy", "fz", "mx", "my", "mz" };
    uint8_t bad = (uint8_t)(d->status_or & (LEP_STATUS_CALIBRATION | LEP_STATUS_SENSOR_FAULT));
    double pct = d->h.nominal_hz > 0 ? 100.0 * d->h.measured_hz / d->h.nominal_hz : 0.0;
    double worst = 0.0;
    int k, wk = 0;
    static const char *const names[C_COUNT] = { "status", "errors",   "loss",
                                                "rate",   "overload", "noise" };
    static const int codes[C_COUNT] = { CLI_CHECK_STATUS, CLI_CHECK_ERRORS,   CLI_CHECK_LOSS,
                                        CLI_CHECK_RATE,   CLI_CHECK_OVERLOAD, CLI_CHECK_NOISE };
    for (k = 0; k < C_COUNT; k++) {
        c[k].name = names[k];
        c[k].exit_code = codes[k];
    }
    c[C_STATUS].pass = bad == 0u;
    snprintf(c[C_STATUS].value, sizeof c[C_STATUS].value, "%s%s%s", bad == 0u ? "ok" : "",
             (bad & LEP_STATUS_CALIBRATION) ? "ROM calibration data error " : "",
             (bad & LEP_STATUS_SENSOR_FAULT) ? "sensor error" : "");
    snprintf(c[C_STATUS].limit, sizeof c[C_STATUS].limit, "bits 1 and 2 clear");
    c[C_ERRORS].pass = d->h.errors <= o->max_errors;
    snprintf(c[C_ERRORS].value, sizeof c[C_ERRORS].value, "%llu", (unsigned long long)d->h.errors);
    snprintf(c[C_ERRORS].limit, sizeof c[C_ERRORS].limit, "<= %llu",
             (unsigned long long)o->max_errors);
    c[C_LOSS].pass = d->h.lost <= o->max_loss;
    snprintf(c[C_LOSS].value, sizeof c[C_LOSS].value, "%llu in %llu gaps",
             (unsigned long long)d->h.lost, (unsigned long long)d->h.gaps);
    snprintf(c[C_LOSS].limit, sizeof c[C_LOSS].limit, "<= %llu", (unsigned long long)o->max_loss);
    c[C_RATE].pass = pct >= o->min_rate_pct;
    snprintf(c[C_RATE].value, sizeof c[C_RATE].value, "%.1f Hz = %.2f %% of %.0f Hz",
             d->h.measured_hz, pct, d->h.nominal_hz);
    snprintf(c[C_RATE].limit, sizeof c[C_RATE].limit, ">= %g %%", o->min_rate_pct);
    c[C_OVERLOAD].pass = d->h.overloads == 0 && (d->status_or & LEP_STATUS_OVERLOAD) == 0u;
    snprintf(c[C_OVERLOAD].value, sizeof c[C_OVERLOAD].value, "%llu episodes",
             (unsigned long long)d->h.overloads);
    snprintf(c[C_OVERLOAD].limit, sizeof c[C_OVERLOAD].limit, "none");
    for (k = 0; k < LEP_AXES; k++) {
        if (d->noise[k] > worst) {
            worst = d->noise[k];
            wk = k;
        }
    }
    c[C_NOISE].pass = d->pairs > 0 && worst <= o->max_noise;
    snprintf(c[C_NOISE].value, sizeof c[C_NOISE].value, "%.2f counts RMS at most (%s)", worst,
             axis[wk]);
    snprintf(c[C_NOISE].limit, sizeof c[C_NOISE].limit, "<= %g", o->max_noise);
}

static void print_text(const check_opts *o, const check_data *d, const criterion c[C_COUNT],
                       const char *port, int code)
{
    const lep_session_meta *m = &d->meta;
    char text[4 * 64 + 1];
    int k;
    printf("%-14s%s%s\n", "port:", port, m->sim ? " (virtual sensor)" : "");
    cli_safe_text(m->info.model, text, sizeof text);
    printf("%-14s%s\n", "model:", text);
    cli_safe_text(m->info.serial, text, sizeof text);
    printf("%-14s%s\n", "serial:", text);
    cli_safe_text(m->info.firmware, text, sizeof text);
    printf("%-14s%s\n", "firmware:", text);
    printf("%-14sFx %g N, Fy %g N, Fz %g N, Mx %g N m, My %g N m, Mz %g N m\n",
           "rated:", (double)m->rated.axis[0], (double)m->rated.axis[1], (double)m->rated.axis[2],
           (double)m->rated.axis[3], (double)m->rated.axis[4], (double)m->rated.axis[5]);
    if (m->sensor_filter >= 0)
        printf("%-14s%d (%s)\n", "filter:", m->sensor_filter, m->sensor_filter_label);
    else
        printf("%-14s%s\n", "filter:", "not supported by this sensor");
    printf("%-14s%llu samples in %.3f s (--duration %g)\n",
           "streamed:", (unsigned long long)d->samples, d->h.elapsed_s, o->duration_s);
    printf("%-14s", "noise:");
    for (k = 0; k < LEP_AXES; k++)
        printf("%s%.2f", k > 0 ? " " : "", d->noise[k]);
    printf(" counts RMS (fx fy fz mx my mz)\n\n");
    for (k = 0; k < C_COUNT; k++)
        printf("%-4s %-9s %-44s (%s)\n", c[k].pass ? "PASS" : "FAIL", c[k].name, c[k].value,
               c[k].limit);
    if (code == CLI_OK)
        printf("\nresult:       PASS\n");
    else
        printf("\nresult:       FAIL (%s, exit code %d)\n", c[code - CLI_CHECK_STATUS].name, code);
}

/* JSON string of sensor text: printable ASCII kept, the rest \u00XX. */
static void jstr(const char *s)
{
    putchar('"');
    for (; *s != '\0'; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\')
            printf("\\%c", ch);
        else if (ch < 0x20 || ch > 0x7E)
            printf("\\u%04x", ch);
        else
            putchar(ch);
    }
    putchar('"');
}

static void print_json(const check_data *d, const criterion c[C_COUNT], const char *port, int code)
{
    const lep_session_meta *m = &d->meta;
    int k;
    printf("{\"port\":");
    jstr(port);
    printf(",\"sim\":%s,\"model\":", m->sim ? "true" : "false");
    jstr(m->info.model);
    printf(",\"serial\":");
    jstr(m->info.serial);
    printf(",\"firmware\":");
    jstr(m->info.firmware);
    printf(",\"rated\":[");
    for (k = 0; k < LEP_AXES; k++)
        printf("%s%.9g", k > 0 ? "," : "", (double)m->rated.axis[k]);
    printf("],\"filter\":%d,\"status_bits\":%u,\"samples\":%llu,\"elapsed_s\":%.6f,"
           "\"measured_hz\":%.3f,\"nominal_hz\":%.3f,\"lost\":%llu,\"gaps\":%llu,\"errors\":%llu,"
           "\"overloads\":%llu,\"noise_counts\":[",
           m->sensor_filter, (unsigned)d->status_or, (unsigned long long)d->samples, d->h.elapsed_s,
           d->h.measured_hz, d->h.nominal_hz, (unsigned long long)d->h.lost,
           (unsigned long long)d->h.gaps, (unsigned long long)d->h.errors,
           (unsigned long long)d->h.overloads);
    for (k = 0; k < LEP_AXES; k++)
        printf("%s%.3f", k > 0 ? "," : "", d->noise[k]);
    printf("],\"criteria\":[");
    for (k = 0; k < C_COUNT; k++) {
        printf("%s{\"name\":\"%s\",\"pass\":%s,\"exit_code\":%d,\"value\":", k > 0 ? "," : "",
               c[k].name, c[k].pass ? "true" : "false", c[k].exit_code);
        jstr(c[k].value);
        printf(",\"limit\":");
        jstr(c[k].limit);
        printf("}");
    }
    printf("],\"pass\":%s,\"exit_code\":%d,\"failed\":", code == CLI_OK ? "true" : "false", code);
    if (code == CLI_OK)
        printf("null}\n");
    else
        printf("\"%s\"}\n", c[code - CLI_CHECK_STATUS].name);
}

int cli_cmd_check(int argc, char **argv)
{
    static check_data d;
    check_opts o;
    cli_port_opts po;
    criterion c[C_COUNT];
    int code, k;

    memset(&d, 0, sizeof d);
    memset(c, 0, sizeof c);
    code = parse(argc, argv, &o, &po);
    if (code != CLI_OK)
        return code < 0 ? CLI_OK : code;
    cli_signals_install();
    code = measure(&o, &po, &d);
    if (code == CLI_OK && cli_stop_requested()) {
        /* an interrupted check has no verdict: never the exit code of a pass */
        fprintf(stderr,
                "leptrino: check: %s: interrupted before the end of --duration: no verdict\n",
                po.sensor[0].name);
        code = CLI_FAIL;
    }
    if (code != CLI_OK) {
        cli_sensors_close(&po);
        return code;
    }
    judge(&o, &d, c);
    for (k = 0; k < C_COUNT && code == CLI_OK; k++)
        if (!c[k].pass)
            code = c[k].exit_code;
    if (o.json)
        print_json(&d, c, d.meta.port, code);
    else
        print_text(&o, &d, c, d.meta.port, code);
    if (code != CLI_OK)
        fprintf(stderr, "leptrino: check: %s: FAIL: %s: %s (%s)\n", po.sensor[0].name,
                c[code - CLI_CHECK_STATUS].name, c[code - CLI_CHECK_STATUS].value,
                c[code - CLI_CHECK_STATUS].limit);
    cli_sensors_close(&po);
    return code;
}
