/* `leptrino stream`: continuous output to CSV or JSON lines, until a
 * duration, a count, Ctrl-C or SIGTERM; optional tare and reconnection. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

#define CLI_BATCH 256
#define CLI_WAIT_MS 100         /* longest wait before looking at the stop flag */
#define CLI_NOTE_PERIOD_S 10.0  /* at most one "still waiting" message per period */
#define CLI_BACKOFF_MIN_MS 100
#define CLI_BACKOFF_MAX_MS 1000

typedef struct stream_opts {
    cli_port_opts po;
    double duration;      /* s, 0 = none */
    uint64_t count;       /* samples written, 0 = none */
    uint64_t tare;        /* samples averaged for the offset, 0 = no tare */
    double data_timeout;  /* s without data that counts as a timeout */
    const char *output;   /* NULL or "-" = stdout */
    cli_format format_value;
    bool si;              /* SI units (default) or raw counts */
    bool reconnect;
} stream_opts;

typedef struct stream_state {
    cli_conn c;
    cli_writer w;
    cli_status st;
    FILE *out;
    bool out_tty;
    double t0;
    double last_t;       /* arrival of the last sample (or of streaming start) */
    uint64_t received;   /* samples received (tare included) */
    uint64_t written;
    uint64_t overloads;
    uint64_t errors_before; /* client error counters of earlier connections */
    uint64_t gaps;
    bool gap_pending;
    double gap_from;
    const char *gap_reason;
    double tare_sum[LEP_AXES];
    uint64_t tare_n;
    int write_errno;     /* != 0 once the output failed */
} stream_state;

static void help(void)
{
    fputs("Usage: leptrino stream PORT|--sim [options]\n"
          "\n"
          "Start continuous output and write every sample, until --duration, --count,\n"
          "Ctrl-C or SIGTERM. On Ctrl-C / SIGTERM the sensor's stream is stopped, the\n"
          "output flushed, and the exit code is 0.\n"
          "\n"
          "Output (CSV header exactly t,fx,fy,fz,mx,my,mz,status):\n"
          "  t       s since streaming started (monotonic clock, taken when the read\n"
          "          that delivered the sample returned)\n"
          "  fx..fz  N;  mx..mz  N m  (raw counts with --units raw: +/-10000 = rated)\n"
          "  status  status bits: 1 calibration data error, 2 sensor fault, 4 overload\n"
          "\n"
          "Options:\n"
          "  -d, --duration S        stop after S seconds (the tare period included)\n"
          "  -c, --count N           stop after N samples written\n"
          "  -o, --output FILE       write to FILE instead of stdout ('-' = stdout)\n"
          "  -f, --format csv|jsonl  CSV (default) or one JSON object per line\n"
          "  -u, --units si|raw      N and N m (default), or raw counts\n"
          "      --tare N            average the first N samples and subtract that offset\n"
          "                          from every later sample; the N samples are not written\n"
          "      --reconnect         when the port goes away, keep reopening it (100 ms ..\n"
          "                          1 s apart), resume streaming, and mark the gap:\n"
          "                          CSV '# gap from=T1 to=T2 reason=R', JSON lines\n"
          "                          {\"gap\":{\"from\":T1,\"to\":T2,\"reason\":\"R\"}}\n"
          "      --data-timeout S    no data for S seconds is an error (default 2)\n"
          "  -h, --help              show this help\n",
          stdout);
    cli_port_help(stdout);
    fputs("\n"
          "A live status line (samples, Hz, errors, overloads, elapsed) is drawn on stderr\n"
          "when stderr is a terminal; a one-line summary is printed on stderr at the end.\n"
          "\n",
          stdout);
    cli_print_exit_codes(stdout);
}

