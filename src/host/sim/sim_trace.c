/* Virtual sensor: the write trace. For each data frame, the CLOCK_MONOTONIC
 * times just before and just after the write() that handed its last byte to
 * the pty, keyed by its stream index k, so a benchmark can measure latency
 * from the write (not from the deadline, which adds the sim's own wake-up
 * lateness). Records are buffered and written in blocks, so tracing adds
 * about one file write per TRACE_BUF samples to the serving thread. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "posix_clock.h"
#include "sim_priv.h"

/* Frames that can wait in the output queue: it holds at most OUTQ_SIZE
 * bytes, and a data frame is at least 25. */
#define TRACE_QUEUED (OUTQ_SIZE / 25u + 1u)

struct lep_sim_trace {
    int fd;
    size_t queued_n; /* data frames in the output queue, oldest first */
    uint64_t queued_k[TRACE_QUEUED];
    size_t queued_end[TRACE_QUEUED]; /* offset just past the frame in s->out */
    size_t buf_n;
    lep_sim_trace_record buf[LEP_SIM_TRACE_BUF];
    bool broken; /* a write to the trace file failed: tracing stopped */
};

static void trace_flush(lep_sim_trace *t)
{
    size_t off = 0, len = t->buf_n * sizeof t->buf[0];
    const uint8_t *p = (const uint8_t *)t->buf;
    while (off < len && !t->broken) {
        ssize_t n = write(t->fd, p + off, len - off);
        if (n > 0)
            off += (size_t)n;
        else if (!(n < 0 && errno == EINTR))
            t->broken = true;
    }
    t->buf_n = 0;
}

static void trace_put(lep_sim_trace *t, uint64_t k, int64_t t_call, int64_t t_return)
{
    lep_sim_trace_record *r;
    if (t->broken)
        return;
    r = &t->buf[t->buf_n++];
    r->k = k;
    r->t_call_ns = t_call;
    r->t_return_ns = t_return;
    if (t->buf_n == LEP_SIM_TRACE_BUF)
        trace_flush(t);
}

int lep_priv_sim_trace_open(const char *path, lep_sim_trace **out, char *err, size_t errlen)
{
    lep_sim_trace *t;
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) {
        lep_priv_set_err(err, errlen, "write trace %s: %s%s", path, strerror(errno),
                         errno == EEXIST ? " (an existing file is never replaced)" : "");
        return errno == EEXIST ? LEP_E_BUSY : LEP_E_IO;
    }
    t = calloc(1, sizeof *t);
    if (t == NULL) {
        close(fd);
        (void)unlink(path);
        lep_priv_set_err(err, errlen, "write trace %s: out of memory", path);
        return LEP_E_IO;
    }
    t->fd = fd;
    *out = t;
    return LEP_OK;
}

void lep_priv_sim_trace_close(lep_sim_trace *t)
{
    if (t == NULL)
        return;
    trace_flush(t);
    close(t->fd);
    free(t);
}

void lep_priv_sim_trace_mark(lep_sim_trace *t, uint64_t marker, int64_t when)
{
    if (t == NULL)
        return;
    trace_put(t, marker, when, when);
    if (marker == LEP_SIM_TRACE_END)
        trace_flush(t); /* complete before the stop command's answer goes out */
}

void lep_priv_sim_trace_queued(lep_sim_trace *t, uint64_t k, size_t end)
{
    if (t == NULL || t->queued_n == TRACE_QUEUED)
        return;
    t->queued_k[t->queued_n] = k;
    t->queued_end[t->queued_n] = end;
    t->queued_n++;
}

void lep_priv_sim_trace_written(lep_sim_trace *t, size_t n, int64_t t_call, int64_t t_return)
{
    size_t done = 0, i;
    if (t == NULL)
        return;
    while (done < t->queued_n && t->queued_end[done] <= n) {
        trace_put(t, t->queued_k[done], t_call, t_return);
        done++;
    }
    for (i = done; i < t->queued_n; i++) {
        t->queued_k[i - done] = t->queued_k[i];
        t->queued_end[i - done] = t->queued_end[i] - n;
    }
    t->queued_n -= done;
}

void lep_priv_sim_trace_discard(lep_sim_trace *t)
{
    if (t != NULL)
        t->queued_n = 0;
}
