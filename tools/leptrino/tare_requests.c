/* What the user asks of the tare while a stream runs, written once for
 * `stream` and `watch`: the keys t (tare) and u (untare) on the terminal and
 * the signals SIGUSR1 (tare) and SIGUSR2 (untare), taken together, and q
 * (quit, for the commands that stop on it). The session does the tare. */
#include "cli.h"

cli_tare_asks cli_take_tare_asks(void)
{
    cli_tare_asks a;
    int key;
    a.tare = cli_take_tare_requests() > 0;
    a.untare = cli_take_untare_requests() > 0;
    a.quit = false;
    while ((key = cli_term_read_key()) >= 0) {
        if (key == 't' || key == 'T')
            a.tare = true;
        else if (key == 'u' || key == 'U')
            a.untare = true;
        else if (key == 'q' || key == 'Q')
            a.quit = true;
    }
    return a;
}

void cli_tare_apply(lep_session *s, cli_tare_asks a, unsigned samples)
{
    if (a.untare)
        lep_session_untare(s);
    if (a.tare) /* after an untare asked with it: the new tare is the last word */
        lep_session_tare(s, (int)samples, 0.0);
}
