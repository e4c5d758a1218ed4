/* Private interface between the files of the `leptrino` command-line tool.
 *
 * Files depend one way (test/checks/depgraph.py): main.c dispatches to one
 * cmd_*.c per command; the commands call the shared helpers below them,
 * never main.c. help.c prints the help's common end, args.c parses options,
 * load_opts.c the options about the tool on the sensor and the limits,
 * sensors.c turns PORT / --sim / --sim-* into sessions (leptrino/session.h:
 * the one place that starts a sensor up) and reports their errors,
 * term_*.c and signals_*.c (one per OS) deal with the terminal and signals,
 * safe_text.c with sensor text on it, tare_requests.c turns their keys and
 * signals into tare requests (stream and watch), status.c draws
 * the live status line, watch_view.c the screen of `leptrino watch`.
 * No sensor logic lives here: tare, units, filtering, gaps, reconnection
 * and the formatting of samples belong to the session and its writer.
 * Nothing here is exported from the program. */
#ifndef LEPTRINO_TOOL_CLI_H
#define LEPTRINO_TOOL_CLI_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* The printf archetype of format attributes: mingw-w64's gcc reads plain
 * "printf" as msvcrt's (no %zu); the build uses its C99 stdio, gnu_printf's. */
#if defined(__MINGW32__)
#define CLI_PRINTF gnu_printf
#else
#define CLI_PRINTF printf
#endif

#include <leptrino/leptrino.h>
#include <leptrino/output.h>
#include <leptrino/process.h>
#include <leptrino/serial.h>
#include <leptrino/session.h>
#include <leptrino/sim.h>
#include "struct_api.h"

/* Exit codes (documented in `leptrino --help` and docs/cli.md): the
 * library's table (leptrino/process.h), which lep_exit_code applies. */
enum cli_exit {
    CLI_OK = LEP_EXIT_OK,
    CLI_FAIL = LEP_EXIT_FAIL,
    CLI_USAGE = LEP_EXIT_USAGE,
    CLI_TIMEOUT = LEP_EXIT_TIMEOUT,
    CLI_DISCONNECTED = LEP_EXIT_DISCONNECTED,
    CLI_SENSOR = LEP_EXIT_SENSOR,
    CLI_NOT_FOUND = LEP_EXIT_NOT_FOUND,
    CLI_BUSY = LEP_EXIT_BUSY,
    CLI_PERMISSION = LEP_EXIT_PERMISSION,
    /* the commands' own outcomes, above the library's statuses */
    CLI_LIMIT = 9, /* stream --stop-on-limit: a limit was exceeded */
    /* leptrino check: the first criterion that failed, in this order */
    CLI_CHECK_STATUS = 10,   /* a status bit: ROM calibration data error or sensor error */
    CLI_CHECK_ERRORS = 11,   /* more frame errors than --max-errors */
    CLI_CHECK_LOSS = 12,     /* more samples lost than --max-loss */
    CLI_CHECK_RATE = 13,     /* measured rate below --min-rate % of nominal */
    CLI_CHECK_OVERLOAD = 14, /* an overload */
    CLI_CHECK_NOISE = 15     /* an axis noisier than --max-noise */
};

/* Sensors one `leptrino stream` may record at once. */
#define CLI_MAX_SENSORS 8

/* ---- args.c: a cursor over argv ----
 * Options may come before or after positionals; `--name=value` and
 * `--name value` are both accepted; `--` ends the options. Every error
 * prints one line "leptrino: CMD: ..." on stderr and sets failed. */
typedef struct cli_args {
    int argc;
    char **argv;
    int next;                 /* index of the next argv element */
    const char *cmd;          /* command name for messages */
    const char *cur;          /* current element as given */
    char name[64];            /* option name without an inline value */
    const char *inline_value; /* after '=' in --name=value, else NULL */
    bool positional;          /* cur is a positional argument */
    bool only_positional;     /* after "--" */
    bool matched;             /* the current option was recognised */
    bool failed;              /* an error was printed */
} cli_args;

