/* Virtual sensor: when stream samples are due (absolute deadlines from the
 * stream start the device set) and sending them through the faults, or
 * skipping them. Called by the serving thread; calls the faults and the pty. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include "leptrino/error.h"
#include "sim_priv.h"

int64_t lep_priv_sim_deadline(const lep_sim *s, uint64_t k)
{
    return s->t0 + (int64_t)((double)(k + 1u) * s->period_ns);
}

void lep_priv_sim_stream_due(lep_sim *s, int64_t now)
{
    uint8_t code = lep_device_filter(&s->dev);
    if (code != s->fir_code) { /* a power cycle applied another filter */
        s->fir_state.primed = false;
        s->fir_code = code;
    }
    while (s->streaming && lep_priv_sim_deadline(s, s->k) <= now) {
        lep_sample smp;
        uint8_t frame[LEP_MAX_FRAME];
        size_t len;
        if (lep_priv_sim_queue_full(s)) { /* nobody reads: not even computed */
            s->st.samples_blocked++;
            s->k++;
            continue;
        }
        if (now - lep_priv_sim_deadline(s, s->k) > MAX_LAG_NS) {
            s->st.samples_skipped++;
            s->k++;
            continue;
        }
        int64_t due = lep_priv_sim_deadline(s, s->k);
        lep_priv_fir_next(&s->fir_state, &s->fir[code], &s->sig, s->k, &smp);
        smp.reserved = (uint16_t)(s->k & 0xFFFFu);
        s->k++;
        if (lep_device_stream_frame(&smp, frame, sizeof frame, &len) == LEP_OK) {
            uint64_t sent = s->st.samples_sent;
            lep_priv_sim_emit(s, frame, len, true, due); /* leaves at its time */
            if (s->st.samples_sent != sent)
                lep_priv_sim_trace_queued(s->trace, s->k - 1u, s->out_len);
        }
    }
}

/* Samples due during a stall are not sent later: skip them (a sequence gap). */
void lep_priv_sim_skip_due(lep_sim *s, int64_t now)
{
    while (s->streaming && lep_priv_sim_deadline(s, s->k) <= now) {
        s->st.samples_skipped++;
        s->k++;
    }
}
