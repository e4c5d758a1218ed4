/* The virtual sensor's options, described once: the table every front end
 * reads (names, types, ranges, defaults, help), parsing from text, and the one
 * validation lep_sim_start uses. */
#include <errno.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "leptrino/sim.h"
#include "options_priv.h"
#include "struct_api.h"

#define F(m) #m, offsetof(lep_sim_options, m), sizeof(((lep_sim_options *)0)->m)
#define NUM(name, type, arg, help, def, lo, hi, excl, member, store)                         \
    {                                                                                        \
        { name, type, arg, help, def, lo, hi, excl }, "sim-" name, LEP_SCOPE_SIM, F(member), \
            store, T_ANY                                                                     \
    }
#define TXT(name, type, arg, help, def, lo, hi, member, rule)                                 \
    {                                                                                         \
        { name, type, arg, help, def, lo, hi, false }, "sim-" name, LEP_SCOPE_SIM, F(member), \
            S_CHARS, rule                                                                     \
    }

/* Time options stop well short of 9.2e9 s, where nanoseconds leave int64. */
#define MAX_SECONDS 1e6
#define MAX_MS 86400000.0

/* Order: identity, signal, faults, port (the order of help screens). */
static const opt_row rows[] = {
    TXT("model", LEP_SIM_OPT_CHOICE, "NAME",
        "model preset (CFS018CA201U, CFS034CA301U, PFS055YA501U6, PFS080YS102U6)", "PFS055YA501U6",
        0, 0, model, T_MODEL),
    TXT("serial", LEP_SIM_OPT_STRING, "DIGITS", "serial number, digits (space padded to 8)",
        "00000001", 1, 8, serial, T_DIGITS),
    TXT("firmware", LEP_SIM_OPT_STRING, "VER", "firmware version, printable ASCII", "1.13", 1, 4,
        firmware, T_PRINTABLE),
    NUM("output-rate-field", LEP_SIM_OPT_FLAG, NULL,
        "product info in the 38-byte form with the output-rate field", NULL, 0, 0, false,
        output_rate_field, S_BOOL),
    NUM("filter", LEP_SIM_OPT_UINT, "CODE", "filter code in effect at power-on", "0", 0, 3, false,
        filter, S_U8),
    NUM("rate", LEP_SIM_OPT_DOUBLE, "HZ", "continuous output rate in Hz", "1200", 1, 10000, false,
        rate_hz, S_DOUBLE),
    NUM("ppm", LEP_SIM_OPT_DOUBLE, "N",
        "crystal off by N ppm: true rate rate*(1+N*1e-6), the nominal one reported", "0", -1000,
        1000, false, ppm, S_DOUBLE),
    NUM("seed", LEP_SIM_OPT_UINT, "N", "seed of the waveform noise and of the faults", "1", 0,
        18446744073709551615.0, false, seed, S_U64),
    NUM("amplitude", LEP_SIM_OPT_DOUBLE, "F",
        "sine amplitude (or constant level), fraction of rated", "0.2", 0, 4, false, amplitude,
        S_DOUBLE),
    NUM("noise", LEP_SIM_OPT_DOUBLE, "F", "uniform noise amplitude, fraction of rated", "0.005", 0,
        1, false, noise, S_DOUBLE),
    NUM("constant", LEP_SIM_OPT_FLAG, NULL, "hold a constant load (the amplitude), no noise", NULL,
        0, 0, false, constant, S_BOOL),
    TXT("replay", LEP_SIM_OPT_STRING, "PATH",
        "replay raw counts from a CSV file (a leptrino raw recording), looping", NULL, 1,
        LEP_SIM_PATH_SIZE - 1, replay_csv, T_ANY),
    NUM("overload-every", LEP_SIM_OPT_DOUBLE, "S",
        "an overload episode every S s of a stream (0: never)", "0", 0, MAX_SECONDS, false,
        overload_every_s, S_DOUBLE),
    NUM("overload-duration", LEP_SIM_OPT_DOUBLE, "S",
        "length of an overload episode in s (< overload-every)", "0.1", 0, MAX_SECONDS, true,
        overload_duration_s, S_DOUBLE),
    NUM("payload", LEP_SIM_OPT_NUMBERS, "M,CX,CY,CZ",
        "a tool on the sensor: mass kg, centre of mass m (sensor frame)", "0,0,0,0", -1000, 1000,
        false, payload, S_DOUBLES),
    NUM("gravity", LEP_SIM_OPT_NUMBERS, "GX,GY,GZ", "gravity in the sensor frame, m/s^2",
        "0,0,-9.80665", -100, 100, false, gravity, S_DOUBLES),
    NUM("nak", LEP_SIM_OPT_DOUBLE, "P", "fault: probability of NAKing a valid command", "0", 0, 1,
        false, p_nak, S_DOUBLE),
    NUM("corrupt", LEP_SIM_OPT_DOUBLE, "P", "fault: probability of flipping a bit of a message",
        "0", 0, 1, false, p_corrupt, S_DOUBLE),
    NUM("garbage", LEP_SIM_OPT_DOUBLE, "P", "fault: probability of garbage bytes before a message",
        "0", 0, 1, false, p_garbage, S_DOUBLE),
    NUM("drop", LEP_SIM_OPT_DOUBLE, "P", "fault: probability of dropping a data message", "0", 0, 1,
        false, p_drop, S_DOUBLE),
    NUM("stall", LEP_SIM_OPT_INT, "MS", "fault: stall (send and answer nothing) for MS ms ...", "0",
        0, MAX_MS, false, stall_ms, S_INT),
    NUM("stall-after", LEP_SIM_OPT_DOUBLE, "S", "... S seconds after start (needs stall)", "0", 0,
        MAX_SECONDS, false, stall_after_s, S_DOUBLE),
    NUM("hangup-after", LEP_SIM_OPT_DOUBLE, "S",
        "fault: hang up (a pulled cable) S s after start (0: never)", "0", 0, MAX_SECONDS, false,
        hangup_after_s, S_DOUBLE),
    NUM("reopen-after", LEP_SIM_OPT_INT, "MS",
        "after a hang-up, come back at the link after MS ms (-1: never)", "-1", -1, MAX_MS, false,
        reopen_after_ms, S_INT),
    NUM("start-streaming", LEP_SIM_OPT_FLAG, NULL,
        "power up already streaming (a stream left by an earlier program)", NULL, 0, 0, false,
        start_streaming, S_BOOL),
    TXT("link", LEP_SIM_OPT_STRING, "PATH",
        "also make a symlink PATH to the port (replaces only a stale link to a pty)", NULL, 1,
        LEP_SIM_PATH_SIZE - 33, link, T_ANY),
    NUM("usb-packets", LEP_SIM_OPT_FLAG, NULL,
        "the port gets the bytes as a USB full-speed adapter sends them: at 1 ms frames", NULL, 0,
        0, false, usb_packets, S_BOOL),
    NUM("ftdi-latency", LEP_SIM_OPT_INT, "MS",
        "an FTDI adapter: 62-byte packets, or what it holds after MS ms (0: none; chip's 16)", "0",
        0, 255, false, ftdi_latency_ms, S_INT),
};

