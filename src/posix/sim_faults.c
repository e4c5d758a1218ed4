/* Virtual sensor: fault injection on the way out (drop, garbage, corrupt) and
 * the NAK fault on the way in (a command withheld from the device). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <string.h>

#include "sim_priv.h"

static bool roll(lep_sim *s, double p)
{
    return p > 0 && lep_priv_uniform(&s->rng) < p;
}

/* Send a message frame, through the garbage/corrupt/drop faults. */
void lep_priv_sim_emit(lep_sim *s, const uint8_t *frame, size_t len, bool data)
{
    uint8_t buf[LEP_SIM_FRAME_ROOM];
    size_t n = 0;
    if (data && roll(s, s->opt.p_drop)) {
        s->st.samples_dropped++;
        return;
    }
    if (roll(s, s->opt.p_garbage)) {
        /* 1..8 bytes, never DLE, so they cannot swallow the frame that follows */
        size_t g = 1u + (size_t)(lep_priv_splitmix64(&s->rng) % 8u);
        while (n < g) {
            uint8_t b = (uint8_t)lep_priv_splitmix64(&s->rng);
            if (b != LEP_DLE)
                buf[n++] = b;
        }
    }
    memcpy(buf + n, frame, len);
    if (roll(s, s->opt.p_corrupt)) {
        size_t at = n + (size_t)(lep_priv_splitmix64(&s->rng) % len);
        buf[at] ^= (uint8_t)(1u << (lep_priv_splitmix64(&s->rng) % 8u));
        s->st.bytes_corrupted++;
    }
    if (!lep_priv_sim_queue(s, buf, n + len)) {
        if (data)
            s->st.samples_blocked++;
        return;
    }
    s->st.garbage_bytes += n;
    if (data)
        s->st.samples_sent++;
    else
        s->st.responses++;
}

void lep_priv_sim_send_nak(lep_sim *s)
{
    static const uint8_t nak[2] = { LEP_DLE, LEP_NAK };
    if (lep_priv_sim_queue(s, nak, sizeof nak))
        s->st.naks++;
}

static void flush_pend(lep_sim *s)
{
    if (s->pend_len > 0)
        lep_priv_sim_feed_device(s, s->pend, s->pend_len);
    s->pend_len = 0;
}

void lep_priv_sim_handle_input(lep_sim *s, const uint8_t *p, size_t len)
{
    while (len > 0) {
        lep_frame_event ev;
        size_t used = lep_frame_decoder_feed(&s->shadow, p, len, &ev);
        if (s->pend_len + used > PEND_SIZE)
            flush_pend(s);
        if (used > PEND_SIZE) { /* cannot happen: frames are bounded */
            lep_priv_sim_feed_device(s, p, used);
        } else {
            memcpy(s->pend + s->pend_len, p, used);
            s->pend_len += used;
        }
        p += used;
        len -= used;
        if (ev.type == LEP_FRAME_MESSAGE) {
            if (ev.len >= 3 && ev.msg[2] == LEP_CMD_SAMPLE)
                lep_priv_sim_handshake_sample(s);
            if (roll(s, s->opt.p_nak)) {
                s->pend_len = 0; /* the device never sees it */
                s->st.faked_naks++;
                lep_priv_sim_send_nak(s);
            } else {
                flush_pend(s);
            }
        } else if (ev.type != LEP_FRAME_NONE || !lep_frame_decoder_busy(&s->shadow)) {
            flush_pend(s);
        }
    }
}
