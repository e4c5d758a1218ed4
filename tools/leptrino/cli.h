/* Private interface between the files of the `leptrino` command-line tool.
 *
 * main.c dispatches to one cmd_*.c per command. args.c parses options,
 * conn.c opens a sensor (real port or in-process virtual sensor) and maps
 * errors to exit codes, output.c writes samples (CSV / JSON lines),
 * status.c draws the live status line, signals.c turns SIGINT/SIGTERM into
 * a flag. Nothing here is exported from the program. */
#ifndef LEPTRINO_TOOL_CLI_H
#define LEPTRINO_TOOL_CLI_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <leptrino/leptrino.h>
#include <leptrino/serial.h>
#include <leptrino/sim.h>

/* poll() sizes: sensors one command may read at once. */
#define CLI_MAX_SENSORS 8

/* Exit codes (documented in `leptrino --help` and docs/cli.md). */
enum cli_exit {
    CLI_OK = 0,           /* success (also after Ctrl-C / SIGTERM during stream) */
    CLI_FAIL = 1,         /* any other failure (I/O error, output file, protocol) */
    CLI_USAGE = 2,        /* bad command line */
    CLI_TIMEOUT = 3,      /* the sensor did not answer / data stopped arriving */
    CLI_DISCONNECTED = 4, /* the port went away */
    CLI_SENSOR = 5,       /* the sensor refused a command (result code or NAKs) */
    CLI_NOT_FOUND = 6,    /* no such port, or not a serial port */
    CLI_BUSY = 7,         /* the port is in use by another program */
    CLI_PERMISSION = 8    /* no permission to open the port */
};

/* ---- args.c: a cursor over argv ----
 * Options may come before or after positionals; `--name=value` and
 * `--name value` are both accepted; `--` ends the options. Every error
 * prints one line "leptrino: CMD: ..." on stderr and sets failed. */
typedef struct cli_args {
    int argc;
    char **argv;
    int next;             /* index of the next argv element */
    const char *cmd;      /* command name for messages */
    const char *cur;      /* current element as given */
    char name[64];        /* option name without an inline value */
    const char *inline_value; /* after '=' in --name=value, else NULL */
    bool positional;      /* cur is a positional argument */
    bool only_positional; /* after "--" */
    bool matched;         /* the current option was recognised */
    bool failed;          /* an error was printed */
} cli_args;

void cli_args_init(cli_args *a, int argc, char **argv, const char *cmd);
/* Advance to the next element; false at the end or after a failure. */
bool cli_args_next(cli_args *a);
/* Current element is the option -s / --long (either may be NULL). */
bool cli_args_is(cli_args *a, const char *short_name, const char *long_name);
/* The option takes no value: fails on --flag=value. Returns true. */
bool cli_args_flag(cli_args *a);
/* The option's value (inline or the next element); NULL and failed if absent. */
const char *cli_args_value(cli_args *a);
/* Numeric values of the current option; on error failed is set and 0 returned. */
double cli_args_double(cli_args *a, double lo, double hi, bool lo_exclusive);
uint64_t cli_args_uint(cli_args *a, uint64_t lo, uint64_t hi);
/* Report the current element as unknown (option) or unexpected (positional). */
void cli_args_unknown(cli_args *a);
/* Print "leptrino: CMD: <message>" and set failed. */
void cli_args_error(cli_args *a, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* ---- conn.c: the sensor behind PORT or --sim ---- */
typedef struct cli_port_opts {
    const char *port;         /* positional PORT, or NULL */
    bool sim;                 /* --sim */
    const char *sim_option;   /* first --sim-* option seen (to reject it without --sim) */
    lep_sim_options sim_opts;
    int timeout_ms;           /* --timeout, transaction timeout */
    bool sim_reopen;          /* --sim-reopen-after given */
    bool reopen_link_auto;    /* a link path was made up for --sim-reopen-after */
    char link_buf[128];
} cli_port_opts;

void cli_port_opts_init(cli_port_opts *po);
/* Handle the current option if it is a port/sim option; true if it was. */
bool cli_port_option(cli_port_opts *po, cli_args *a);
/* After parsing: exactly one of PORT and --sim; --sim-* only with --sim. */
bool cli_port_check(cli_port_opts *po, cli_args *a);
/* Help text for the port/sim options. */
void cli_port_help(FILE *f);

typedef struct cli_conn {
    const char *cmd;
    lep_sim *sim;
    lep_serial *serial;
    lep_client client;
    lep_product_info info;
    int timeout_ms;
    char path[512];
} cli_conn;

/* Start the virtual sensor if asked, open the port, sync (stop a stale
 * stream, confirm the sensor answers). Prints the error; returns an exit code. */
int cli_conn_open(cli_conn *c, const cli_port_opts *po, const char *cmd);
/* Open c->path again after a disconnect and sync. Quiet; returns LEP_* code. */
int cli_conn_reopen(cli_conn *c);
/* Close the port (not the virtual sensor). */
void cli_conn_drop(cli_conn *c);
/* Close everything. */
void cli_conn_close(cli_conn *c);
/* Print "leptrino: CMD: <what>: <error>" and return the exit code for err. */
int cli_conn_fail(const cli_conn *c, const char *what, int err);
/* Exit code for a LEP_E_* code. */
int cli_exit_code(int err);

/* ---- output.c: samples as CSV or JSON lines ---- */
typedef enum cli_format { CLI_FORMAT_CSV, CLI_FORMAT_JSONL } cli_format;

typedef struct cli_writer {
    FILE *f;
    cli_format format;
    bool si;           /* N and N m; else raw counts */
    lep_rated rated;
    bool tared;
    double offset[LEP_AXES]; /* raw counts subtracted (mean of the tare samples) */
} cli_writer;

bool cli_parse_format(const char *s, cli_format *out);
bool cli_parse_units(const char *s, bool *si);
void cli_write_header(cli_writer *w);
void cli_write_sample(cli_writer *w, double t, const lep_sample *s);
/* A gap in the data: from = last t before, to = first t after (< 0: never resumed). */
void cli_write_gap(cli_writer *w, double from, double to, const char *reason);

/* ---- term.c: the user's terminal ---- */
/* Single keys from stdin without echo (stdin a terminal); false otherwise. */
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

/* ---- signals.c ---- */
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

/* ---- main.c ---- */
void cli_print_exit_codes(FILE *f);

/* ---- commands ---- */
int cli_cmd_list(int argc, char **argv);
int cli_cmd_info(int argc, char **argv);
int cli_cmd_read(int argc, char **argv);
int cli_cmd_stream(int argc, char **argv);
int cli_cmd_filter(int argc, char **argv);

#endif