void cli_args_init(cli_args *a, int argc, char **argv, const char *cmd);
/* Advance to the next element; false at the end or after a failure. */
bool cli_args_next(cli_args *a);
/* Current element is the option -s / --long (either may be NULL). */
bool cli_args_is(cli_args *a, const char *short_name, const char *long_name);
/* The current element is -h / --help (without a value: --help=x fails). */
bool cli_args_help(cli_args *a);
/* The option takes no value: fails on --flag=value. Returns true. */
bool cli_args_flag(cli_args *a);
/* The option's value (inline or the next element); NULL and failed if absent. */
const char *cli_args_value(cli_args *a);
/* Numeric values of the current option; on error failed is set and 0 returned. */
double cli_args_double(cli_args *a, double lo, double hi, bool lo_exclusive);
uint64_t cli_args_uint(cli_args *a, uint64_t lo, uint64_t hi);
/* n comma-separated finite numbers into out; false (and failed) otherwise. */
bool cli_args_doubles(cli_args *a, double *out, size_t n);
/* Report the current element as unknown (option) or unexpected (positional). */
void cli_args_unknown(cli_args *a);
/* Print "leptrino: CMD: <message>" and set failed. */
void cli_args_error(cli_args *a, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(CLI_PRINTF, 2, 3)))
#endif
    ;

/* ---- load_opts.c: --payload, --gravity, --limit ---- */
/* The current option is one of them (--limit only when limits): parsed into
 * so (errors reported, a->failed set); false when it is none of them. */
bool cli_load_option(cli_args *a, lep_session_options *so, bool limits);
/* Their help lines. */
void cli_load_help(FILE *f, bool limits);

/* ---- sensors.c: PORT... / --sim... into sessions ---- */
typedef struct cli_sensor {
    const char *port;     /* PORT as given, or NULL for a virtual sensor */
    lep_sim_options sim;  /* its options (virtual sensor) */
    char name[64];        /* label: the port, or sim1, sim2, ... */
    lep_session *session; /* after cli_sensors_open */
} cli_sensor;

typedef struct cli_port_opts {
    cli_sensor sensor[CLI_MAX_SENSORS];
    size_t n;
    size_t sims;                  /* how many of them are virtual */
    bool several;                 /* the command takes several sensors */
    lep_sim_options sim_defaults; /* --sim-* given before the first --sim */
    const char *sim_option;       /* the first --sim-* option seen (needs a --sim) */
    int timeout_ms;               /* --timeout, transaction timeout */
} cli_port_opts;

void cli_port_opts_init(cli_port_opts *po, bool several);
/* Handle the current element if it is PORT, --sim, --sim-* or --timeout. */
bool cli_port_option(cli_port_opts *po, cli_args *a);
/* Add a serial port (as a positional PORT does); false and failed on error. */
bool cli_port_add(cli_port_opts *po, cli_args *a, const char *port);
/* After parsing: at least one sensor (exactly one unless several). */
bool cli_port_check(cli_port_opts *po, cli_args *a);
/* Help text for the port and virtual sensor options (from the sim table). */
void cli_port_help(FILE *f, bool several);

/* Open a session on every sensor with o as the template (port and sim
 * filled in here). Prints the error naming the port and closes what was
 * opened; returns an exit code. */
int cli_sensors_open(cli_port_opts *po, const lep_session_options *o, const char *cmd);
void cli_sensors_close(cli_port_opts *po);
/* Print "leptrino: CMD: PORT: WHAT: <error>"; returns the exit code for err. */
/* `leptrino help sim`: every --sim-NAME option (from the simulator's table). */
void cli_sim_help(FILE *f);
int cli_session_fail(lep_session *s, const char *cmd, const char *port, const char *what, int err);

/* ---- term_posix.c / term_win32.c: the user's terminal ---- */
/* Single keys from stdin without echo when stdin is a terminal and we are in
 * its foreground process group; false otherwise (no change made). */
bool cli_term_keys_begin(void);
void cli_term_keys_end(void);
/* A key pressed, or -1 (none waiting, or keys not begun). Never blocks. */
int cli_term_read_key(void);
/* Full-screen mode on fd (alternate screen, cursor hidden) and back. */
void cli_term_screen_begin(int fd);
void cli_term_screen_end(void);
/* Undo keys and screen mode from a signal handler (async-signal-safe). */
void cli_term_restore_from_signal(void);
/* Both fds are the same terminal. */
bool cli_term_same_tty(int fd_a, int fd_b);
/* A status line may be drawn on stderr: a terminal, ours (not a background
 * job's), and not the one the data (out_fd, -1 for a file) goes to. */
