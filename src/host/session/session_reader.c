/* Host session, the reader (session_reader.h): the port (open, start-up
 * recovery and identity of the sensor on it, close), the stream's start and
 * stop on it, bytes stepped into samples, and the read of a call with a
 * latency budget. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <math.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "posix_clock.h"
#include "session_clock.h"
#include "session_reader.h"

/* A read with a latency budget sleeps most of the budget out, drains the
 * port, then waits for the next arrival: seen at once, it is a point on the
 * sensor's clock as close as an unbudgeted read's. A drain alone returns at
 * a time unrelated to the newest sample's arrival: up to a packet after it,
 * and in lockstep with the stream when the budget is a whole number of
 * periods. The drain comes PROBE_SHARE of the budget (at most PROBE_MAX_S)
 * before the budget ends, less up to half of that by a golden-ratio dither,
 * so that successive probes see every phase of a transport's packets (1 ms
 * USB frames against a 1.2 kHz sample period repeat every 5 ms; an FTDI
 * adapter's 62-byte packets come every 2 ms). The probe takes up to
 * PROBE_ARRIVALS arrivals one by one, waiting at most until the budget
 * ends: each a point as tight as the transport allows, of a packet phase of
 * its own. PROBE_ARRIVALS wake-ups more per budget; made when that leaves
 * the probe PROBE_MIN_PERIODS periods or more. */
#define PROBE_SHARE 0.25
#define PROBE_MAX_S 0.02
#define PROBE_MIN_PERIODS 2.0
#define PROBE_ARRIVALS 4
#define GOLDEN_FRACTION 0.6180339887498949

/* Where a call with a latency budget is. */
enum budget_stage {
    BUDGET_AWAKE,   /* not slept yet */
    BUDGET_SLEPT,   /* slept out the budget: draining without waiting */
    BUDGET_DRAINED, /* the port found empty: the next read waits for a frame */
    BUDGET_PROBING, /* that read is made */
    BUDGET_DONE     /* the budgeted read is made: deliver */
};

void lep_priv_reader_init(session_reader *rd, const reader_config *cfg)
{
    memset(rd, 0, sizeof *rd);
    rd->cfg = *cfg;
}

void lep_priv_reader_set_rate(session_reader *rd, double nominal_hz)
{
    rd->cfg.nominal_hz = nominal_hz;
}

int lep_priv_reader_connect(session_reader *rd, lep_product_info *info, char *err, size_t errlen)
{
    const reader_config *cfg = &rd->cfg;
    int rc = lep_serial_open(cfg->port, &rd->serial, err, errlen);
    if (rc != LEP_OK) {
        rd->serial = NULL;
        return rc;
    }
    rc = lep_serial_client_init(&rd->client, rd->serial);
    if (rc == LEP_OK)
        rc = lep_client_set_timeout(&rd->client, cfg->timeout_ms);
    if (rc == LEP_OK)
        rc = lep_client_set_retries(&rd->client, cfg->retries);
    if (rc == LEP_OK)
        rc = lep_client_sync(&rd->client, cfg->sync_quiet_ms > 0 ? cfg->sync_quiet_ms : 1, info);
    if (rc != LEP_OK) {
        lep_priv_set_err(err, errlen, "%s: start-up recovery (stop, drain, product info): %s",
                         cfg->port, lep_strerror(rc));
        lep_priv_reader_disconnect(rd);
        return rc;
    }
    if (!rd->identified) {
        rd->first = *info;
        rd->identified = true;
    }
    rd->up = true;
    return LEP_OK;
}

void lep_priv_reader_disconnect(session_reader *rd)
{
    lep_serial_close(rd->serial);
    rd->serial = NULL;
    rd->up = false;
}

bool lep_priv_reader_up(const session_reader *rd)
{
    return rd->up;
}

lep_client *lep_priv_reader_client(session_reader *rd)
{
    return rd->up ? &rd->client : NULL;
}

int lep_priv_reader_serial_info(const session_reader *rd, lep_serial_info *out)
{
    if (!rd->up)
        return LEP_E_DISCONNECTED;
    lep_serial_get_latency_info(rd->serial, out);
    return LEP_OK;
}

int lep_priv_reader_fd(const session_reader *rd)
{
    return rd->up ? lep_serial_fd(rd->serial) : -1;
}

void lep_priv_reader_stats(const session_reader *rd, lep_client_stats *st)
{
    lep_client_get_stats(&rd->client, st);
}

int lep_priv_reader_start(session_reader *rd)
{
    if (!rd->up)
        return LEP_E_DISCONNECTED;
    return lep_client_start(&rd->client);
}

size_t lep_priv_reader_resume(session_reader *rd, double now, uint8_t left[LEP_CLIENT_RX_SIZE])
{
    lep_client_rx *rx = rd->client.rx; /* the serial port's, attached by lep_serial_client_init */
    size_t n = 0;
    rd->failed = 0;
    rd->backlog = false;
    rd->last_read_t = now;
    rd->last_data_read_t = now;
    /* Bytes the client read past the start command's answer are stream data. */
    if (rx != NULL && rx->pos < rx->len) {
        n = (size_t)(rx->len - rx->pos);
        memcpy(left, rx->buf + rx->pos, n);
        rx->pos = rx->len;
    }
    return n;
}

int lep_priv_reader_stop(session_reader *rd)
{
    int rc = LEP_OK;
    if (rd->up && lep_client_streaming(&rd->client)) {
        rc = lep_client_stop(&rd->client);
        /* one more try, e.g. after a lost answer; not after a silence that
         * already lost the stream (it would only double the wait) */
        if (rc != LEP_OK && rc != LEP_E_DISCONNECTED && rd->failed != LEP_E_LOST)
            rc = lep_client_stop(&rd->client);
    }
    return rc == LEP_E_DISCONNECTED ? LEP_OK : rc;
}

