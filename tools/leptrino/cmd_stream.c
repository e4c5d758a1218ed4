/* `leptrino stream`: one or more sensors' continuous output to CSV or JSON
 * lines until a duration, a count, Ctrl-C or SIGTERM. Everything about the
 * data (tare, filter, frame, gaps, health, reconnection, how a row is
 * written) belongs to the session and its writer (leptrino/output.h); this
 * file parses options, wires sessions to writers, turns keys and signals
 * into tare requests and reports. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

#define BATCH 512
#define WAIT_MS 100 /* longest wait before looking at flags and keys */
#define EVENTS 64
#define PI 3.14159265358979323846

typedef struct stream_opts {
    cli_port_opts po;
    lep_session_options so; /* duration, count, tare, filter, frame, timeouts, latency */
    unsigned retare;        /* samples a tare during the run averages */
    bool rotate_given, matrix_given;
    double rpy_deg[3];
    const char *output;     /* NULL or "-" = stdout */
    const char *split;      /* pattern: one file per sensor */
    lep_output_options out; /* format, columns, time, overwrite */
    bool columns_given, units_given;
    bool stop_on_limit;
} stream_opts;

typedef struct sensor_run {
    cli_sensor *sensor;
    lep_session *s;
    lep_output *w; /* its writer (shared when all go to one file) */
    int index;     /* its sensor index in w */
    bool own_writer;
    bool done;            /* reached duration/count */
    int failed;           /* LEP_E_* that ended it, 0 while fine */
    bool limit_stop;      /* a limit was exceeded with --stop-on-limit */
    unsigned tare_events; /* tares done, offsets set and un-tares during the run */
} sensor_run;

static void help(void)
{
    fputs("Usage: leptrino stream PORT|--sim [PORT|--sim ...] [options]\n"
          "\n"
          "Start continuous output of one or more sensors and write every sample until\n"
          "--duration, --count, Ctrl-C or SIGTERM. On Ctrl-C / SIGTERM the sensors'\n"
          "streams are stopped, the output flushed, and the exit code is 0.\n"
          "\n"
          "Output:\n"
          "  -o, --output FILE        write to FILE ('-' = stdout, the default); an\n"
          "                           existing FILE is kept unless --overwrite\n"
          "      --split PATTERN      one file per sensor: {sensor} in PATTERN becomes\n"
          "                           the sensor's name (sim1, sim2, or the port with '/'\n"
          "                           as '_'), {n} its number (1, 2, ...)\n"
          "      --overwrite          replace existing output files\n"
          "  -f, --format csv|jsonl   CSV (default) or one JSON object per line\n"
          "      --columns LIST       comma-separated, in this order in the output:\n"
          "                           raw     counts as received (fx_counts..mz_counts)\n"
          "                           zeroed  counts minus the tare (fx_zeroed_counts..)\n"
          "                           si      N and N m after tare, low-pass, rotation,\n"
          "                                   shift (fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm)\n"
          "                           status  the sensor's status bits (1 calibration\n"
          "                                   data error, 2 sensor fault, 4 overload)\n"
          "                           flags   the session's flags (1 gap before, 2\n"
          "                                   overload, 4 taring, 8 low-pass settling,\n"
          "                                   16 beyond a --limit)\n"
          "                           seq     the virtual sensor's sequence number\n"
          "                           sensor  the sensor's name (added by itself when\n"
          "                                   several sensors share one file)\n"
          "                           (default si,status)\n"
          "  -u, --units si|raw       shorthand: --columns si,status or raw,status\n"
          "      --time rel|mono|utc  the first column: t_s, seconds since the start\n"
          "                           (default; one time base for every sensor),\n"
          "                           t_mono_s (monotonic clock) or t_utc_s (Unix time)\n"
          "A metadata header comes first (CSV: '# leptrino-metadata: {...}' lines; JSON\n"
          "lines: a first {\"metadata\": ...} object): sensor, rated values, filters, tare,\n"
          "frame, start time. Gaps are marked where they happen: CSV '# gap ...' lines,\n"
          "JSON lines {\"event\":\"gap\", ...} objects.\n"
          "\n"
          "Run:\n"
          "  -d, --duration S         stop after S seconds of data\n"
          "  -c, --count N            stop after N samples of each sensor\n"
          "      --tare N             zero on the mean of the first N samples (they are\n"
          "                           not written)\n"
          "      --retare N           samples a tare during the run averages (default:\n"
          "                           --tare N, else 100)\n"
          "      --lowpass HZ         host low-pass filter cut-off on the SI values\n"
          "      --decimate N         write every Nth sample (after the low-pass)\n"
          "      --rotate R,P,Y       output frame rotated by roll, pitch, yaw (degrees)\n"
          "      --matrix M11,...,M33 output frame rotated by this 3x3 matrix (row-major)\n"
          "      --shift X,Y,Z        moments about this point (m, in the output frame)\n"
          "      --latency MS         delivery may wait up to MS ms to save wake-ups\n"
          "                           (default 0; 50 or more suits recording)\n"
          "      --reconnect          when a port goes away, reopen it (100 ms .. 1 s\n"
          "                           apart) and resume; the gap is marked\n"
          "      --data-timeout S     no data for S seconds is an error (default 2)\n"
          "\n",
          stdout);
    fputs("Payload and limits:\n", stdout);
    cli_load_help(stdout, true);
    fputs("      --stop-on-limit      stop at the first sample beyond a limit (it is\n"
          "                           written), exit code 9\n"
          "  -h, --help               show this help\n"
          "\n",
          stdout);
    fputs("Tare during the run: press t (tare) or u (untare) when standard input is a\n"
          "terminal; send SIGUSR1 (tare) or SIGUSR2 (untare) otherwise. A tare applies\n"
          "to every sensor and never stalls the stream.\n"
          "\n",
          stdout);
    cli_port_help(stdout, true);
    fputs("\n"
          "A live status line is drawn on stderr when stderr is a terminal that the data\n"
          "do not go to; a summary per sensor is printed on stderr at the end, with the\n"
          "measured rate against the nominal one.\n"
          "\n",
          stdout);
    cli_print_exit_codes(stdout);
}

