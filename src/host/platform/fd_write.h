/* Private: writing a whole buffer to a file descriptor that may be non-blocking. */
#ifndef LEPTRINO_FD_WRITE_H
#define LEPTRINO_FD_WRITE_H

#include <stddef.h>
#include <stdint.h>

enum lep_priv_write_result {
    LEP_PRIV_WRITE_OK = 0,  /* every byte was written */
    LEP_PRIV_WRITE_TIMEOUT, /* the deadline passed while fd would not take more (errno ETIMEDOUT) */
    LEP_PRIV_WRITE_HANGUP,  /* poll reported POLLHUP or POLLERR on fd (errno EPIPE) */
    LEP_PRIV_WRITE_FAILED,  /* write() failed (errno is its error) or took nothing (errno 0) */
    LEP_PRIV_WRITE_POLL_FAILED /* poll() failed (errno is its error) or reported POLLNVAL (EBADF) */
};

/* Write data[0..len) to fd. Retries after EINTR; after EAGAIN/EWOULDBLOCK it
 * waits in poll() for POLLOUT, until deadline_ns (CLOCK_MONOTONIC, as
 * lep_priv_monotonic_ns) or without end when deadline_ns is negative. Blocks
 * at most until the deadline. On failure some bytes may have been written.
 * Returns an enum lep_priv_write_result; errno is set as stated there. */
int lep_priv_write_all(int fd, const void *data, size_t len, int64_t deadline_ns);

#endif
