/* Virtual sensor: the output queue (messages made, not yet written to the
 * port by sim_pty.c or sim_link_win32.c) and the transport between the two
 * (sim_transport.c: which of the queued bytes the port may have by now). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE /* PATH_MAX */
#endif

#include <string.h>

#include "posix_clock.h"
#include "sim_priv.h"

void lep_priv_sim_queue_init(lep_sim *s)
{
    int mode = s->opt.usb_packets           ? SIM_TRANSPORT_USB
               : s->opt.ftdi_latency_ms > 0 ? SIM_TRANSPORT_FTDI
                                            : SIM_TRANSPORT_NONE;
    s->out_len = 0;
    lep_priv_sim_transport_init(&s->tr, mode, s->opt.ftdi_latency_ms);
}

bool lep_priv_sim_queue_full(const lep_sim *s)
{
    return s->out_len + LEP_SIM_FRAME_ROOM > OUTQ_SIZE;
}

bool lep_priv_sim_queue(lep_sim *s, const uint8_t *b, size_t n, int64_t at)
{
    if (s->out_len + n > OUTQ_SIZE)
        return false;
    memcpy(s->out + s->out_len, b, n);
    s->out_len += n;
    if (s->tr.mode != SIM_TRANSPORT_NONE && at == 0)
        at = lep_priv_monotonic_ns();
    lep_priv_sim_transport_in(&s->tr, at, n);
    return true;
}

void lep_priv_sim_queue_advance(lep_sim *s, int64_t now)
{
    lep_priv_sim_transport_advance(&s->tr, now);
}

size_t lep_priv_sim_queue_ready(const lep_sim *s)
{
    size_t n = lep_priv_sim_transport_ready(&s->tr);
    return n < s->out_len ? n : s->out_len;
}

int64_t lep_priv_sim_queue_next(const lep_sim *s)
{
    return lep_priv_sim_transport_next(&s->tr);
}

void lep_priv_sim_queue_written(lep_sim *s, size_t n)
{
    if (n > s->out_len)
        n = s->out_len;
    memmove(s->out, s->out + n, s->out_len - n);
    s->out_len -= n;
    lep_priv_sim_transport_written(&s->tr, n);
}

void lep_priv_sim_queue_clear(lep_sim *s)
{
    s->out_len = 0;
    lep_priv_sim_transport_clear(&s->tr);
}
