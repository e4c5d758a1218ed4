/* Virtual sensor: fault injection on the way out (drop, garbage, corrupt) and
 * the NAK fault on the way in (the roll that withholds a command from the
 * device, and the NAK sent instead). Calls the pty's queue only. */
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
void lep_priv_sim_emit(lep_sim *s, const uint8_t *frame, size_t len, bool data, int64_t at)
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
        size_t flip = n + (size_t)(lep_priv_splitmix64(&s->rng) % len);
        buf[flip] ^= (uint8_t)(1u << (lep_priv_splitmix64(&s->rng) % 8u));
        s->st.bytes_corrupted++;
    }
    if (!lep_priv_sim_queue(s, buf, n + len, at)) {
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
    if (lep_priv_sim_queue(s, nak, sizeof nak, 0))
        s->st.naks++;
}

bool lep_priv_sim_nak_fault(lep_sim *s)
{
    if (!roll(s, s->opt.p_nak))
        return false;
    s->st.faked_naks++;
    lep_priv_sim_send_nak(s);
    return true;
}
