/* The console's control events on Windows (cli.h, signals_posix.c's duty):
 * Ctrl-C, Ctrl-Break and closing the console window request a stop (the
 * first one; a second Ctrl-C or Ctrl-Break ends the program at once with
 * exit status 130, as a second SIGINT does on POSIX). Windows has no
 * SIGUSR1/SIGUSR2 or SIGWINCH: no tare, untare or resize requests come from
 * outside (docs/windows.md). SetConsoleCtrlHandler runs the handler in a
 * thread of its own (Microsoft docs, "HandlerRoutine callback function"),
 * hence the volatile flags. */
#include <windows.h>

#include "cli.h"

static volatile LONG stop_count = 0;

static BOOL WINAPI on_console_event(DWORD event)
{
    switch (event) {
    case CTRL_C_EVENT:
    case CTRL_BREAK_EVENT:
        if (InterlockedIncrement(&stop_count) > 1) {
            cli_term_restore_from_signal();
            ExitProcess(130);
        }
        return TRUE;
    case CTRL_CLOSE_EVENT:
    case CTRL_LOGOFF_EVENT:
    case CTRL_SHUTDOWN_EVENT:
        InterlockedIncrement(&stop_count);
        /* The process ends when this returns: give the loop time to stop. */
        Sleep(500);
        return TRUE;
    default:
        return FALSE;
    }
}

void cli_signals_install(void)
{
    (void)SetConsoleCtrlHandler(on_console_event, TRUE);
}

bool cli_stop_requested(void)
{
    return stop_count > 0;
}

unsigned cli_take_tare_requests(void)
{
    return 0;
}

unsigned cli_take_untare_requests(void)
{
    return 0;
}

bool cli_take_resize(void)
{
    return false;
}

void cli_sleep_ms(int ms)
{
    /* Sleep in slices so that a stop request is seen within 50 ms. */
    while (ms > 0 && !cli_stop_requested()) {
        int slice = ms < 50 ? ms : 50;
        Sleep((DWORD)slice);
        ms -= slice;
    }
}