static bool parse_columns(const char *v, unsigned *out)
{
    static const struct {
        const char *name;
        unsigned bit;
    } NAMES[] = {
        { "raw", LEP_COL_RAW },       { "zeroed", LEP_COL_ZEROED }, { "si", LEP_COL_SI },
        { "status", LEP_COL_STATUS }, { "flags", LEP_COL_FLAGS },   { "seq", LEP_COL_SEQ },
        { "sensor", LEP_COL_SENSOR },
    };
    const char *p = v;
    *out = 0;
    while (*p != '\0') {
        size_t len = strcspn(p, ","), i;
        bool found = false;
        for (i = 0; i < sizeof NAMES / sizeof NAMES[0]; ++i) {
            if (strlen(NAMES[i].name) == len && strncmp(p, NAMES[i].name, len) == 0) {
                if ((*out & NAMES[i].bit) != 0)
                    return false; /* twice */
                *out |= NAMES[i].bit;
                found = true;
            }
        }
        if (!found)
            return false;
        p += len;
        if (*p == ',' && *++p == '\0')
            return false;
    }
    return *out != 0;
}

static int parse(int argc, char **argv, stream_opts *o)
{
    cli_args a;
    const char *v;
    double shift[3];
    cli_args_init(&a, argc, argv, "stream");
    memset(o, 0, sizeof *o);
    cli_port_opts_init(&o->po, true);
    lep_session_options_init(&o->so);
    lep_output_options_init(&o->out);
    while (cli_args_next(&a)) {
        if (cli_args_help(&a)) {
            help();
            return -1;
        } else if (cli_args_is(&a, "-d", "--duration")) {
            o->so.duration_s = cli_args_double(&a, 0.0, 1e9, true);
        } else if (cli_args_is(&a, "-c", "--count")) {
            o->so.count = cli_args_uint(&a, 1, UINT64_MAX);
        } else if (cli_args_is(&a, "-o", "--output")) {
            o->output = cli_args_value(&a);
        } else if (cli_args_is(&a, NULL, "--split")) {
            o->split = cli_args_value(&a);
            if (o->split != NULL && strstr(o->split, "{sensor}") == NULL &&
                strstr(o->split, "{n}") == NULL)
                cli_args_error(&a, "option --split: '%s' has neither {sensor} nor {n}", o->split);
        } else if (cli_args_is(&a, NULL, "--overwrite")) {
            cli_args_flag(&a);
            o->out.overwrite = true;
        } else if (cli_args_is(&a, "-f", "--format")) {
            v = cli_args_value(&a);
            if (v != NULL && strcmp(v, "csv") == 0)
                o->out.format = LEP_OUTPUT_CSV;
            else if (v != NULL && strcmp(v, "jsonl") == 0)
                o->out.format = LEP_OUTPUT_JSONL;
            else if (v != NULL)
                cli_args_error(&a, "unknown format '%s' (csv or jsonl)", v);
        } else if (cli_args_is(&a, NULL, "--columns")) {
            v = cli_args_value(&a);
            o->columns_given = true;
            if (v != NULL && !parse_columns(v, &o->out.columns))
                cli_args_error(&a,
                               "option --columns: '%s' is not a list of raw, zeroed, si, "
                               "status, flags, seq, sensor (each once)",
                               v);
        } else if (cli_args_is(&a, "-u", "--units")) {
            v = cli_args_value(&a);
            o->units_given = true;
            if (v != NULL && strcmp(v, "si") == 0)
                o->out.columns = LEP_COL_SI | LEP_COL_STATUS;
            else if (v != NULL && strcmp(v, "raw") == 0)
                o->out.columns = LEP_COL_RAW | LEP_COL_STATUS;
            else if (v != NULL)
                cli_args_error(&a, "unknown units '%s' (si or raw)", v);
        } else if (cli_args_is(&a, NULL, "--time")) {
            v = cli_args_value(&a);
            if (v != NULL && strcmp(v, "rel") == 0)
                o->out.time = LEP_TIME_REL;
            else if (v != NULL && strcmp(v, "mono") == 0)
                o->out.time = LEP_TIME_MONO;
            else if (v != NULL && strcmp(v, "utc") == 0)
                o->out.time = LEP_TIME_UTC;
            else if (v != NULL)
                cli_args_error(&a, "unknown time '%s' (rel, mono or utc)", v);
        } else if (cli_args_is(&a, NULL, "--tare")) {
            o->so.tare_samples = (unsigned)cli_args_uint(&a, 1, 1000000);
        } else if (cli_args_is(&a, NULL, "--retare")) {
            o->retare = (unsigned)cli_args_uint(&a, 1, 1000000);
        } else if (cli_args_is(&a, NULL, "--lowpass")) {
            o->so.lowpass_hz = cli_args_double(&a, 0.0, 1e5, true);
        } else if (cli_args_is(&a, NULL, "--decimate")) {
            o->so.decimate = (unsigned)cli_args_uint(&a, 1, 100000);
        } else if (cli_args_is(&a, NULL, "--rotate")) {
            o->rotate_given = cli_args_doubles(&a, o->rpy_deg, 3);
        } else if (cli_args_is(&a, NULL, "--matrix")) {
            o->matrix_given = cli_args_doubles(&a, o->so.rotation, 9);
        } else if (cli_args_is(&a, NULL, "--shift")) {
            if (cli_args_doubles(&a, shift, 3))
                memcpy(o->so.shift_m, shift, sizeof shift);
        } else if (cli_args_is(&a, NULL, "--latency")) {
            o->so.latency_ms = (int)cli_args_uint(&a, 0, 10000);
        } else if (cli_args_is(&a, NULL, "--reconnect")) {
            cli_args_flag(&a);
            o->so.reconnect = true;
        } else if (cli_args_is(&a, NULL, "--data-timeout")) {
            o->so.data_timeout_ms = (int)(cli_args_double(&a, 0.0, 3600.0, true) * 1000.0);
            if (o->so.data_timeout_ms < 1 && !a.failed)
                o->so.data_timeout_ms = 1;
        } else if (cli_load_option(&a, &o->so, true)) {
            /* --payload, --gravity, --limit */
        } else if (cli_args_is(&a, NULL, "--stop-on-limit")) {
            cli_args_flag(&a);
            o->stop_on_limit = true;
        } else if (!cli_port_option(&o->po, &a)) {
            cli_args_unknown(&a);
        }
    }
    if (a.failed || !cli_port_check(&o->po, &a))
        return CLI_USAGE;
    if (o->stop_on_limit) {
        int k;
        bool any = false;
        for (k = 0; k < LEP_AXES; k++)
            any = any || o->so.limit[k] > 0.0;
        if (!any) {
            cli_args_error(&a, "--stop-on-limit needs --limit");
            return CLI_USAGE;
        }
    }
    if (o->columns_given && o->units_given) {
        cli_args_error(&a, "give --columns or --units, not both");
        return CLI_USAGE;
    }
    if (o->rotate_given && o->matrix_given) {
        cli_args_error(&a, "give --rotate or --matrix, not both");
        return CLI_USAGE;
    }
    if (o->split != NULL && o->output != NULL) {
        cli_args_error(&a, "give --output or --split, not both");
        return CLI_USAGE;
    }
    if (o->rotate_given)
        lep_rotation_from_rpy(o->rpy_deg[0] * PI / 180.0, o->rpy_deg[1] * PI / 180.0,
                              o->rpy_deg[2] * PI / 180.0, o->so.rotation);
    if (o->retare == 0)
        o->retare = o->so.tare_samples > 0 ? o->so.tare_samples : 100;
    if (o->po.n > 1 && o->split == NULL)
        o->out.columns |= LEP_COL_SENSOR;
    return CLI_OK;
}

