/* The user's terminal: single-key input without echo (restored on every
 * exit path, signals included), the window size, whether two streams share
 * one terminal, and text from a sensor made safe to print.
 *
 * The saved settings live in a static so that the signal handlers of
 * signals.c can restore them (tcsetattr is async-signal-safe). */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <signal.h>
#include <poll.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include "cli.h"

static struct termios saved_termios;
static volatile sig_atomic_t keys_on = 0;    /* saved_termios holds stdin's settings */
static volatile sig_atomic_t screen_fd = -1; /* the full-screen view is on this fd */

/* Leave the alternate screen and show the cursor again. */
static const char SCREEN_LEAVE[] = "\033[0m\033[?25h\033[?1049l";

bool cli_term_keys_begin(void)
{
    struct termios t;
    pid_t fg;
    if (keys_on)
        return true;
    if (isatty(STDIN_FILENO) != 1 || tcgetattr(STDIN_FILENO, &saved_termios) != 0)
        return false;
    /* Only in the foreground: a background job (`leptrino stream ... &`)
     * that changed the terminal would be stopped by SIGTTOU. */
    fg = tcgetpgrp(STDIN_FILENO); /* -1: not our controlling terminal, no job control */
    if (fg >= 0 && fg != getpgrp())
        return false;
    t = saved_termios;
    /* No line buffering, no echo; ISIG stays so Ctrl-C is still SIGINT, and
     * the output settings are untouched (\n still moves to column 0). */
    t.c_lflag &= (tcflag_t) ~(ICANON | ECHO);
    t.c_cc[VMIN] = 0;
    t.c_cc[VTIME] = 0;
    if (tcsetattr(STDIN_FILENO, TCSANOW, &t) != 0)
        return false;
    keys_on = 1;
    return true;
}

void cli_term_keys_end(void)
{
    if (keys_on) {
        tcsetattr(STDIN_FILENO, TCSANOW, &saved_termios);
        keys_on = 0;
    }
}

void cli_term_screen_begin(int fd)
{
    static const char enter[] = "\033[?1049h\033[?25l\033[2J\033[H";
    if (screen_fd >= 0)
        return;
    screen_fd = fd;
    (void)!write(fd, enter, sizeof enter - 1);
}

void cli_term_screen_end(void)
{
    if (screen_fd >= 0) {
        (void)!write(screen_fd, SCREEN_LEAVE, sizeof SCREEN_LEAVE - 1);
        screen_fd = -1;
    }
}

void cli_term_restore_from_signal(void)
{
    if (screen_fd >= 0)
        (void)!write(screen_fd, SCREEN_LEAVE, sizeof SCREEN_LEAVE - 1);
    if (keys_on)
        tcsetattr(STDIN_FILENO, TCSANOW, &saved_termios);
}

int cli_term_read_key(void)
{
    unsigned char c;
    ssize_t n;
    if (!keys_on)
        return -1;
    n = read(STDIN_FILENO, &c, 1);
    return n == 1 ? (int)c : -1;
}

bool cli_term_status_ok(int out_fd)
{
    pid_t fg = tcgetpgrp(STDERR_FILENO); /* -1: not our controlling terminal */
    return isatty(STDERR_FILENO) == 1 && (fg < 0 || fg == getpgrp()) &&
           (out_fd < 0 || !cli_term_same_tty(out_fd, STDERR_FILENO));
}

bool cli_term_same_tty(int fd_a, int fd_b)
{
    struct stat a, b;
    if (isatty(fd_a) != 1 || isatty(fd_b) != 1)
        return false;
    if (fstat(fd_a, &a) != 0 || fstat(fd_b, &b) != 0)
        return true; /* cannot tell: assume the worst */
    return a.st_rdev == b.st_rdev;
}

void cli_term_size(int fd, int *cols, int *rows)
{
    struct winsize ws;
    *cols = 80;
    *rows = 24;
    if (ioctl(fd, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 && ws.ws_row > 0) {
        *cols = ws.ws_col;
        *rows = ws.ws_row;
    }
}

int cli_wait_input(const int *fds, size_t n, bool *ready, int timeout_ms)
{
    struct pollfd p[CLI_MAX_SENSORS + 1];
    size_t i;
    int rc;
    if (n > CLI_MAX_SENSORS + 1)
        n = CLI_MAX_SENSORS + 1;
    for (i = 0; i < n; ++i) {
        p[i].fd = fds[i];
        p[i].events = POLLIN;
        p[i].revents = 0;
    }
    rc = poll(p, (nfds_t)n, timeout_ms);
    for (i = 0; i < n; ++i)
        ready[i] = rc > 0 && p[i].fd >= 0 && p[i].revents != 0;
    return rc < 0 && errno != EINTR ? -1 : (rc < 0 ? 0 : rc);
}
