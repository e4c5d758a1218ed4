/* Signals of the leptrino tool: SIGINT and SIGTERM only set a flag that the
 * stream loop checks; the handler does nothing else.
 *
 * SA_RESTART keeps an interrupted write() of the output going (no lost or
 * torn lines), while poll() and nanosleep() still return early with EINTR
 * (Linux and macOS never restart them), so the loop sees the flag at once.
 * SA_RESETHAND: a second Ctrl-C ends the program the default way, as an
 * escape when the output blocks forever (a reader that stopped reading). */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <signal.h>
#include <string.h>
#include <time.h>

#include "cli.h"

static volatile sig_atomic_t stop_flag = 0;

static void on_stop(int sig)
{
    (void)sig;
    stop_flag = 1;
}

void cli_signals_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = (int)(SA_RESTART | SA_RESETHAND); /* SA_RESETHAND is 0x80000000 on Linux */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = SIG_IGN;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGPIPE, &sa, NULL);
}

bool cli_stop_requested(void)
{
    return stop_flag != 0;
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
