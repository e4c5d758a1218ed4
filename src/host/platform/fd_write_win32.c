/* File descriptors on Windows (fd_write.h): the C runtime's _open/_write/
 * _close over Win32 handles. Descriptors there block (no O_NONBLOCK), so a
 * write takes every byte or fails; the deadline is not needed. Files are
 * opened _O_BINARY (the same bytes as on POSIX, no CR added) and _O_NOINHERIT
 * (not passed to child processes, as O_CLOEXEC). */
#include <errno.h>
#include <fcntl.h>
#include <io.h>
#include <limits.h>
#include <sys/stat.h>

#include "fd_write.h"

int lep_priv_write_all(int fd, const void *data, size_t len, int64_t deadline_ns)
{
    const unsigned char *p = data;
    size_t off = 0;
    (void)deadline_ns;
    while (off < len) {
        size_t chunk = len - off;
        int n;
        if (chunk > (size_t)INT_MAX)
            chunk = (size_t)INT_MAX;
        n = _write(fd, p + off, (unsigned)chunk);
        if (n > 0) {
            off += (size_t)n;
            continue;
        }
        if (n < 0 && errno == EPIPE)
            return LEP_PRIV_WRITE_HANGUP;
        if (n == 0)
            errno = 0;
        return LEP_PRIV_WRITE_FAILED;
    }
    return LEP_PRIV_WRITE_OK;
}

int lep_priv_fd_create(const char *path, int overwrite)
{
    return _open(path,
                 _O_WRONLY | _O_CREAT | _O_BINARY | _O_NOINHERIT | (overwrite ? _O_TRUNC : _O_EXCL),
                 _S_IREAD | _S_IWRITE);
}

int lep_priv_fd_is_regular(int fd)
{
    struct _stat64 sb;
    return _fstat64(fd, &sb) == 0 && (sb.st_mode & _S_IFMT) == _S_IFREG ? 1 : 0;
}

int lep_priv_fd_close(int fd)
{
    return _close(fd);
}