static int parse(int argc, char **argv, stream_opts *o)
{
    cli_args a;
    const char *v;
    cli_args_init(&a, argc, argv, "stream");
    memset(o, 0, sizeof *o);
    cli_port_opts_init(&o->po);
    o->data_timeout = 2.0;
    o->format_value = CLI_FORMAT_CSV;
    o->si = true;
    while (cli_args_next(&a)) {
        if (cli_args_is(&a, "-h", "--help")) {
            cli_args_flag(&a);
            if (a.failed)
                break;
            help();
            return -1;
        } else if (cli_args_is(&a, "-d", "--duration")) {
            o->duration = cli_args_double(&a, 0.0, 1e9, true);
        } else if (cli_args_is(&a, "-c", "--count")) {
            o->count = cli_args_uint(&a, 1, UINT64_MAX);
        } else if (cli_args_is(&a, "-o", "--output")) {
            o->output = cli_args_value(&a);
        } else if (cli_args_is(&a, "-f", "--format")) {
            v = cli_args_value(&a);
            if (v != NULL && !cli_parse_format(v, &o->format_value))
                cli_args_error(&a, "unknown format '%s' (csv or jsonl)", v);
        } else if (cli_args_is(&a, "-u", "--units")) {
            v = cli_args_value(&a);
            if (v != NULL && !cli_parse_units(v, &o->si))
                cli_args_error(&a, "unknown units '%s' (si or raw)", v);
        } else if (cli_args_is(&a, NULL, "--tare")) {
            o->tare = cli_args_uint(&a, 1, 1000000);
        } else if (cli_args_is(&a, NULL, "--reconnect")) {
            cli_args_flag(&a);
            o->reconnect = true;
        } else if (cli_args_is(&a, NULL, "--data-timeout")) {
            o->data_timeout = cli_args_double(&a, 0.0, 3600.0, true);
        } else if (cli_port_option(&o->po, &a)) {
        } else if (a.positional && o->po.port == NULL) {
            o->po.port = a.cur;
        } else {
            cli_args_unknown(&a);
        }
    }
    if (a.failed || !cli_port_check(&o->po, &a))
        return CLI_USAGE;
    return CLI_OK;
}

static double now_s(const stream_state *s)
{
    return lep_monotonic_seconds() - s->t0;
}

static uint64_t client_errors(const cli_conn *c)
{
    lep_client_stats cs;
    if (c->serial == NULL)
        return 0;
    lep_client_get_stats(&c->client, &cs);
    return (uint64_t)cs.bcc_errors + cs.frame_errors + cs.invalid;
}

static uint64_t total_errors(const stream_state *s)
{
    return s->errors_before + client_errors(&s->c);
}

static void show_status(stream_state *s, double t, const char *note)
{
    char text[200];
    snprintf(text, sizeof text, "%llu samples  %7.1f Hz  %llu errors  %llu overloads  %.1f s%s",
             (unsigned long long)s->written, t > 0.0 ? (double)s->received / t : 0.0,
             (unsigned long long)total_errors(s), (unsigned long long)s->overloads, t, note);
    cli_status_update(&s->st, t, text);
}

/* Take one sample: tare, gap mark, output. False when the output failed. */
static bool take(stream_state *s, const stream_opts *o, double t, const lep_sample *smp)
{
    int i;
    s->received++;
    if ((smp->status & LEP_STATUS_OVERLOAD) != 0)
        s->overloads++;
    if (o->tare > 0 && s->tare_n < o->tare) {
        for (i = 0; i < LEP_AXES; ++i)
            s->tare_sum[i] += smp->raw[i];
        if (++s->tare_n == o->tare) {
            for (i = 0; i < LEP_AXES; ++i)
                s->w.offset[i] = s->tare_sum[i] / (double)s->tare_n;
            s->w.tared = true;
        }
        return true;
    }
    if (s->gap_pending) {
        cli_write_gap(&s->w, s->gap_from, t, s->gap_reason);
        s->gap_pending = false;
    }
    cli_write_sample(&s->w, t, smp);
    s->written++;
    if (ferror(s->out)) {
        s->write_errno = errno != 0 ? errno : EIO;
        return false;
    }
    return true;
}

static bool time_is_up(const stream_state *s, const stream_opts *o)
{
    return o->duration > 0.0 && now_s(s) >= o->duration;
}

/* Open again after a disconnect (or a data timeout) and restart streaming.
 * LEP_OK when resumed; 1 when stopped by a signal or the duration. */
