/* Virtual sensor: the output queue (messages made, not yet written to the
 * port by sim_pty.c or sim_link_win32.c). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE /* PATH_MAX */
#endif

#include <string.h>

#include "sim_priv.h"

bool lep_priv_sim_queue_full(const lep_sim *s)
{
    return s->out_len + LEP_SIM_FRAME_ROOM > OUTQ_SIZE;
}

bool lep_priv_sim_queue(lep_sim *s, const uint8_t *b, size_t n)
{
    if (s->out_len + n > OUTQ_SIZE)
        return false;
    memcpy(s->out + s->out_len, b, n);
    s->out_len += n;
    return true;
}
