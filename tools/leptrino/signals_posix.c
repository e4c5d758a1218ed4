/* Signals of the leptrino tool. The handlers only set flags that the loops
 * check (and, on the way out, restore the terminal):
 *   SIGINT, SIGTERM, SIGHUP  stop (the first one; a second SIGINT/SIGTERM
 *                            restores the terminal and ends the program the
 *                            default way, an escape when the output blocks)
 *   SIGUSR1 / SIGUSR2        tare / untare requests (counted)
 *   SIGWINCH                 the terminal was resized
 *   SIGQUIT                  restore the terminal, then the default action
 *   SIGPIPE                  ignored: a closed output is a write error (EPIPE)
 *
 * SA_RESTART keeps an interrupted write() of the output going (no lost or
 * torn lines), while poll() and nanosleep() still return early with EINTR
 * (Linux and macOS never restart them), so the loop sees the flag at once. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <signal.h>
#include <string.h>
#include <time.h>

#include "cli.h"

static volatile sig_atomic_t stop_count = 0;
static volatile sig_atomic_t tare_requests = 0;
static volatile sig_atomic_t untare_requests = 0;
static volatile sig_atomic_t resized = 0;

static void die_by(int sig)
{
    struct sigaction sa;
    cli_term_restore_from_signal();
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = SIG_DFL;
    sigemptyset(&sa.sa_mask);
    sigaction(sig, &sa, NULL);
    raise(sig);
}

static void on_signal(int sig)
{
    int saved = errno;
    switch (sig) {
    case SIGUSR1:
        tare_requests++;
        break;
    case SIGUSR2:
        untare_requests++;
        break;
    case SIGWINCH:
        resized = 1;
        break;
    case SIGQUIT:
        die_by(sig);
        break;
    default: /* SIGINT, SIGTERM, SIGHUP */
        if (stop_count > 0 && sig != SIGHUP)
            die_by(sig);
        stop_count++;
        break;
    }
    errno = saved;
}

static void handle(int sig, void (*fn)(int), int flags)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = fn;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = flags;
    sigaction(sig, &sa, NULL);
}

void cli_signals_install(void)
{
    handle(SIGINT, on_signal, SA_RESTART);
    handle(SIGTERM, on_signal, SA_RESTART);
    handle(SIGHUP, on_signal, SA_RESTART);
    handle(SIGQUIT, on_signal, SA_RESTART);
    handle(SIGUSR1, on_signal, SA_RESTART);
    handle(SIGUSR2, on_signal, SA_RESTART);
    handle(SIGWINCH, on_signal, SA_RESTART);
    handle(SIGPIPE, SIG_IGN, 0);
}

bool cli_stop_requested(void)
{
    return stop_count != 0;
}

/* The handlers only count up; the loop remembers what it has seen, so a
 * signal arriving while it looks is never lost. */
unsigned cli_take_tare_requests(void)
{
    static sig_atomic_t seen = 0;
    sig_atomic_t now = tare_requests;
    unsigned n = (unsigned)(now - seen);
    seen = now;
    return n;
}

unsigned cli_take_untare_requests(void)
{
    static sig_atomic_t seen = 0;
    sig_atomic_t now = untare_requests;
    unsigned n = (unsigned)(now - seen);
    seen = now;
    return n;
}

bool cli_take_resize(void)
{
    bool r = resized != 0;
    resized = 0;
    return r;
}

void cli_sleep_ms(int ms)
{
    /* Sleep in slices so that a stop request is seen within 50 ms. */
    while (ms > 0 && !cli_stop_requested()) {
        int slice = ms < 50 ? ms : 50;
        struct timespec ts;
        ts.tv_sec = 0;
        ts.tv_nsec = (long)slice * 1000000L;
        while (nanosleep(&ts, &ts) != 0 && errno == EINTR && !cli_stop_requested()) {
        }
        ms -= slice;
    }
}