static int reconnect(stream_state *s, const stream_opts *o, const char *reason)
{
    int delay = CLI_BACKOFF_MIN_MS;
    unsigned attempts = 0;
    double lost_at = now_s(s);
    double next_note = lost_at + CLI_NOTE_PERIOD_S;

    s->errors_before += client_errors(&s->c);
    cli_conn_drop(&s->c);
    if (!s->gap_pending) {
        s->gap_pending = true;
        s->gap_from = s->last_t;
        s->gap_reason = reason;
        s->gaps++;
    }
    cli_status_clear(&s->st);
    fprintf(stderr, "leptrino: stream: %s: %s at t=%.3f s; reopening it (Ctrl-C to stop)\n",
            s->c.path, reason, lost_at);
    for (;;) {
        int rc;
        double t;
        cli_sleep_ms(delay);
        if (cli_stop_requested() || time_is_up(s, o))
            return 1;
        attempts++;
        rc = cli_conn_reopen(&s->c);
        if (rc == LEP_OK)
            rc = lep_client_rated(&s->c.client, &s->w.rated);
        if (rc == LEP_OK)
            rc = lep_client_start(&s->c.client);
        t = now_s(s);
        if (rc == LEP_OK) {
            cli_status_clear(&s->st);
            fprintf(stderr, "leptrino: stream: %s: back after %.1f s (%u attempts); streaming "
                            "resumed\n",
                    s->c.path, t - lost_at, attempts);
            s->last_t = t;
            return LEP_OK;
        }
        cli_conn_drop(&s->c);
        if (t >= next_note) {
            cli_status_clear(&s->st);
            fprintf(stderr, "leptrino: stream: %s: still waiting after %.0f s (%u attempts; "
                            "last: %s)\n",
                    s->c.path, t - lost_at, attempts, lep_strerror(rc));
            next_note = t + CLI_NOTE_PERIOD_S;
        }
        show_status(s, t, "  reconnecting");
        delay = delay * 2 > CLI_BACKOFF_MAX_MS ? CLI_BACKOFF_MAX_MS : delay * 2;
    }
}

/* The stream loop. Returns an exit code; *stopped says a signal ended it. */
static int loop(stream_state *s, const stream_opts *o, bool *stopped)
{
    static lep_sample batch[CLI_BATCH];

    for (;;) {
        size_t n = 0, i;
        int rc, wait_ms = CLI_WAIT_MS;
        double t;

        if (cli_stop_requested()) {
            *stopped = true;
            return CLI_OK;
        }
        t = now_s(s);
        if (o->duration > 0.0) {
            double left = o->duration - t;
            if (left <= 0.0)
                return CLI_OK;
            if (left * 1000.0 < (double)wait_ms)
                wait_ms = (int)(left * 1000.0) + 1;
        }
        rc = lep_client_next_samples(&s->c.client, batch, CLI_BATCH, &n, wait_ms);
        t = now_s(s);
        for (i = 0; i < n; ++i) {
            if (o->duration > 0.0 && t >= o->duration)
                return CLI_OK; /* arrived after the end: not part of the record */
            if (!take(s, o, t, &batch[i]))
                return CLI_FAIL;
            if (o->count > 0 && s->written >= o->count)
                return CLI_OK;
        }
        if (n > 0) {
            s->last_t = t;
            if (s->out_tty)
                fflush(s->out);
        }
        show_status(s, t, "");

        if (rc == LEP_OK || (rc == LEP_E_TIMEOUT && n > 0))
            continue;
        if (rc == LEP_E_TIMEOUT) {
            if (t - s->last_t < o->data_timeout)
                continue;
            if (o->reconnect) {
                if (reconnect(s, o, "no data") != LEP_OK) {
                    *stopped = cli_stop_requested();
                    return CLI_OK;
                }
                continue;
            }
            cli_status_clear(&s->st);
            fprintf(stderr, "leptrino: stream: %s: timeout: no data for %.1f s\n", s->c.path,
                    t - s->last_t);
            return CLI_TIMEOUT;
        }
        if (cli_stop_requested()) { /* a read interrupted by the signal */
            *stopped = true;
            return CLI_OK;
        }
        if (rc == LEP_E_DISCONNECTED && o->reconnect) {
            if (reconnect(s, o, "disconnected") != LEP_OK) {
                *stopped = cli_stop_requested();
                return CLI_OK;
            }
            continue;
        }
        cli_status_clear(&s->st);
        if (rc == LEP_E_DISCONNECTED) {
            fprintf(stderr, "leptrino: stream: %s: disconnected (the port went away at t=%.3f s; "
                            "--reconnect keeps trying)\n",
                    s->c.path, t);
            return CLI_DISCONNECTED;
        }
        return cli_conn_fail(&s->c, "stream", rc);
    }
}