/* The file for sensor i under --split: {sensor} and {n} replaced. */
static bool split_path(const char *pattern, const cli_sensor *s, size_t i, char *out, size_t cap)
{
    size_t used = 0;
    const char *p = pattern;
    char name[64], num[24];
    size_t k;
    snprintf(name, sizeof name, "%s", s->name);
    for (k = 0; name[k] != '\0'; ++k)
        if (name[k] == '/')
            name[k] = '_';
    snprintf(num, sizeof num, "%lu", (unsigned long)i + 1);
    while (*p != '\0') {
        const char *rep = NULL;
        size_t skip = 1, len;
        if (strncmp(p, "{sensor}", 8) == 0) {
            rep = name[0] == '_' ? name + 1 : name;
            skip = 8;
        } else if (strncmp(p, "{n}", 3) == 0) {
            rep = num;
            skip = 3;
        }
        len = rep != NULL ? strlen(rep) : 1;
        if (used + len >= cap)
            return false;
        memcpy(out + used, rep != NULL ? rep : p, len);
        used += len;
        p += skip;
    }
    out[used] = '\0';
    return true;
}

typedef struct stream_state {
    stream_opts o;
    sensor_run run[CLI_MAX_SENSORS];
    size_t n;
    double t0; /* the one time base: the earliest start */
    cli_status st;
    bool keys;
    bool stopped;    /* by a signal */
    int write_error; /* errno of a failed output, 0 while fine */
    /* one batch, reused */
    double t_mono[BATCH], t_utc[BATCH], zeroed[BATCH * LEP_AXES], si[BATCH * LEP_AXES];
    int16_t raw[BATCH * LEP_AXES];
    uint8_t status[BATCH], flags[BATCH];
    uint16_t seq[BATCH];
} stream_state;

