/* Virtual sensor on Windows: not available yet. The POSIX sensor serves a
 * pseudo-terminal from a thread (sim_api.c .. sim_trace.c, left out of a
 * Windows build); Windows has no pseudo-terminal a COM-port client could
 * open, and the in-process link that would replace it is not written yet
 * (docs/windows.md). lep_sim_start says so; the rest of the API takes the
 * NULL handle it never returns. The signal, filter, models, options and
 * replay files are portable and built as everywhere. */
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "sim_priv.h"

int lep_sim_start_so(const lep_sim_options *o, lep_sim **out, char *err, size_t errlen)
{
    int rc;
    if (out != NULL)
        *out = NULL;
    if (out == NULL) {
        lep_priv_set_err(err, errlen, "no place for the result");
        return LEP_E_ARG;
    }
    if (o != NULL) {
        rc = lep_sim_options_check(o, err, errlen);
        if (rc != LEP_OK)
            return rc;
    }
    lep_priv_set_err(err, errlen,
                     "the virtual sensor is not available on Windows yet (it serves a "
                     "pseudo-terminal); use a sensor's COM port (docs/windows.md)");
    return LEP_E_IO;
}

int lep_sim_sample_at(const lep_sim *s, uint64_t k, uint8_t filter, lep_sample *out)
{
    (void)s;
    (void)k;
    (void)filter;
    (void)out;
    return LEP_E_ARG;
}

const char *lep_sim_port(const lep_sim *s)
{
    (void)s;
    return "";
}

const char *lep_sim_pty_path(const lep_sim *s)
{
    (void)s;
    return "";
}

void lep_sim_power_cycle(lep_sim *s)
{
    (void)s;
}

void lep_sim_hangup(lep_sim *s)
{
    (void)s;
}

void lep_sim_stall(lep_sim *s, int ms)
{
    (void)s;
    (void)ms;
}

void lep_sim_hold(lep_sim *s, int ms)
{
    (void)s;
    (void)ms;
}

int lep_sim_trace_writes(lep_sim *s, const char *path, char *err, size_t errlen)
{
    (void)s;
    (void)path;
    lep_priv_set_err(err, errlen, "no virtual sensor");
    return LEP_E_ARG;
}

void lep_sim_get_stats(lep_sim *s, lep_sim_counters *out)
{
    (void)s;
    if (out != NULL)
        memset(out, 0, sizeof *out);
}

void lep_sim_stop(lep_sim *s)
{
    (void)s;
}
