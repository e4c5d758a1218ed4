/* Virtual sensor: the flat functions of leptrino/sim.h over the struct ones
 * (start from options by name, a stream sample as plain values, the counters
 * as an array by enumerator); no OS call here. */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE /* PATH_MAX in sim_priv.h */
#endif

#include <string.h>

#include "leptrino/error.h"
#include "options_priv.h"
#include "sim_priv.h"

/* ---- the flat form (leptrino/sim.h) ---- */

int lep_sim_start(const lep_options *o, lep_sim **out, char *err, size_t errlen)
{
    lep_sim_options so;
    if (o == NULL) {
        lep_sim_options_init(&so);
        return lep_sim_start_so(&so, out, err, errlen);
    }
    return lep_sim_start_so(&o->so.sim, out, err, errlen);
}

int lep_sim_stream_sample(const lep_sim *s, uint64_t k, int filter, int16_t raw[6], uint8_t *status,
                          uint16_t *seq)
{
    lep_sample smp;
    int rc;
    if (filter < 0 || filter > (int)LEP_FILTER_MAX)
        return LEP_E_ARG;
    rc = lep_sim_sample_at(s, k, (uint8_t)filter, &smp);
    if (rc != LEP_OK)
        return rc;
    if (raw != NULL)
        memcpy(raw, smp.raw, sizeof smp.raw);
    if (status != NULL)
        *status = smp.status;
    if (seq != NULL)
        *seq = smp.reserved;
    return LEP_OK;
}

static const char *const stat_names[LEP_SIMST_COUNT] = {
    "samples_sent",    "samples_dropped", "commands",        "naks",
    "bytes_corrupted", "hangups",         "streaming",       "filter",
    "filter_pending",  "hung_up",         "sequence",        "responses",
    "faked_naks",      "samples_skipped", "samples_blocked", "garbage_bytes",
    "bytes_received",  "reopens",         "power_cycles",    "stalls"
};

size_t lep_sim_stats_fields(void)
{
    return LEP_SIMST_COUNT;
}

const char *lep_sim_stats_field_name(size_t i)
{
    return i < LEP_SIMST_COUNT ? stat_names[i] : NULL;
}

int lep_sim_stats(lep_sim *s, uint64_t *out, size_t n)
{
    lep_sim_counters c;
    uint64_t f[LEP_SIMST_COUNT];
    if (s == NULL || (out == NULL && n > 0))
        return LEP_E_ARG;
    lep_sim_get_stats(s, &c);
    f[LEP_SIMST_SAMPLES_SENT] = c.samples_sent;
    f[LEP_SIMST_SAMPLES_DROPPED] = c.samples_dropped;
    f[LEP_SIMST_COMMANDS] = c.commands;
    f[LEP_SIMST_NAKS] = c.naks;
    f[LEP_SIMST_BYTES_CORRUPTED] = c.bytes_corrupted;
    f[LEP_SIMST_HANGUPS] = c.hangups;
    f[LEP_SIMST_STREAMING] = c.streaming ? 1u : 0u;
    f[LEP_SIMST_FILTER] = c.filter;
    f[LEP_SIMST_FILTER_PENDING] = c.filter_pending;
    f[LEP_SIMST_HUNG_UP] = c.hung_up ? 1u : 0u;
    f[LEP_SIMST_SEQUENCE] = c.sequence;
    f[LEP_SIMST_RESPONSES] = c.responses;
    f[LEP_SIMST_FAKED_NAKS] = c.faked_naks;
    f[LEP_SIMST_SAMPLES_SKIPPED] = c.samples_skipped;
    f[LEP_SIMST_SAMPLES_BLOCKED] = c.samples_blocked;
    f[LEP_SIMST_GARBAGE_BYTES] = c.garbage_bytes;
    f[LEP_SIMST_BYTES_RECEIVED] = c.bytes_received;
    f[LEP_SIMST_REOPENS] = c.reopens;
    f[LEP_SIMST_POWER_CYCLES] = c.power_cycles;
    f[LEP_SIMST_STALLS] = c.stalls;
    memcpy(out, f, sizeof(uint64_t) * (n < LEP_SIMST_COUNT ? n : LEP_SIMST_COUNT));
    return LEP_OK;
}