static void batch_init(stream_state *st, lep_session_batch *b)
{
    memset(b, 0, sizeof *b);
    b->cap = BATCH;
    b->t_mono = st->t_mono;
    b->t_utc = st->t_utc;
    b->raw = st->raw;
    b->zeroed = st->zeroed;
    b->si = st->si;
    b->status = st->status;
    b->flags = st->flags;
    b->seq = st->seq;
}

static void note(stream_state *st, const sensor_run *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(CLI_PRINTF, 3, 4)))
#endif
    ;

/* One message line on stderr about sensor r (the status line erased first). */
static void note(stream_state *st, const sensor_run *r, const char *fmt, ...)
{
    va_list ap;
    cli_status_clear(&st->st);
    fprintf(stderr, "leptrino: stream: %s: ", r->sensor->name);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

/* With --stop-on-limit, the first limit exceeded among ev[0..*nev) ends the
 * run: the rows of b after its row and the events after it are dropped, and
 * it is reported. */
static void stop_at_limit(stream_state *st, sensor_run *r, lep_session_batch *b,
                          lep_session_event *ev, size_t *nev)
{
    static const char *const names[LEP_AXES] = { "fx", "fy", "fz", "mx", "my", "mz" };
    static const char *const units[LEP_AXES] = { "N", "N", "N", "N m", "N m", "N m" };
    lep_session_meta m;
    size_t k;
    int a;
    for (k = 0; k < *nev && ev[k].type != LEP_EV_LIMIT_EXCEEDED; ++k) {
    }
    if (k == *nev)
        return;
    r->limit_stop = true;
    *nev = k + 1;
    if (ev[k].row >= 0 && (uint64_t)ev[k].row < b->n) /* the row of this read's batch */
        b->n = (size_t)ev[k].row + 1u;
    lep_session_get_metadata(r->s, &m);
    cli_status_clear(&st->st);
    fprintf(stderr, "leptrino: stream: %s: limit exceeded at t=%.6f s:", r->sensor->name,
            ev[k].t_mono - st->t0);
    for (a = 0; a < LEP_AXES; a++)
        if (((unsigned)ev[k].axes >> a) & 1u)
            fprintf(stderr, " %s %.6g %s beyond %g", names[a], ev[k].wrench[a], units[a],
                    m.limit[a]);
    fprintf(stderr, "; stopped (--stop-on-limit)\n");
}

/* Write what one read gave: rows, and the events where they belong. */
static void emit(stream_state *st, sensor_run *r, const lep_session_batch *batch)
{
    lep_session_event ev[EVENTS];
    lep_session_batch cut = *batch, *b = &cut;
    size_t nev = 0, k;
    int rc;
    size_t from = 0;
    bool more = true;
    while (more) {
        nev = 0;
        while (nev < EVENTS && lep_session_pop_event(r->s, &ev[nev]))
            nev++;
        more = nev == EVENTS;
        if (st->o.stop_on_limit) {
            stop_at_limit(st, r, b, ev, &nev);
            more = more && !r->limit_stop;
        }
        for (k = 0; k < nev; ++k) {
            /* without reconnect, the next read says the stream is over */
            if (ev[k].type == LEP_EV_DISCONNECTED && st->o.so.reconnect) {
                if (ev[k].error == LEP_E_TIMEOUT)
                    note(st, r,
                         "no data for %g s (--data-timeout) at t=%.3f s; reopening the port "
                         "(--reconnect; Ctrl-C to stop)",
                         st->o.so.data_timeout_ms / 1000.0, ev[k].gap_from - st->t0);
                else
                    note(st, r, "disconnected at t=%.3f s; reopening the port (Ctrl-C to stop)",
                         ev[k].gap_from - st->t0);
            } else if (ev[k].type == LEP_EV_TARE) {
                r->tare_events++;
            } else if (ev[k].type == LEP_EV_RECONNECTED) {
                note(st, r, "back at t=%.3f s after %.1f s; streaming resumed",
                     ev[k].t_mono - st->t0, ev[k].gap_to - ev[k].gap_from);
            }
        }
        if (st->write_error != 0 || (b->n == 0 && nev == 0))
            break;
        rc = lep_output_write_batch(r->w, r->index, b, from, ev, nev);
        from = b->n; /* the rows go with the first events only */
        if (rc != LEP_OK) {
            st->write_error = lep_output_errno(r->w) != 0 ? lep_output_errno(r->w) : EIO;
            break;
        }
    }
}

static void status_line(stream_state *st)
{
    char text[256];
    size_t i, used = 0;
    double now = lep_monotonic_seconds();
    if (!st->st.enabled)
        return;
    text[0] = '\0';
    for (i = 0; i < st->n && used < sizeof text - 1; ++i) {
        lep_session_health_info h;
        int len;
        lep_session_get_health(st->run[i].s, &h);
        len = snprintf(text + used, sizeof text - used,
                       "%s%s%s%llu samples %.1f Hz %llu err %llu gaps", i > 0 ? " | " : "",
                       st->n > 1 ? st->run[i].sensor->name : "", st->n > 1 ? " " : "",
                       (unsigned long long)h.delivered, h.recent_hz, (unsigned long long)h.errors,
                       (unsigned long long)h.gaps);
        used = len < 0 ? used : used + (size_t)len;
        if (used > sizeof text - 1)
            used = sizeof text - 1; /* truncated: the line is cut there */
    }
    if (used < sizeof text - 1)
        snprintf(text + used, sizeof text - used, "  %.1f s", now - st->t0);
    cli_status_update(&st->st, now, text);
}

static void tare_requests(stream_state *st)
{
    cli_tare_asks a = cli_take_tare_asks(); /* q means nothing here: Ctrl-C stops */
    size_t i;
    for (i = 0; i < st->n; ++i)
        cli_tare_apply(st->run[i].s, a, st->o.retare);
}

/* Read and write until every sensor is done, one fails, a signal or an
 * output error. Returns an exit code. */
static int loop(stream_state *st)
{
    lep_session_batch b;
    size_t i;
    for (;;) {
        size_t active = 0;
        int fds[CLI_MAX_SENSORS + 1];
        bool ready[CLI_MAX_SENSORS + 1];

        if (cli_stop_requested()) {
            st->stopped = true;
            return CLI_OK;
        }
        tare_requests(st);
        for (i = 0; i < st->n; ++i) {
            sensor_run *r = &st->run[i];
            if (r->failed == LEP_E_LOST) {
                /* a lost stream: say which option decides it, never wait in silence */
                note(st, r,
                     "no data for %g s (--data-timeout %g): the stream is lost (--reconnect "
                     "reopens the port and waits for the sensor instead)",
                     st->o.so.data_timeout_ms / 1000.0, st->o.so.data_timeout_ms / 1000.0);
                return lep_exit_code(LEP_E_LOST);
            }
            if (r->failed != 0)
                return cli_session_fail(r->s, "stream", r->sensor->name, "stream", r->failed);
            if (r->limit_stop)
                return CLI_LIMIT;
            fds[i] = r->done ? -1 : lep_session_fd(r->s);
            active += r->done ? 0u : 1u;
        }
        if (active == 0)
            return CLI_OK;
        if (st->write_error != 0)
            return st->write_error == EPIPE ? CLI_OK : CLI_FAIL;
        if (st->n > 1 || st->keys) {
            /* Several sources: wait for any, then take what each has. */
            fds[st->n] = st->keys ? STDIN_FILENO : -1;
            cli_wait_input(fds, st->n + 1, ready, WAIT_MS);
        }
        for (i = 0; i < st->n; ++i) {
            sensor_run *r = &st->run[i];
            int rc;
            if (r->done)
                continue;
            batch_init(st, &b);
            rc = lep_session_read_batch(r->s, &b, st->n > 1 || st->keys ? 0 : WAIT_MS);
            emit(st, r, &b);
            /* a quiet source: what was written reaches the file now (the
             * writer itself flushes a file every 100 ms while rows come) */
            if (b.n == 0 && st->write_error == 0 && lep_output_flush(r->w) != LEP_OK)
                st->write_error = lep_output_errno(r->w) != 0 ? lep_output_errno(r->w) : EIO;
            if (rc == LEP_E_END)
                r->done = true;
            else if (rc != LEP_OK && rc != LEP_E_TIMEOUT && r->failed == 0)
                r->failed = rc;
        }
        status_line(st);
    }
}

/* One line per sensor: samples, time, measured against nominal rate (a
 * shortfall said plainly), errors, overloads, gaps and what they lost. */
static void summary(stream_state *st)
{
    size_t i;
    for (i = 0; i < st->n; ++i) {
        sensor_run *r = &st->run[i];
        lep_session_health_info h;
        bool tared;
        double off[LEP_AXES];
        const char *tare_words = "";
        lep_session_get_health(r->s, &h);
        tared = lep_session_get_tare(r->s, off);
        /* What the tare is at the end: averaging still, in force, or removed
         * (by u / SIGUSR2) after one; nothing when no tare was asked for. */
        if (lep_session_taring(r->s))
            tare_words = ", tare incomplete (still averaging at the end)";
        else if (tared)
            tare_words = ", tared";
        else if (r->tare_events > 0)
            tare_words = ", untared";
        else if (st->o.so.tare_samples > 0)
            tare_words = ", tare incomplete";
        fprintf(stderr,
                "leptrino: stream: %s: %llu samples in %.3f s, %.1f Hz measured (nominal %.0f "
                "Hz), %llu errors, %llu overloads, %llu gaps (%llu samples lost, longest "
                "%.3f s)%s%s\n",
                r->sensor->name, (unsigned long long)h.delivered, h.elapsed_s, h.measured_hz,
                h.nominal_hz, (unsigned long long)h.errors, (unsigned long long)h.overloads,
                (unsigned long long)h.gaps, (unsigned long long)h.lost, h.max_gap_s, tare_words,
                st->stopped ? "; stopped by signal" : "");
        if (h.events_dropped > 0)
            fprintf(stderr,
                    "leptrino: stream: %s: %llu events dropped (the session's event queue was "
                    "full): the output lacks them\n",
                    r->sensor->name, (unsigned long long)h.events_dropped);
        if (h.limit_episodes > 0)
            fprintf(stderr, "leptrino: stream: %s: %llu limit episode%s\n", r->sensor->name,
                    (unsigned long long)h.limit_episodes, h.limit_episodes == 1 ? "" : "s");
        if (h.shortfall)
            fprintf(stderr,
                    "leptrino: stream: %s: RATE SHORTFALL: %.1f Hz is %.1f %% below the "
                    "nominal %.0f Hz (samples were lost or the sensor runs slow)\n",
                    r->sensor->name, h.measured_hz,
                    100.0 * (h.nominal_hz - h.measured_hz) / h.nominal_hz, h.nominal_hz);
    }
}

/* Writers: one for every sensor (--split) or one shared. */
/* With --split, refuse before creating any file when one of them already
 * holds a regular file: no metadata-only file is left behind for a run that
 * does not happen (the writer's own exclusive open still guards each file). */
static int check_split_targets(stream_state *st)
{
    size_t i;
    if (st->o.split == NULL || st->o.out.overwrite)
        return CLI_OK;
    for (i = 0; i < st->n; ++i) {
        char path[1024];
        struct stat sb;
        if (!split_path(st->o.split, st->run[i].sensor, i, path, sizeof path))
            continue; /* reported by open_outputs */
        if (stat(path, &sb) == 0 && (S_ISREG(sb.st_mode) || S_ISDIR(sb.st_mode))) {
            fprintf(stderr,
                    "leptrino: stream: %s: already exists; not overwritten (choose another "
                    "name, or --overwrite); no file was written\n",
                    path);
            return CLI_FAIL;
        }
    }
    return CLI_OK;
}

static int open_outputs(stream_state *st)
{
    size_t i;
    if (check_split_targets(st) != CLI_OK)
        return CLI_FAIL;
    for (i = 0; i < st->n; ++i) {
        sensor_run *r = &st->run[i];
        char path[1024], err[512];
        const char *target = st->o.output;
        lep_output_options oo;
        struct stat sb;
        int rc;
        if (st->o.split == NULL && i > 0) {
            r->w = st->run[0].w;
            r->index = lep_output_add_session(r->w, r->s, r->sensor->name);
            continue;
        }
        if (st->o.split != NULL) {
            if (!split_path(st->o.split, r->sensor, i, path, sizeof path)) {
                fprintf(stderr, "leptrino: stream: --split: the file name is too long\n");
                return CLI_FAIL;
            }
            target = path;
        }
        if (target != NULL && strcmp(target, "-") == 0)
            target = NULL;
        err[0] = '\0';
        oo = st->o.out;
        /* A device or a pipe (-o /dev/null, a FIFO) holds nobody's file:
         * writing to it needs no --overwrite. */
        if (target != NULL && stat(target, &sb) == 0 && !S_ISREG(sb.st_mode) &&
            !S_ISDIR(sb.st_mode))
            oo.overwrite = true;
        rc = lep_output_open_opts(target, &oo, &r->w, err, sizeof err);
        if (rc == LEP_E_ARG && target != NULL && !oo.overwrite && stat(target, &sb) == 0) {
            r->w = NULL; /* the library's words name no flag: this tool's does */
            fprintf(stderr,
                    "leptrino: stream: %s: already exists; not overwritten (choose another "
                    "name, or --overwrite)\n",
                    target);
            return CLI_FAIL;
        }
        if (rc != LEP_OK) {
            r->w = NULL;
            fprintf(stderr, "leptrino: stream: %s\n", err[0] != '\0' ? err : lep_strerror(rc));
            return CLI_FAIL;
        }
        r->own_writer = true;
        r->index = lep_output_add_session(r->w, r->s, r->sensor->name);
    }
    return CLI_OK;
}

static void close_outputs(stream_state *st)
{
    size_t i;
    for (i = 0; i < st->n; ++i) {
        sensor_run *r = &st->run[i];
        if (r->own_writer && lep_output_close(r->w) != LEP_OK && st->write_error == 0)
            st->write_error = EIO;
        r->w = NULL;
        r->own_writer = false;
    }
}

int cli_cmd_stream(int argc, char **argv)
{
    static stream_state st;
    bool ran = false; /* the stream ran (a summary is due) */
    int code, rc;
    size_t i;

    memset(&st, 0, sizeof st);
    code = parse(argc, argv, &st.o);
    if (code != CLI_OK)
        return code < 0 ? CLI_OK : code;
    cli_signals_install();

    /* The sensors first: a run that cannot reach them leaves the files alone. */
    code = cli_sensors_open(&st.o.po, &st.o.so, "stream");
    if (code != CLI_OK)
        return code;
    st.n = st.o.po.n;
    for (i = 0; i < st.n; ++i) {
        st.run[i].sensor = &st.o.po.sensor[i];
        st.run[i].s = st.o.po.sensor[i].session;
    }
    for (i = 0; code == CLI_OK && i < st.n; ++i) {
        rc = lep_session_start(st.run[i].s);
        if (rc != LEP_OK)
            code = cli_session_fail(st.run[i].s, "stream", st.run[i].sensor->name, "start", rc);
    }
    if (code == CLI_OK) {
        /* One time base: t = 0 at the earliest start. */
        st.t0 = INFINITY;
        for (i = 0; i < st.n; ++i) {
            lep_session_meta m;
            lep_session_get_metadata(st.run[i].s, &m);
            if (m.start_mono < st.t0)
                st.t0 = m.start_mono;
        }
        st.o.out.t0_mono = st.t0;
        code = open_outputs(&st);
    }
    if (code == CLI_OK) {
        bool to_stdout =
            st.o.split == NULL && (st.o.output == NULL || strcmp(st.o.output, "-") == 0);
        cli_status_init(&st.st, to_stdout ? STDOUT_FILENO : -1);
        st.keys = cli_term_keys_begin();
        ran = true;
        code = loop(&st);
        cli_term_keys_end();
    }
    for (i = 0; i < st.n; ++i) {
        if (lep_session_streaming(st.run[i].s)) {
            /* A sensor that went quiet may not answer the stop either: the
             * wait is said first, with the option that bounds it. */
            int per_try = st.o.po.timeout_ms;
            if (st.run[i].failed == LEP_E_LOST)
                note(&st, &st.run[i],
                     "stopping the sensor's stream: up to %.1f s without an answer "
                     "(-t/--timeout %d ms a try)",
                     lep_session_stop_wait(st.run[i].s), per_try);
            rc = lep_session_stop(st.run[i].s);
            if (rc == LEP_E_TIMEOUT)
                note(&st, &st.run[i],
                     "could not stop the sensor's stream: no answer within -t/--timeout %d ms "
                     "a try (the next leptrino run stops it at start-up)",
                     per_try);
            else if (rc != LEP_OK && rc != LEP_E_DISCONNECTED)
                note(&st, &st.run[i], "could not stop the sensor's stream: %s", lep_strerror(rc));
        }
    }
    close_outputs(&st);
    cli_status_clear(&st.st);
    if (st.write_error == EPIPE) {
        code = CLI_OK; /* the reader went away (e.g. `| head`): a normal end */
    } else if (st.write_error != 0) {
        fprintf(stderr, "leptrino: stream: cannot write the output: %s\n",
                strerror(st.write_error));
        code = CLI_FAIL;
    }
    if (ran && st.t0 > 0.0 && st.t0 < INFINITY)
        summary(&st);
    cli_sensors_close(&st.o.po);
    return code;
}