bool cli_term_status_ok(int out_fd);
/* Window size of the terminal on fd (80x24 when unknown). */
void cli_term_size(int fd, int *cols, int *rows);
/* poll() for input on fds[0..n) (n <= CLI_MAX_SENSORS + 1; fd < 0 ignored);
 * ready[i] says which. Returns how many, 0 on timeout or a signal, -1 on error. */
int cli_wait_input(const int *fds, size_t n, bool *ready, int timeout_ms);
/* Sensor text made safe for a terminal: printable ASCII kept, a backslash
 * doubled, any other byte as \xNN. Returns the length written (truncated to
 * fit out[0..cap), always NUL-terminated). */
size_t cli_safe_text(const char *s, char *out, size_t cap);

/* ---- status.c: live status line on stderr ---- */
typedef struct cli_status {
    bool enabled;
    bool drawn;
    double last_draw;
} cli_status;

/* Enabled when stderr is a terminal that the data does not go to (out_fd
 * is the data's fd, -1 for a file that is not a terminal). */
void cli_status_init(cli_status *st, int out_fd);
/* Redraw at most ~4 times per second: text is one line. */
void cli_status_update(cli_status *st, double now, const char *text);
/* Erase the line so that a message can be printed. */
void cli_status_clear(cli_status *st);

/* ---- signals_posix.c / signals_win32.c ---- */
/* Stop on SIGINT/SIGTERM/SIGHUP (a second SIGINT/SIGTERM ends the program
 * after restoring the terminal); SIGUSR1 / SIGUSR2 request tare / untare;
 * SIGWINCH notes a resize; SIGPIPE is ignored so a closed output is a write
 * error (EPIPE). */
void cli_signals_install(void);
bool cli_stop_requested(void);
/* Requests received since the last call. */
unsigned cli_take_tare_requests(void);
unsigned cli_take_untare_requests(void);
bool cli_take_resize(void);
/* Sleep ms milliseconds, returning early when a stop is requested. */
void cli_sleep_ms(int ms);

/* ---- tare_requests.c: keys and signals into tare requests ---- */
typedef struct cli_tare_asks {
    bool tare;   /* t or T pressed, or SIGUSR1, since the last call */
    bool untare; /* u or U, or SIGUSR2 */
    bool quit;   /* q or Q (for the commands that stop on it) */
} cli_tare_asks;
/* Everything asked since the last call: the signals' requests and every key
 * waiting (never blocks; several of one kind count once). */
cli_tare_asks cli_take_tare_asks(void);
/* Do what a asks on s: the untare first, then a tare over `samples` samples. */
void cli_tare_apply(lep_session *s, cli_tare_asks a, unsigned samples);

/* ---- watch_view.c: the screen of `leptrino watch` ---- */
typedef struct cli_watch_view {
    lep_session_meta meta;
    lep_session_health_info health;
    bool have_sample;
    double si[LEP_AXES];   /* the latest sample, zeroed SI */
    uint8_t status;        /* its status bits */
    uint8_t overload_axes; /* axes in an overload episode */
    bool taring;
    char lowpass_text[32];
    char message[160]; /* the last event, already safe to print */
} cli_watch_view;

/* Draw the whole view for a cols x rows window with one write() to fd. */
void cli_watch_draw(int fd, const cli_watch_view *v, int cols, int rows);

/* ---- help.c ---- */
void cli_print_exit_codes(FILE *f);
/* The end of a command's help: the sensor options (sensors 1: one, 2:
 * several, 0: none), then the exit codes. */
void cli_print_help_end(FILE *f, int sensors);

/* ---- commands ---- */
int cli_cmd_list(int argc, char **argv);
int cli_cmd_info(int argc, char **argv);
int cli_cmd_read(int argc, char **argv);
int cli_cmd_stream(int argc, char **argv);
int cli_cmd_filter(int argc, char **argv);
int cli_cmd_watch(int argc, char **argv);
int cli_cmd_payload(int argc, char **argv);
int cli_cmd_check(int argc, char **argv);

#endif
