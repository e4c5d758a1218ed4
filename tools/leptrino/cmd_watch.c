/* `leptrino watch`: a live view of one sensor in the terminal (full screen,
 * plain ANSI sequences), with keys for tare, untare and quit. The numbers
 * and events come from the session; this file only reads keys and draws. */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

#define WATCH_BATCH 512
#define WATCH_FRAME_S 0.1 /* redraw period */
#define WATCH_WAIT_MS 50  /* longest wait for a key between reads */

typedef struct watch_opts {
    cli_port_opts po;
    unsigned tare_n; /* samples a tare averages */
    double lowpass;
    bool reconnect;
    double data_timeout;
    lep_session_options load; /* --payload, --gravity */
} watch_opts;

static void help(void)
{
    fputs("Usage: leptrino watch PORT|--sim [options]\n"
          "\n"
          "Show one sensor live in the terminal: the six axes as bars against the\n"
          "rated range (zeroed, in N and N m), overload and status bits, the measured\n"
          "rate against the nominal one, errors, gaps and overloads. Standard output\n"
          "must be a terminal. The screen is restored on exit, on Ctrl-C and on\n"
          "SIGTERM; a resized window is redrawn to fit.\n"
          "\n"
          "Keys:\n"
          "  t  tare: zero every axis on the mean of the next --tare samples\n"
          "  u  untare: back to the sensor's own zero\n"
          "  q  quit (also Ctrl-C)\n"
          "SIGUSR1 and SIGUSR2 tare and untare too.\n"
          "\n"
          "Options:\n"
          "      --tare N             samples a tare averages (default 100)\n"
          "      --lowpass HZ         host low-pass filter cut-off in Hz (default off)\n"
          "      --reconnect          when the port goes away, reopen it and go on\n"
          "      --data-timeout S     no data for S seconds is an error (default 2)\n",
          stdout);
    cli_load_help(stdout, false);
    fputs("  -h, --help               show this help\n"
          "\n",
          stdout);
    cli_print_help_end(stdout, 1);
}

static int parse(int argc, char **argv, watch_opts *o)
{
    cli_args a;
    cli_args_init(&a, argc, argv, "watch");
    memset(o, 0, sizeof *o);
    cli_port_opts_init(&o->po, false);
    o->tare_n = 100;
    o->data_timeout = 2.0;
    lep_session_options_init(&o->load);
    while (cli_args_next(&a)) {
        if (cli_args_help(&a)) {
            help();
            return -1;
        } else if (cli_args_is(&a, NULL, "--tare")) {
            o->tare_n = (unsigned)cli_args_uint(&a, 1, 1000000);
        } else if (cli_args_is(&a, NULL, "--lowpass")) {
            o->lowpass = cli_args_double(&a, 0.0, 10000.0, true);
        } else if (cli_args_is(&a, NULL, "--reconnect")) {
            cli_args_flag(&a);
            o->reconnect = true;
        } else if (cli_args_is(&a, NULL, "--data-timeout")) {
            o->data_timeout = cli_args_double(&a, 0.0, 3600.0, true);
        } else if (cli_load_option(&a, &o->load, false)) {
            /* --payload, --gravity */
        } else if (!cli_port_option(&o->po, &a)) {
            cli_args_unknown(&a);
        }
    }
    if (a.failed || !cli_port_check(&o->po, &a))
        return CLI_USAGE;
    if (isatty(STDOUT_FILENO) != 1) {
        cli_args_error(&a, "standard output is not a terminal (use 'leptrino stream' to record)");
        return CLI_USAGE;
    }
    return CLI_OK;
}

/* What an event means, one line for the view. */
static void note_event(cli_watch_view *v, const lep_session_event *ev, double t0)
{
    switch (ev->type) {
    case LEP_EV_GAP:
        snprintf(v->message, sizeof v->message, "gap of %.0f ms at %.1f s (%lu samples lost)",
                 (ev->gap_to - ev->gap_from) * 1000.0, ev->gap_from - t0, (unsigned long)ev->lost);
        break;
    case LEP_EV_DISCONNECTED:
        snprintf(v->message, sizeof v->message, "%s at %.1f s",
                 ev->error == LEP_E_TIMEOUT ? "no data for --data-timeout" : "disconnected",
                 ev->t_mono - t0);
        break;
    case LEP_EV_RECONNECTED:
        snprintf(v->message, sizeof v->message, "reconnected at %.1f s after %.1f s",
                 ev->t_mono - t0, ev->gap_to - ev->gap_from);
        break;
    case LEP_EV_TARE:
        snprintf(v->message, sizeof v->message, "tare %s at %.1f s",
                 ev->tare[0] == 0.0 && ev->tare[1] == 0.0 && ev->tare[2] == 0.0 &&
                         ev->tare[3] == 0.0 && ev->tare[4] == 0.0 && ev->tare[5] == 0.0
                     ? "removed"
                     : "done",
                 ev->t_mono - t0);
        break;
    case LEP_EV_OVERLOAD_BEGIN:
        v->overload_axes = ev->axes;
        snprintf(v->message, sizeof v->message, "overload began at %.1f s", ev->t_mono - t0);
        break;
    case LEP_EV_OVERLOAD_END:
        v->overload_axes = 0;
        snprintf(v->message, sizeof v->message, "overload ended at %.1f s", ev->t_mono - t0);
        break;
    default:
        break;
    }
}

