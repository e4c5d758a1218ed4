/* Host session, feeding: bytes read from the port stepped through the client
 * into samples, each stamped with its arrival (monotonic and UTC), checked
 * for gaps, counted, processed and kept as a row for the next read. */
#include <math.h>
#include <string.h>

#include "leptrino/error.h"
#include "session_priv.h"

/* Step bytes through the client; the samples they complete into got[]. */
static size_t step_samples(lep_session *s, const uint8_t *data, size_t len,
                           lep_sample got[SESSION_PENDING])
{
    size_t n = 0, off = 0;
    while (off < len) {
        size_t used = 0;
        int rc = lep_client_step(&s->client, data + off, len - off, &used);
        off += used;
        if (rc == LEP_STEP_SAMPLE && n < SESSION_PENDING &&
            lep_client_get_sample(&s->client, &got[n]) == LEP_OK)
            ++n;
        if (used == 0)
            break;
    }
    return n;
}

void lep_priv_session_feed(lep_session *s, const uint8_t *data, size_t len, double t_read)
{
    lep_sample got[SESSION_PENDING];
    uint32_t lost[SESSION_PENDING];
    lep_client_stats st;
    session_timing *tm = &s->tm;
    size_t n = step_samples(s, data, len, got), i;

    lep_client_get_stats(&s->client, &st);
    if (n > 0 && lep_priv_utc_may_have_moved(tm->utc_off, t_read)) {
        double fresh = lep_priv_utc_offset();
        if (fabs(fresh - tm->utc_off) > SESSION_UTC_STEP_S)
            tm->utc_off = fresh; /* the wall clock was set (NTP step, by hand) */
    }

    pthread_mutex_lock(&s->mu);
    lep_priv_sink_client(&s->sink, &st);
    if (n > 0) {
        timeline_verdict v;
        uint64_t j = 0, known = lep_priv_timing_seq(tm, s->sim != NULL, got, n, t_read,
                                                    s->nominal_hz, lost);
        size_t rows_before;
        lep_priv_timeline_read(&tm->tl, t_read, n, known, &v);
        lep_priv_timing_judged(s, &v);
        rows_before = lep_priv_sink_pending(&s->sink);
        for (i = 0; i < n; i++) {
            double t;
            uint8_t flags;
            j += lost[i];
            t = lep_priv_timeline_stamp(&tm->tl, j++);
            flags = lep_priv_timing_sample(s, lost[i], t);
            lep_priv_sink_received(&s->sink, t);
            if (lep_priv_sink_room(&s->sink))
                lep_priv_chain_sample(&s->chain, &s->sink, &got[i], t, t + tm->utc_off, t_read,
                                      flags);
            tm->last_sample_t = t;
        }
        if (v.extend) { /* too soon to judge */
            lep_priv_sink_hold(&s->sink, lep_priv_sink_held(&s->sink) +
                                             lep_priv_sink_pending(&s->sink) - rows_before);
        } else if (v.hold && lep_priv_sink_pending(&s->sink) > rows_before) {
            lep_priv_sink_hold(&s->sink, lep_priv_sink_pending(&s->sink) - rows_before);
            tm->suspect_index = lep_priv_sink_processed(&s->sink) - lep_priv_sink_held(&s->sink);
        } else if (v.hold) {
            lep_priv_timeline_forget_held(&tm->tl); /* nothing kept to hold */
        }
        tm->last_data_read_t = t_read;
    }
    tm->last_read_t = t_read;
    pthread_mutex_unlock(&s->mu);
}

void lep_priv_session_stream_reset(lep_session *s, double now)
{
    uint8_t left[LEP_CLIENT_RX_SIZE];
    lep_client_rx *rx = s->client.rx; /* the serial port's, attached by lep_serial_client_init */
    size_t n = 0;
    s->tm.last_read_t = now;
    s->tm.last_data_read_t = now;
    if (s->tm.last_sample_t > now)
        s->tm.last_sample_t = now;
    /* Bytes the client read past the start command's answer are stream data. */
    if (rx != NULL && rx->pos < rx->len) {
        n = (size_t)(rx->len - rx->pos);
        memcpy(left, rx->buf + rx->pos, n);
        rx->pos = rx->len;
    }
    if (n > 0)
        lep_priv_session_feed(s, left, n, now);
}
