/* The session's options, described once: the rows of the public table
 * (leptrino/options.h) for everything lep_session_open reads. */
#include <stddef.h>

#include "leptrino/options.h"
#include "options_priv.h"

#define F(m) #m, offsetof(struct lep_options, m), sizeof(((struct lep_options *)0)->m)
#define ROW(name, type, arg, help, def, lo, hi, scope, member, store)                       \
    {                                                                                       \
        { name, type, arg, help, def, lo, hi, false }, name, scope, F(member), store, T_ANY \
    }

#define MAX_MS 86400000.0
#define MAX_SECONDS 1e9

/* Order: the port, start-up, the stream, processing, the end (help screens). */
static const opt_row rows[] = {
    ROW("port", LEP_SIM_OPT_STRING, "PATH", "the sensor's serial port (/dev/ttyACM0)", NULL, 1,
        LEP_PORT_PATH_SIZE - 1, LEP_SCOPE_SESSION, port, S_CHARS),
    ROW("sim", LEP_SIM_OPT_FLAG, NULL,
        "run an in-process virtual sensor (the sim-* options) instead of a port", NULL, 0, 0,
        LEP_SCOPE_SESSION, so.use_sim, S_BOOL),
    ROW("timeout", LEP_SIM_OPT_INT, "MS", "answer timeout per attempt of a command, ms", "500", 1,
        MAX_MS, LEP_SCOPE_SESSION, so.timeout_ms, S_INT),
    ROW("sync-quiet", LEP_SIM_OPT_INT, "MS", "quiet time that ends the start-up drain, ms", "30", 0,
        MAX_MS, LEP_SCOPE_SESSION, so.sync_quiet_ms, S_INT),
    ROW("data-timeout", LEP_SIM_OPT_INT, "MS",
        "no sample for MS ms while streaming: a disconnect (reconnect) or a lost stream", "2000", 1,
        MAX_MS, LEP_SCOPE_SESSION, so.data_timeout_ms, S_INT),
    ROW("gap-periods", LEP_SIM_OPT_DOUBLE, "N", "a hole longer than N nominal periods is a gap",
        "3", 1, 1e6, LEP_SCOPE_SESSION, so.gap_periods, S_DOUBLE),
    ROW("nominal-rate", LEP_SIM_OPT_DOUBLE, "HZ",
        "nominal output rate in Hz (0: the sensor's output-rate field, else the virtual "
        "sensor's rate, else 1200)",
        "0", 0, 100000, LEP_SCOPE_SESSION, so.nominal_hz, S_DOUBLE),
    ROW("reconnect", LEP_SIM_OPT_FLAG, NULL,
        "after a disconnect or data timeout, reopen with backoff and restart the stream", NULL, 0,
        0, LEP_SCOPE_SESSION, so.reconnect, S_BOOL),
    ROW("reconnect-min", LEP_SIM_OPT_INT, "MS", "reconnect backoff from MS ms ...", "100", 1,
        MAX_MS, LEP_SCOPE_SESSION, so.reconnect_min_ms, S_INT),
    ROW("reconnect-max", LEP_SIM_OPT_INT, "MS", "... doubling up to MS ms", "1000", 1, MAX_MS,
        LEP_SCOPE_SESSION, so.reconnect_max_ms, S_INT),
    ROW("reconnect-give-up", LEP_SIM_OPT_INT, "MS",
        "give up after MS ms without the sensor (-1: never)", "-1", -1, MAX_MS, LEP_SCOPE_SESSION,
        so.reconnect_give_up_ms, S_INT),
    ROW("latency", LEP_SIM_OPT_INT, "MS",
        "latency budget: how long delivery may hold samples back to save wake-ups (0: none)", "0",
        0, 10000, LEP_SCOPE_LIVE, so.latency_ms, S_INT),
    ROW("tare-samples", LEP_SIM_OPT_UINT, "N",
        "tare over the first N samples after start; they are not delivered (0: none)", "0", 0, 1e9,
        LEP_SCOPE_SESSION, so.tare_samples, S_UNSIGNED),
    ROW("lowpass", LEP_SIM_OPT_DOUBLE, "HZ",
        "host low-pass cut-off on the SI values, Hz, at most 0.45 x the rate (0: off)", "0", 0,
        100000, LEP_SCOPE_LIVE, so.lowpass_hz, S_DOUBLE),
    ROW("decimate", LEP_SIM_OPT_UINT, "N", "deliver every Nth sample (after the low-pass)", "1", 1,
        1e6, LEP_SCOPE_SESSION, so.decimate, S_UNSIGNED),
    ROW("rotation", LEP_SIM_OPT_NUMBERS, "R11,R12,R13,R21,R22,R23,R31,R32,R33",
        "output frame: row-major orthonormal R, force = R f, moment = R m", "1,0,0,0,1,0,0,0,1", -1,
        1, LEP_SCOPE_LIVE, so.rotation, S_DOUBLES),
    ROW("shift", LEP_SIM_OPT_NUMBERS, "X,Y,Z",
        "moment reference point in the output frame, m: moment = m' - r x f'", "0,0,0", -1000, 1000,
        LEP_SCOPE_LIVE, so.shift_m, S_DOUBLES),
    ROW("duration", LEP_SIM_OPT_DOUBLE, "S",
        "reading ends (LEP_E_END) S s after the first sample (0: none)", "0", 0, MAX_SECONDS,
        LEP_SCOPE_SESSION, so.duration_s, S_DOUBLE),
    ROW("count", LEP_SIM_OPT_UINT, "N", "reading ends after N samples delivered (0: none)", "0", 0,
        9007199254740992.0, LEP_SCOPE_SESSION, so.count, S_U64),
    ROW("payload", LEP_SIM_OPT_NUMBERS, "M,CX,CY,CZ",
        "a tool on the sensor, its gravity wrench removed: mass kg, centre of mass m (sensor "
        "frame)",
        "0,0,0,0", -1000, 1000, LEP_SCOPE_LIVE, so.payload, S_DOUBLES),
    ROW("gravity", LEP_SIM_OPT_NUMBERS, "GX,GY,GZ", "gravity in the sensor frame, m/s^2",
        "0,0,-9.80665", -100, 100, LEP_SCOPE_LIVE, so.gravity, S_DOUBLES),
    ROW("limit", LEP_SIM_OPT_NUMBERS, "FX,FY,FZ,MX,MY,MZ",
        "per-axis limits on the SI values, N and N m (0: none), or AXIS=VALUE,... (fz=50,mz=2)",
        "0,0,0,0,0,0", 0, 1e12, LEP_SCOPE_LIVE, so.limit, S_DOUBLES),
};

const opt_row *lep_priv_session_rows(size_t *n)
{
    *n = sizeof rows / sizeof rows[0];
    return rows;
}