int cli_cmd_watch(int argc, char **argv)
{
    static double si[WATCH_BATCH * LEP_AXES];
    static uint8_t status[WATCH_BATCH];
    static cli_watch_view v;
    watch_opts o;
    lep_session_options so;
    lep_session *s;
    const char *port;
    int code, rc, cols, rows;
    double t0, next_frame = 0.0;
    bool quit = false, keys;

    code = parse(argc, argv, &o);
    if (code != CLI_OK)
        return code < 0 ? CLI_OK : code;
    lep_session_options_init(&so);
    so.lowpass_hz = o.lowpass;
    so.reconnect = o.reconnect;
    so.data_timeout_ms = (int)(o.data_timeout * 1000.0);
    so.payload = o.load.payload;
    memcpy(so.gravity, o.load.gravity, sizeof so.gravity);
    cli_signals_install();
    code = cli_sensors_open(&o.po, &so, "watch");
    if (code != CLI_OK)
        return code;
    s = o.po.sensor[0].session;
    port = lep_session_port(s);
    rc = lep_session_start(s);
    if (rc != LEP_OK) {
        code = cli_session_fail(s, "watch", port, "start", rc);
        cli_sensors_close(&o.po);
        return code;
    }
    t0 = lep_monotonic_seconds();
    memset(&v, 0, sizeof v);
    if (o.lowpass > 0.0)
        snprintf(v.lowpass_text, sizeof v.lowpass_text, "%g Hz", o.lowpass);
    else
        snprintf(v.lowpass_text, sizeof v.lowpass_text, "off");
    snprintf(v.message, sizeof v.message, "-");
    keys = cli_term_keys_begin();
    cli_term_screen_begin(STDOUT_FILENO);
    cli_term_size(STDOUT_FILENO, &cols, &rows);

    while (!quit && !cli_stop_requested()) {
        int fds[1];
        bool ready[1];
        lep_session_batch b;
        lep_session_event ev;
        cli_tare_asks asks;
        double now;

        /* Wake for a key or every 50 ms, then take all the samples that came:
         * a view needs no per-sample wake-up (20 a second instead of 1200). */
        fds[0] = keys ? STDIN_FILENO : -1;
        cli_wait_input(fds, 1, ready, WATCH_WAIT_MS);

        do { /* everything that came, the last sample shown */
            memset(&b, 0, sizeof b);
            b.cap = WATCH_BATCH;
            b.si = si;
            b.status = status;
            rc = lep_session_read_batch(s, &b, 0);
            if (b.n > 0) {
                memcpy(v.si, &si[(b.n - 1) * LEP_AXES], sizeof v.si);
                v.status = status[b.n - 1];
                v.have_sample = true;
            }
        } while (rc == LEP_OK && b.n == b.cap);
        while (lep_session_pop_event(s, &ev))
            note_event(&v, &ev, t0);
        /* LEP_E_TIMEOUT: nothing yet; LEP_E_LOST, LEP_E_DISCONNECTED: the end */
        if (rc != LEP_OK && rc != LEP_E_TIMEOUT) {
            code = lep_exit_code(rc); /* LEP_E_END: LEP_EXIT_OK */
            break;
        }

        asks = cli_take_tare_asks();
        cli_tare_apply(s, asks, o.tare_n);
        quit = asks.quit;

        now = lep_monotonic_seconds();
        if (cli_take_resize()) {
            cli_term_size(STDOUT_FILENO, &cols, &rows);
            (void)!write(STDOUT_FILENO, "\033[2J", 4);
            next_frame = 0.0;
        }
        if (now >= next_frame) {
            lep_session_get_metadata(s, &v.meta);
            lep_session_get_health(s, &v.health);
            v.taring = lep_session_taring(s);
            cli_watch_draw(STDOUT_FILENO, &v, cols, rows);
            next_frame = now + WATCH_FRAME_S;
        }
    }

    cli_term_screen_end();
    cli_term_keys_end();
    lep_session_get_health(s, &v.health);
    if (code != CLI_OK) {
        cli_session_fail(s, "watch", port, "stream", rc);
        if (rc == LEP_E_LOST && lep_session_streaming(s)) {
            /* a quiet sensor may not answer the stop: say the wait first */
            fprintf(stderr,
                    "leptrino: watch: %s: stopping the sensor's stream: up to %.1f s without an "
                    "answer (-t/--timeout %d ms a try)\n",
                    port, lep_session_stop_wait(s), o.po.timeout_ms);
            (void)lep_session_stop(s);
        }
    } else {
        lep_session_stop(s);
        fprintf(stderr,
                "leptrino: watch: %llu samples, %.1f Hz (nominal %.0f), %llu errors, "
                "%llu gaps, %llu overloads\n",
                (unsigned long long)v.health.received, v.health.measured_hz, v.health.nominal_hz,
                (unsigned long long)v.health.errors, (unsigned long long)v.health.gaps,
                (unsigned long long)v.health.overloads);
    }
    cli_sensors_close(&o.po);
    return code;
}
