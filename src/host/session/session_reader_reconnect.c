/* Host session, the reader's loss and reconnection (session_reader.h):
 * without reconnect a lost stream ends (a sticky outcome for
 * lep_session_read), with reconnect the port is reopened with backoff,
 * re-synced and restarted, and must hold the sensor found at open. The
 * event, the counters and the stamps of a loss are the caller's. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <string.h>
#include <unistd.h>

#include "leptrino/error.h"
#include "posix_clock.h"
#include "session_reader.h"

void lep_priv_reader_lost(session_reader *rd, int error, double now)
{
    if (!rd->cfg.reconnect) {
        /* a data timeout is the stream lost; a port gone stays a disconnect */
        rd->failed = error == LEP_E_TIMEOUT ? LEP_E_LOST : error;
        return;
    }
    lep_priv_reader_disconnect(rd);
    rd->down_since = now;
    rd->port_missing = access(rd->cfg.port, F_OK) != 0;
    rd->backoff_ms = rd->cfg.reconnect_min_ms;
    rd->next_attempt = now + (double)rd->backoff_ms / 1000.0;
}

static bool same_sensor(const session_reader *rd, const lep_product_info *info)
{
    return strcmp(info->model, rd->first.model) == 0 && strcmp(info->serial, rd->first.serial) == 0;
}

/* One reconnection attempt: open, recover, restart the stream. */
static int attempt(session_reader *rd, lep_product_info *info, bool *identified)
{
    char err[256];
    int rc = lep_priv_reader_connect(rd, info, err, sizeof err);
    *identified = rc == LEP_OK;
    if (rc == LEP_OK && !same_sensor(rd, info)) {
        /* Another sensor on the port: its data is not this recording's
         * (other rated values, other frame). Stop here, clearly. */
        lep_priv_reader_disconnect(rd);
        rd->failed = LEP_E_UNEXPECTED;
        return READER_OTHER;
    }
    if (rc == LEP_OK)
        rc = lep_client_start(&rd->client);
    if (rc != LEP_OK) {
        /* a port that is not there: watch for it to come back (a replug) */
        rd->port_missing = rc == LEP_E_NOT_FOUND;
        lep_priv_reader_disconnect(rd);
        rd->backoff_ms = rd->backoff_ms * 2 > rd->cfg.reconnect_max_ms ? rd->cfg.reconnect_max_ms
                                                                       : rd->backoff_ms * 2;
        rd->next_attempt = lep_monotonic_seconds() + (double)rd->backoff_ms / 1000.0;
        return READER_NOT_YET;
    }
    rd->port_missing = false;
    return READER_RECONNECTED;
}

int lep_priv_reader_wait(session_reader *rd, double now, double deadline, lep_product_info *info,
                         bool *identified)
{
    double wake;
    *identified = false;
    if (rd->cfg.reconnect_give_up_ms >= 0 &&
        now - rd->down_since >= (double)rd->cfg.reconnect_give_up_ms / 1000.0) {
        rd->failed = LEP_E_DISCONNECTED;
        return READER_GAVE_UP;
    }
    /* Attempt when the backoff is over, or at once when a port that had
     * vanished is back (checked every SESSION_WATCH_S). */
    if (now < rd->next_attempt && !(rd->port_missing && access(rd->cfg.port, F_OK) == 0)) {
        wake = rd->next_attempt < deadline ? rd->next_attempt : deadline;
        if (rd->port_missing && wake > now + SESSION_WATCH_S)
            wake = now + SESSION_WATCH_S;
        lep_priv_sleep_until_ns((int64_t)(wake * 1e9));
        return lep_monotonic_seconds() < deadline ? READER_WAITED : READER_TIMED_OUT;
    }
    return attempt(rd, info, identified);
}
