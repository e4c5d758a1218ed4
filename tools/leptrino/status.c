/* Live status line of `leptrino stream` on stderr: drawn only when stderr is
 * a terminal, redrawn at most about four times per second. */
#define _POSIX_C_SOURCE 200809L

#include <unistd.h>

#include "cli.h"

#define CLI_STATUS_PERIOD_S 0.25

void cli_status_init(cli_status *st)
{
    st->enabled = isatty(STDERR_FILENO) == 1;
    st->drawn = false;
    st->last_draw = -1.0;
    st->last_elapsed = 0.0;
    st->last_samples = 0;
    st->hz = 0.0;
}

void cli_status_update(cli_status *st, double elapsed, uint64_t samples, uint64_t errors,
                       uint64_t overloads, const char *note)
{
    if (!st->enabled)
        return;
    if (st->last_draw >= 0.0 && elapsed - st->last_draw < CLI_STATUS_PERIOD_S)
        return;
    if (elapsed > st->last_elapsed && st->last_draw >= 0.0)
        st->hz = (double)(samples - st->last_samples) / (elapsed - st->last_elapsed);
    st->last_elapsed = elapsed;
    st->last_samples = samples;
    st->last_draw = elapsed;
    /* \r then erase to end of line: the line is rewritten in place. */
    fprintf(stderr, "\r\033[K%llu samples  %7.1f Hz  %llu errors  %llu overloads  %.1f s%s%s",
            (unsigned long long)samples, st->hz, (unsigned long long)errors,
            (unsigned long long)overloads, elapsed, note != NULL ? "  " : "",
            note != NULL ? note : "");
    fflush(stderr);
    st->drawn = true;
}

void cli_status_clear(cli_status *st)
{
    if (st->enabled && st->drawn) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
        st->drawn = false;
    }
}