int lep_priv_reader_sample(session_reader *rd, lep_sample *smp)
{
    if (!rd->up)
        return LEP_E_DISCONNECTED;
    return lep_client_sample(&rd->client, smp);
}

size_t lep_priv_reader_samples(session_reader *rd, const uint8_t *data, size_t len,
                               lep_sample got[SESSION_PENDING], double t_read)
{
    size_t n = 0, off = 0;
    while (off < len) {
        size_t used = 0;
        int rc = lep_client_step(&rd->client, data + off, len - off, &used);
        off += used;
        if (rc == LEP_STEP_SAMPLE && n < SESSION_PENDING &&
            lep_client_get_sample(&rd->client, &got[n]) == LEP_OK)
            ++n;
        if (used == 0)
            break;
    }
    if (n > 0)
        rd->last_data_read_t = t_read;
    return n;
}

int lep_priv_reader_failed(const session_reader *rd)
{
    return rd->failed;
}

/* ---- a read call's budget ---- */

void lep_priv_reader_call(const session_reader *rd, reader_call *c, int latency_ms, int timeout_ms)
{
    /* Never sleep longer than the kernel can buffer for us. */
    double kernel_s = SESSION_KERNEL_BYTES / (rd->cfg.nominal_hz * SESSION_MIN_FRAME);
    memset(c, 0, sizeof *c);
    c->stage = BUDGET_AWAKE;
    c->budget = (double)latency_ms / 1000.0;
    if (c->budget > kernel_s)
        c->budget = kernel_s;
    c->probe = c->budget * PROBE_SHARE < PROBE_MAX_S ? c->budget * PROBE_SHARE : PROBE_MAX_S;
    if (c->probe < PROBE_MIN_PERIODS / rd->cfg.nominal_hz)
        c->probe = 0.0;
    c->deadline = timeout_ms < 0 ? INFINITY : lep_monotonic_seconds() + (double)timeout_ms / 1000.0;
}

static double data_deadline(const session_reader *rd)
{
    return rd->last_data_read_t + (double)rd->cfg.data_timeout_ms / 1000.0;
}

const uint8_t *lep_priv_reader_bytes(const session_reader *rd)
{
    return rd->rbuf;
}

bool lep_priv_reader_silent(const session_reader *rd, double now)
{
    return now >= data_deadline(rd);
}

bool lep_priv_reader_call_over(const session_reader *rd, const reader_call *c, double now,
                               bool rows, double first)
{
    return !rd->backlog &&
           (c->budget <= 0.0 || !rows || c->stage == BUDGET_DONE || now >= first + c->budget);
}

/* How long the next port read may wait, ms; with a budget, sleep it out first. */
static int port_wait(session_reader *rd, reader_call *c, double now, bool got, double first,
                     bool holding)
{
    double period_s = 1.0 / rd->cfg.nominal_hz;
    double wake, dd = data_deadline(rd);
    if (rd->backlog)
        return 0; /* the last read filled the buffer: more is waiting, take it now */
    if (c->budget <= 0.0)
        return lep_priv_ms_until(c->deadline < dd ? c->deadline : dd, now);
    if (c->stage == BUDGET_DRAINED) {
        /* the port is empty: the next arrival is seen at once */
        wake = c->wake > now + PROBE_MIN_PERIODS * period_s ? c->wake
                                                            : now + PROBE_MIN_PERIODS * period_s;
        c->stage = BUDGET_PROBING;
        return lep_priv_ms_until(wake < c->deadline ? wake : c->deadline, now);
    }
    /* Save wake-ups: sleep until the budget is spent (less the probe's
     * share), then take everything in reads that do not wait. */
    wake = got ? first + c->budget : rd->last_read_t + c->budget;
    if (holding && wake > rd->last_read_t + SESSION_CONFIRM_S)
        wake = rd->last_read_t + SESSION_CONFIRM_S; /* judge a suspected hole soon */
    if (wake > c->deadline)
        wake = c->deadline;
    if (wake > dd)
        wake = dd;
    c->wake = wake;
    if (c->probe > 0.0) {
        rd->probes++;
        wake -= c->probe * (1.0 - 0.5 * fmod((double)rd->probes * GOLDEN_FRACTION, 1.0));
    }
    lep_priv_sleep_until_ns((int64_t)(wake * 1e9));
    c->stage = BUDGET_SLEPT;
    return 0;
}

int lep_priv_reader_read(session_reader *rd, reader_call *c, double now, bool got, double first,
                         bool holding, double *t)
{
    int wait = port_wait(rd, c, now, got, first, holding);
    int rc = rd->client.io.read(rd->client.io.user, rd->rbuf, sizeof rd->rbuf, wait);
    *t = lep_monotonic_seconds();
    /* More may be waiting: a read returns at most what the tty layer holds
     * (4 KiB on Linux), so with a budget, read until one comes back empty;
     * without, only after a read that filled the buffer. */
    rd->backlog =
        rc == (int)sizeof rd->rbuf || (c->budget > 0.0 && rc > 0 && c->stage == BUDGET_SLEPT);
    if (rc == 0 && c->stage == BUDGET_SLEPT) {
        c->stage = c->probe > 0.0 ? BUDGET_DRAINED : BUDGET_DONE;
        c->arrivals = PROBE_ARRIVALS;
    } else if (c->stage == BUDGET_PROBING) {
        /* another arrival while the budget lasts, or done */
        c->stage = rc > 0 && --c->arrivals > 0 && *t < c->wake ? BUDGET_DRAINED : BUDGET_DONE;
    }
    if (rc >= 0)
        rd->last_read_t = *t;
    return rc;
}
