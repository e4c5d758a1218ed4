/* Writing a whole buffer to a possibly non-blocking file descriptor (fd_write.h). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include "fd_write.h"

#include <errno.h>
#include <poll.h>
#include <unistd.h>

#include "posix_clock.h"

int lep_priv_write_all(int fd, const void *data, size_t len, int64_t deadline_ns)
{
    const unsigned char *p = data;
    size_t off = 0;
    while (off < len) {
        ssize_t n = write(fd, p + off, len - off);
        if (n > 0) {
            off += (size_t)n;
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            struct pollfd q;
            int r, wait = deadline_ns < 0 ? -1 : lep_priv_ms_left(deadline_ns);
            if (wait == 0) {
                errno = ETIMEDOUT;
                return LEP_PRIV_WRITE_TIMEOUT;
            }
            q.fd = fd;
            q.events = POLLOUT;
            q.revents = 0;
            r = poll(&q, 1, wait);
            if (r < 0 && errno != EINTR)
                return LEP_PRIV_WRITE_POLL_FAILED;
            if (r > 0 && (q.revents & (POLLHUP | POLLERR))) {
                errno = EPIPE;
                return LEP_PRIV_WRITE_HANGUP;
            }
            if (r > 0 && (q.revents & POLLNVAL)) {
                errno = EBADF;
                return LEP_PRIV_WRITE_POLL_FAILED;
            }
            continue;
        }
        if (n == 0)
            errno = 0;
        return LEP_PRIV_WRITE_FAILED;
    }
    return LEP_PRIV_WRITE_OK;
}
