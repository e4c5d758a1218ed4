/* Live status line of `leptrino stream` on stderr, redrawn in place at most
 * about four times per second.
 *
 * It is drawn only when stderr is a terminal that the data does not go to:
 * when stdout and stderr are the same terminal (`make demo`), a line
 * rewritten with \r would land in the middle of the data rows, so there is
 * none, and only the summary is printed after the last row. Nor is there
 * one for a background job, which would draw over the shell's prompt. */
#include "cli.h"

#define CLI_STATUS_PERIOD_S 0.25

void cli_status_init(cli_status *st, int out_fd)
{
    st->enabled = cli_term_status_ok(out_fd);
    st->drawn = false;
    st->last_draw = -1.0;
}

void cli_status_update(cli_status *st, double now, const char *text)
{
    if (!st->enabled)
        return;
    if (st->last_draw >= 0.0 && now - st->last_draw < CLI_STATUS_PERIOD_S)
        return;
    st->last_draw = now;
    /* \r then erase to end of line: the line is rewritten in place. */
    fprintf(stderr, "\r\033[K%s", text);
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