#define N_ROWS (sizeof rows / sizeof rows[0])

size_t lep_sim_option_count(void)
{
    return N_ROWS;
}

const lep_sim_option_info *lep_sim_option_at(size_t i)
{
    return i < N_ROWS ? &rows[i].info : NULL;
}

const opt_row *lep_priv_sim_rows(size_t *n)
{
    *n = N_ROWS;
    return rows;
}

const lep_sim_option_info *lep_sim_option_find(const char *name)
{
    const opt_row *r = lep_priv_row_find(rows, N_ROWS, name);
    return r ? &r->info : NULL;
}

int lep_sim_options_check(const lep_sim_options *o, char *err, size_t errlen)
{
    size_t i;
    if (err != NULL && errlen > 0)
        err[0] = '\0';
    if (o == NULL) {
        lep_priv_set_err(err, errlen, "no options given");
        return LEP_E_ARG;
    }
    for (i = 0; i < N_ROWS; i++) {
        int rc = lep_priv_row_check(o, &rows[i], err, errlen);
        if (rc != LEP_OK)
            return rc;
    }
    if (o->overload_every_s > 0 && !(o->overload_duration_s < o->overload_every_s)) {
        lep_priv_set_err(err, errlen,
                         "overload-duration %g: expected less than overload-every (%g)",
                         o->overload_duration_s, o->overload_every_s);
        return LEP_E_ARG;
    }
    if (o->payload[0] < 0.0) {
        lep_priv_set_err(err, errlen, "payload mass %g: expected >= 0 kg", o->payload[0]);
        return LEP_E_ARG;
    }
    if (o->reopen_after_ms >= 0 && o->link[0] == '\0') {
        lep_priv_set_err(err, errlen,
                         "reopen-after needs link (the path that survives the reopen)");
        return LEP_E_ARG;
    }
    if (o->usb_packets && o->ftdi_latency_ms > 0) {
        lep_priv_set_err(err, errlen,
                         "usb-packets and ftdi-latency: choose one (an FTDI adapter sends "
                         "USB packets too)");
        return LEP_E_ARG;
    }
    if (o->stall_after_s > 0 && o->stall_ms == 0) {
        lep_priv_set_err(err, errlen, "stall-after needs stall (how many ms to stall)");
        return LEP_E_ARG;
    }
    return LEP_OK;
}

int lep_sim_option_set(lep_sim_options *o, const char *name, const char *value, char *err,
                       size_t errlen)
{
    const opt_row *r;
    if (err != NULL && errlen > 0)
        err[0] = '\0';
    if (o == NULL || name == NULL) {
        lep_priv_set_err(err, errlen, "no options or no option name given");
        return LEP_E_ARG;
    }
    r = lep_priv_row_find(rows, N_ROWS, name);
    if (r == NULL) {
        lep_priv_set_err(err, errlen, "unknown virtual sensor option '%s'", name);
        return LEP_E_ARG;
    }
    return lep_priv_row_set(o, r, r->info.name, value, err, errlen);
}

int lep_sim_option_get(const lep_sim_options *o, const char *name, char *buf, size_t buflen)
{
    const opt_row *r = lep_priv_row_find(rows, N_ROWS, name);
    if (o == NULL || r == NULL || buf == NULL || buflen == 0)
        return LEP_E_ARG;
    return lep_priv_row_get(o, r, buf, buflen, NULL);
}

void lep_sim_options_init(lep_sim_options *o)
{
    size_t i;
    if (o == NULL)
        return;
    memset(o, 0, sizeof *o);
    for (i = 0; i < N_ROWS; i++)
        if (rows[i].info.default_text != NULL)
            (void)lep_sim_option_set(o, rows[i].info.name, rows[i].info.default_text, NULL, 0);
}
