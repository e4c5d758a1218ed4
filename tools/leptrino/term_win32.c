/* The user's terminal on Windows (cli.h, term_posix.c's duty). Single keys
 * while streaming (t, u) and the full-screen view of `watch` are not there
 * yet: cli_term_keys_begin says no, and `watch` says so itself
 * (cmd_watch_win32.c). A status line is drawn when stderr is a console and
 * standard output is not the same console. */
#include <io.h>
#include <windows.h>

#include "cli.h"

bool cli_term_keys_begin(void)
{
    return false;
}

void cli_term_keys_end(void)
{
}

int cli_term_read_key(void)
{
    return -1;
}

void cli_term_screen_begin(int fd)
{
    (void)fd;
}

void cli_term_screen_end(void)
{
}

void cli_term_restore_from_signal(void)
{
}

bool cli_term_same_tty(int fd_a, int fd_b)
{
    /* Two console descriptors are the one console of the process. */
    return _isatty(fd_a) != 0 && _isatty(fd_b) != 0;
}

bool cli_term_status_ok(int out_fd)
{
    return _isatty(2) != 0 && (out_fd < 0 || !cli_term_same_tty(out_fd, 2));
}

void cli_term_size(int fd, int *cols, int *rows)
{
    CONSOLE_SCREEN_BUFFER_INFO info;
    HANDLE h = (HANDLE)_get_osfhandle(fd);
    *cols = 80;
    *rows = 24;
    if (h != INVALID_HANDLE_VALUE && GetConsoleScreenBufferInfo(h, &info)) {
        *cols = info.srWindow.Right - info.srWindow.Left + 1;
        *rows = info.srWindow.Bottom - info.srWindow.Top + 1;
    }
}

int cli_wait_input(const int *fds, size_t n, bool *ready, int timeout_ms)
{
    /* No descriptor to wait on (a COM port is a HANDLE; lep_session_fd is
     * -1): a short sleep, then every source is read without waiting. */
    size_t i;
    int count = 0;
    Sleep((DWORD)(timeout_ms < 0 ? 10 : timeout_ms < 10 ? timeout_ms : 10));
    for (i = 0; i < n; ++i) {
        ready[i] = fds[i] >= 0;
        count += ready[i] ? 1 : 0;
    }
    return count;
}