/* Stop the sensor's stream if the port is still there (errors are reported). */
static void stop_sensor(stream_state *s)
{
    int rc;
    if (s->c.serial == NULL || !lep_client_streaming(&s->c.client))
        return;
    rc = lep_client_stop(&s->c.client);
    if (rc != LEP_OK && rc != LEP_E_DISCONNECTED)
        rc = lep_client_stop(&s->c.client); /* one more try, e.g. after a lost answer */
    if (rc != LEP_OK && rc != LEP_E_DISCONNECTED) {
        cli_status_clear(&s->st);
        fprintf(stderr, "leptrino: stream: %s: could not stop the sensor's stream: %s\n",
                s->c.path, lep_strerror(rc));
    }
}

static FILE *open_output(const stream_opts *o, bool *is_tty)
{
    FILE *f;
    if (o->output == NULL || strcmp(o->output, "-") == 0) {
        f = stdout;
    } else {
        f = fopen(o->output, "w");
        if (f == NULL) {
            fprintf(stderr, "leptrino: stream: cannot open output '%s': %s\n", o->output,
                    strerror(errno));
            return NULL;
        }
    }
    *is_tty = isatty(fileno(f)) == 1;
    /* Block buffering for files and pipes: no per-sample system call. */
    setvbuf(f, NULL, *is_tty ? _IOLBF : _IOFBF, (size_t)1 << 16);
    return f;
}

int cli_cmd_stream(int argc, char **argv)
{
    static stream_state s; /* large (client context): keep it off the stack */
    stream_opts o;
    bool stopped = false;
    int code, rc;
    double elapsed;

    code = parse(argc, argv, &o);
    if (code != CLI_OK)
        return code < 0 ? CLI_OK : code;

    memset(&s, 0, sizeof s);
    cli_signals_install();
    /* The sensor first: a run that cannot reach it leaves FILE alone. */
    code = cli_conn_open(&s.c, &o.po, "stream");
    if (code != CLI_OK)
        return code;
    rc = lep_client_rated(&s.c.client, &s.w.rated);
    if (rc != LEP_OK) {
        code = cli_conn_fail(&s.c, "rated values", rc);
        cli_conn_close(&s.c);
        return code;
    }
    s.out = open_output(&o, &s.out_tty);
    if (s.out == NULL) {
        cli_conn_close(&s.c);
        return CLI_FAIL;
    }
    cli_status_init(&s.st, s.out_tty ? fileno(s.out) : -1);
    s.w.f = s.out;
    s.w.format = o.format_value;
    s.w.si = o.si;
    rc = lep_client_start(&s.c.client);
    if (rc != LEP_OK) {
        code = cli_conn_fail(&s.c, "start", rc);
        cli_conn_close(&s.c);
        if (s.out != stdout)
            fclose(s.out);
        return code;
    }
    s.t0 = lep_monotonic_seconds();
    cli_write_header(&s.w);

    code = loop(&s, &o, &stopped);
    elapsed = now_s(&s);
    stop_sensor(&s);
    if (s.gap_pending)
        cli_write_gap(&s.w, s.gap_from, -1.0, s.gap_reason);

    if (fflush(s.out) != 0 && s.write_errno == 0)
        s.write_errno = errno != 0 ? errno : EIO;
    if (s.out != stdout && fclose(s.out) != 0 && s.write_errno == 0)
        s.write_errno = errno != 0 ? errno : EIO;
    cli_status_clear(&s.st);
    if (s.write_errno == EPIPE) {
        code = CLI_OK; /* the reader went away (e.g. `| head`): a normal end */
    } else if (s.write_errno != 0) {
        fprintf(stderr, "leptrino: stream: cannot write the output: %s\n", strerror(s.write_errno));
        code = CLI_FAIL;
    }
    fprintf(stderr,
            "leptrino: stream: %llu samples in %.3f s (%.1f Hz), %llu errors, %llu overloads, "
            "%llu gaps%s%s\n",
            (unsigned long long)s.written, elapsed,
            elapsed > 0.0 ? (double)s.received / elapsed : 0.0,
            (unsigned long long)total_errors(&s), (unsigned long long)s.overloads,
            (unsigned long long)s.gaps,
            o.tare == 0 ? "" : s.w.tared ? ", tared" : ", tare incomplete",
            stopped ? "; stopped by signal" : "");
    cli_conn_close(&s.c);
    return code;
}
