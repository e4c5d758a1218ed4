/* The struct form of the OS layer's API, private to the tree.
 *
 * The public headers (include/leptrino) give every language handles,
 * numbers, flat arrays and strings. Underneath, the session, the virtual
 * sensor, the output writer, the ROS encoder and payload work on the structs
 * below; the public functions fill or read them, so there is one
 * implementation of each behaviour. The tree's own C front ends (the
 * leptrino tool, leptrino-sim, leptrino-soak, the benchmarks) and the C
 * tests use this form directly; it is not installed, not exported from the
 * shared library (no LEP_API), and may change at any commit. */
#ifndef LEPTRINO_STRUCT_API_H
#define LEPTRINO_STRUCT_API_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "leptrino/client.h"
#include "leptrino/message.h"
#include "leptrino/options.h"
#include "leptrino/output.h"
#include "leptrino/payload.h"
#include "leptrino/record.h"
#include "leptrino/ros_cdr.h"
#include "leptrino/serial.h"
#include "leptrino/session.h"
#include "leptrino/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ==== payload ==== */

/* Standard gravity, m/s^2 (the default gravity vector is (0, 0, -this)). */
#define LEP_STANDARD_GRAVITY 9.80665

/* Fewest poses an identification takes. */

/* Smallest spread of the gravity vectors an identification accepts (see
 * lep_payload_fit.spread): 0.02 is an RMS tilt of about 1.1 degrees in the
 * direction the poses cover least. */
#define LEP_PAYLOAD_MIN_SPREAD 0.02

/* A payload: what compensation needs. */
typedef struct lep_payload {
    double mass_kg;  /* >= 0 */
    double com_m[3]; /* centre of mass, sensor frame, metres */
} lep_payload;

/* What an identification found. */
typedef struct lep_payload_fit {
    lep_payload payload;
    double force_bias_N[3];    /* F_b */
    double torque_bias_Nm[3];  /* M_b */
    double residual[LEP_AXES]; /* per axis, RMS over the poses of measured - model (N, N m):
                                  the noise of the means plus whatever the model misses */
    double spread;             /* how well the gravity vectors cover the directions the
                                  centre of mass needs: sqrt(l_min / (n mean|g|^2)), l_min the
                                  smallest eigenvalue of sum(|d|^2 I - d d^T), d = g - mean g.
                                  0 when the vectors lie on one line; 1/sqrt(2)..1 for poses
                                  spread evenly over the sphere */
    size_t poses;
} lep_payload_fit;

/* lep_payload_wrench on a struct. */
int lep_payload_wrench_p(const lep_payload *p, const double gravity[3], double wrench[LEP_AXES]);
/* lep_payload_identify into a struct. */
int lep_payload_identify_fit(const double *gravity, const double *wrench, size_t n,
                             lep_payload_fit *out, char *err, size_t errlen);

/* ==== the virtual sensor ==== */

/* Sizes of the string fields of lep_sim_options (each includes the NUL). */
#define LEP_SIM_MODEL_SIZE 32u
#define LEP_SIM_SERIAL_SIZE 16u
#define LEP_SIM_FIRMWARE_SIZE 8u
#define LEP_SIM_PATH_SIZE 512u

/* Options of a virtual sensor. Start from lep_sim_options_init() (the
 * defaults), then set fields directly or by name from text with
 * lep_sim_option_set(). The struct owns its strings (NUL-terminated char
 * arrays): nothing it holds points elsewhere, so it may be copied, kept or
 * filled through an FFI freely. Every option is described once, in the
 * table read by lep_sim_option_at()/lep_sim_option_find(): leptrino-sim's
 * options, the leptrino tool's --sim-* options and Python's
 * Simulator(**options) are derived from it. The name of each option in that
 * table is given in brackets. */
typedef struct lep_sim_options {
    char model[LEP_SIM_MODEL_SIZE];   /* [model] preset: CFS018CA201U, CFS034CA301U,
                                             PFS055YA501U6 (default), PFS080YS102U6 */
    char serial[LEP_SIM_SERIAL_SIZE]; /* [serial] 1..8 ASCII digits, default "00000001" */
    char
        firmware[LEP_SIM_FIRMWARE_SIZE]; /* [firmware] 1..4 printable ASCII chars, default "1.13" */
    bool output_rate_field; /* [output-rate-field] answer product info in the 38-byte form */
    double rate_hz;         /* [rate] continuous output rate, 1..10000 Hz, default 1200 */
    uint8_t filter;         /* [filter] filter code in effect at power-on, 0..3, default 0 */
    uint64_t seed;          /* [seed] waveform and fault randomness, default 1 */
    double amplitude; /* [amplitude] sine amplitude as a fraction of rated, 0..4, default 0.2 */
    double noise;     /* [noise] uniform noise amplitude as a fraction of rated, 0..1,
                               default 0.005 */
    bool constant;    /* [constant] hold a constant load (amplitude as the level), no noise */
    char replay_csv[LEP_SIM_PATH_SIZE]; /* [replay] replay raw counts from this CSV file,
                                           looping; "" (default): the waveform */
    double overload_every_s;    /* [overload-every] an overload episode every N s of a stream,
                                   0 (default) = never: one axis at 4x rated, saturated at
                                   +/-32000, status bit 2 */
    double overload_duration_s; /* [overload-duration] length of an episode, > 0 and
                                   < overload_every_s, default 0.1 */
    double p_nak;               /* [nak] probability of NAKing a valid command (not executed) */
    double p_corrupt;      /* [corrupt] probability of flipping one bit of an outgoing message */
    double p_garbage;      /* [garbage] probability of 1..8 garbage bytes (never DLE) before
                               an outgoing message */
    double p_drop;         /* [drop] probability of dropping a continuous data message */
    int stall_ms;          /* [stall] stall (send nothing, answer nothing) for N ms ... */
    double stall_after_s;  /* [stall-after] ... starting this long after start (needs stall_ms) */
    double hangup_after_s; /* [hangup-after] hang up (close the pty) once, N s after start,
                               0 (default) = never */
    int reopen_after_ms;   /* [reopen-after] after a hang-up, open a new pty after N ms and
                               re-point link (needs link; the sensor comes back powered up,
                               idle), -1 (default) = never */
    bool start_streaming;  /* [start-streaming] power up already streaming (a stream left by
                               an earlier program) */
    char link[LEP_SIM_PATH_SIZE]; /* [link] also make a symlink at this path to the port;
                                     "" (default): none. Replaces only a symlink to a
                                     pseudo-terminal that no running virtual sensor owns */
    /* added with payload compensation (leptrino/payload.h: the model): */
    double payload[4]; /* [payload] a tool on the sensor: mass kg (>= 0), centre of mass
                          x, y, z m in the sensor frame; default 0,0,0,0 (none) */
    double gravity[3]; /* [gravity] gravity in the sensor frame, m/s^2, default
                          0,0,-9.80665 (z up): the sensor reads the payload's gravity
                          wrench at it on top of the waveform */
    /* added with the transport emulation (docs/simulator.md, "Transport"): */
    double ppm;          /* [ppm] the crystal off by this many ppm, -1000..1000, default 0:
                             samples come at rate * (1 + ppm 1e-6), the nominal rate reported */
    bool usb_packets;    /* [usb-packets] the port gets the bytes as a USB full-speed adapter
                             delivers them: at 1 ms frame boundaries only */
    int ftdi_latency_ms; /* [ftdi-latency] an FTDI-style adapter with this latency timer, ms,
                             1..255 (0, default: none): 62-byte packets, or what is held when
                             the timer runs out, at 1 ms frame boundaries */
} lep_sim_options;

/* ---- The option table ----
 *
 * One row per field of lep_sim_options. Front ends print their own help line
 * from a row: e.g. "--sim-" name, arg, help, the range [min, max] and
 * "(default " default_text ")". All functions below are re-entrant (the table
 * is constant), never block and never allocate. */
enum lep_sim_option_type {
    LEP_SIM_OPT_FLAG = 0, /* bool; takes no argument on a command line */
    LEP_SIM_OPT_INT,      /* integer in [min, max] */
    LEP_SIM_OPT_UINT,     /* non-negative integer in [min, max] (decimal) */
    LEP_SIM_OPT_DOUBLE,   /* finite number in [min, max] (or (min, max] with min_exclusive) */
    LEP_SIM_OPT_STRING,   /* text of min..max bytes (a path, a serial, a version) */
    LEP_SIM_OPT_CHOICE,   /* one of a fixed set of names (model: lep_sim_models()) */
    LEP_SIM_OPT_NUMBERS   /* comma-separated finite numbers, as many as arg names
                             ("M,CX,CY,CZ"), each in [min, max] */
};

typedef struct lep_sim_option_info {
    const char *name; /* dash-separated, e.g. "amplitude", "output-rate-field" */
    int type;         /* enum lep_sim_option_type */
    const char *arg;  /* name of the argument for help ("F", "HZ", "PATH"); NULL for flags */
    const char *help; /* one line, no trailing period, without range or default */
    const char *default_text; /* the default as lep_sim_option_set accepts it; NULL when the
                                 option is off/empty by default (flags, replay, link) */
    double min, max;          /* numbers: the allowed range; STRING: its length in bytes;
                                 FLAG, CHOICE: 0 */
    bool min_exclusive;       /* the value must be > min (not >=) */
} lep_sim_option_info;

/* Number of options in the table. */
size_t lep_sim_option_count(void);

/* Row i of the table, for i < lep_sim_option_count(); NULL otherwise. The
 * pointer is to static data, valid for the life of the program. */
const lep_sim_option_info *lep_sim_option_at(size_t i);

/* The row named name, or NULL. Accepts the dash-separated name, the same
 * with underscores ("output_rate_field", so Python keyword arguments map
 * directly) and the lep_sim_options field name ("rate_hz", "p_nak",
 * "replay_csv", "stall_after_s", ...). */
const lep_sim_option_info *lep_sim_option_find(const char *name);

/* Parse value (text) for the option called name (any form lep_sim_option_find
 * accepts), range-check it and store it in o. Flags take NULL (on), "1",
 * "0", "true" or "false". Numbers must be finite and parse completely.
 * On error returns LEP_E_ARG, leaves o unchanged and writes one line into err
 * (when not NULL) naming the option and what is allowed, e.g.
 * "amplitude '5': expected a number from 0 to 4". Re-entrant. */
int lep_sim_option_set(lep_sim_options *o, const char *name, const char *value, char *err,
                       size_t errlen);

/* Write the current value of an option in o as text that lep_sim_option_set
 * accepts (flags: "1"/"0") into buf. LEP_E_ARG for an unknown name or a NULL
 * argument, LEP_E_BUFFER when buf is too small (buf then holds ""). */
int lep_sim_option_get(const lep_sim_options *o, const char *name, char *buf, size_t buflen);

/* Check every option of o and how they combine (overload duration < every,
 * reopen needs a link, stall-after needs a stall): the one validation
 * lep_sim_start() uses too. LEP_OK, or LEP_E_ARG with one line in err naming
 * the option. Checks values only (not whether a replay file exists or the
 * link may be replaced: lep_sim_start() does that). Re-entrant. */
int lep_sim_options_check(const lep_sim_options *o, char *err, size_t errlen);

/* Counters of what the virtual sensor did (since lep_sim_start). */
typedef struct lep_sim_counters {
    uint64_t samples_sent;    /* continuous data messages queued to the port */
    uint64_t samples_dropped; /* data messages dropped by the p_drop fault */
    uint64_t commands;        /* commands answered (any result code) */
    uint64_t naks;            /* DLE NAK sent (bad BCC, or the p_nak fault) */
    uint64_t bytes_corrupted; /* messages with a byte flipped by the p_corrupt fault */
    uint64_t hangups;
    bool streaming;
    uint8_t filter;         /* in effect */
    uint8_t filter_pending; /* takes effect at the next power cycle */
    /* added after the first draft of this header: */
    bool hung_up;             /* the pty is closed now (after a hang-up, before a reopen) */
    uint16_t sequence;        /* sequence number the next stream sample will carry */
    uint64_t responses;       /* answers to commands queued to the port */
    uint64_t faked_naks;      /* of naks: those sent by the p_nak fault */
    uint64_t samples_skipped; /* sample periods with nothing sent: a stall, or > 500 ms late */
    uint64_t samples_blocked; /* data messages not sent because nobody read the port */
    uint64_t garbage_bytes;   /* bytes added by the p_garbage fault */
    uint64_t bytes_received;  /* bytes read from the host */
    uint64_t reopens;         /* new ptys opened after a hang-up */
    uint64_t power_cycles;    /* lep_sim_power_cycle / SIGUSR1 applied */
    uint64_t stalls;          /* stalls begun */
} lep_sim_counters;

/* Fill o with the defaults (every option's default_text). NULL is ignored. */
void lep_sim_options_init(lep_sim_options *o);

/* Names of the model presets, NULL-terminated static array. */
const char *const *lep_sim_models(void);

/* Rated values of a preset; LEP_E_ARG for an unknown model. */
int lep_sim_model_rated_f(const char *model, lep_rated *out);

/* lep_sim_start on a struct (the one implementation). */
int lep_sim_start_so(const lep_sim_options *o, lep_sim **out, char *err, size_t errlen);
/* lep_sim_stream_sample into a lep_sample. */
int lep_sim_sample_at(const lep_sim *s, uint64_t k, uint8_t filter, lep_sample *out);
void lep_sim_get_stats(lep_sim *s, lep_sim_counters *out);

typedef struct lep_sim_trace_record {
    uint64_t k;          /* stream index, or LEP_SIM_TRACE_START / LEP_SIM_TRACE_END */
    int64_t t_call_ns;   /* CLOCK_MONOTONIC before the write() (markers: the event) */
    int64_t t_return_ns; /* CLOCK_MONOTONIC after it returned (markers: the same) */
} lep_sim_trace_record;

#define LEP_SIM_TRACE_START UINT64_MAX
#define LEP_SIM_TRACE_END (UINT64_MAX - 1u)

/* ==== serial ==== */

typedef struct lep_serial_info {
    bool low_latency;    /* ASYNC_LOW_LATENCY flag set on the port */
    int ftdi_latency_ms; /* FTDI latency timer now in force, or -1 if not FTDI/unknown */
    bool ftdi_lowered;   /* the timer was lowered by this open */
} lep_serial_info;

void lep_serial_get_latency_info(const lep_serial *s, lep_serial_info *info);

/* A serial port found on this machine. */
typedef struct lep_port_info {
    char path[256];        /* /dev/ttyACM0 */
    char by_id[256];       /* /dev/serial/by-id/... or empty */
    char description[128]; /* USB product/manufacturer when known */
    uint16_t vid;          /* USB vendor id, 0 if unknown */
    uint16_t pid;          /* USB product id, 0 if unknown */
    bool likely_sensor;    /* STM VCP 0483:5740 or FTDI 0403:6001 */
} lep_port_info;

/* List serial ports into out[0..max); *n gets how many exist (may exceed max). */
int lep_serial_list(lep_port_info *out, size_t max, size_t *n);

/* ==== the session ==== */

/* Options; start from lep_session_options_init(). Copied at open. */
typedef struct lep_session_options {
    /* ---- the port ---- */
    const char *port;    /* serial port path (used when use_sim is false) */
    bool use_sim;        /* start an in-process virtual sensor with sim instead */
    lep_sim_options sim; /* its options (lep_sim_options_init'ed by default) */
    /* ---- start-up and transactions ---- */
    int timeout_ms;    /* answer timeout per attempt, default 500 */
    int sync_quiet_ms; /* quiet time that ends the start-up drain, default 30 */
    /* ---- stream ---- */
    int data_timeout_ms;      /* no sample for this long while streaming: a disconnect
                                (reconnect) or LEP_E_TIMEOUT, default 2000 */
    double gap_periods;       /* a hole longer than this many nominal periods is a gap, default 3 */
    double nominal_hz;        /* 0 (default): the sensor's output-rate field, else the virtual
                                sensor's rate_hz with use_sim, else 1200 */
    bool reconnect;           /* after a disconnect or data timeout, reopen with backoff,
                                re-sync and restart the stream (default false) */
    int reconnect_min_ms;     /* backoff from ... (default 100) */
    int reconnect_max_ms;     /* ... doubling up to this (default 1000) */
    int reconnect_give_up_ms; /* give up after this long without the sensor, < 0 never (default) */
    int latency_ms;           /* latency budget: how long delivery may hold samples back to
                                save wake-ups; 0 (default) delivers as soon as a read returns */
    /* ---- processing (all can be changed later except tare_samples) ---- */
    unsigned tare_samples; /* tare over the first N samples after start; they are not
                                delivered (0 = none) */
    double lowpass_hz;     /* host low-pass cut-off on SI values, 0 = off */
    unsigned decimate;     /* deliver every Nth sample (after the low-pass), default 1 */
    double rotation[9];    /* row-major R: output force = R f, moment = R m (identity) */
    double shift_m[3];     /* moment reference point, in the output frame, metres: the
                                moment about it is m' - r x f' (default 0) */
    /* ---- end of stream ---- */
    double duration_s; /* lep_session_read gives LEP_E_END after this long from the
                                first delivered sample's arrival, 0 = none */
    uint64_t count;    /* ... or after this many samples delivered, 0 = none */
    /* ---- payload and limits (added later; all can be changed while streaming) ---- */
    lep_payload payload;    /* the tool on the sensor (leptrino/payload.h): its gravity wrench
                               at `gravity` is removed from the SI values; mass 0 (default):
                               none */
    double gravity[3];      /* gravity in the sensor frame, m/s^2, default (0, 0, -9.80665) */
    double limit[LEP_AXES]; /* per axis, N and N m: an SI value (compensated, in the output
                               frame) beyond +/- limit is a limit episode; 0 (default): none */
    /* ---- added with the flat API ---- */
    int retries; /* a command is sent again this many times after a NAK or a timeout, on
                    every connection (0..255, default LEP_CLIENT_DEFAULT_RETRIES) */
} lep_session_options;

/* Destination arrays, caller-owned. Every pointer may be NULL to skip that
 * column. lep_session_read appends from n up to cap. */
typedef struct lep_session_batch {
    size_t cap;      /* capacity in samples */
    size_t n;        /* samples filled so far */
    double *t_mono;  /* [cap] s, lep_monotonic_seconds() when the read delivering it returned */
    double *t_utc;   /* [cap] s since 1970-01-01 UTC, the same instant on the wall clock */
    int16_t *raw;    /* [cap*6] counts as received */
    double *zeroed;  /* [cap*6] raw - tare offset, counts */
    double *si;      /* [cap*6] N, N m: zeroed, low-passed, decimated, rotated, shifted */
    uint8_t *status; /* [cap] the sensor's LEP_STATUS_* bits */
    uint8_t *flags;  /* [cap] LEP_SF_* */
    uint16_t *seq;   /* [cap] the reserved bytes (leptrino-sim's sequence number) */
} lep_session_batch;

typedef struct lep_session_event {
    int type;        /* enum lep_session_event_type */
    uint64_t sample; /* index (count of samples delivered before it since the stream's start)
                        where it applies; 0 when queued before the start */
    double t_mono;   /* when, monotonic s */
    double t_utc;    /* when, UTC s */
    double gap_from; /* GAP/RECONNECTED: arrival of the last sample before (mono s);
                              DISCONNECTED: the same, the last sample received */
    double gap_to;   /* ... and of the first after */
    uint32_t lost;   /* GAP: samples estimated lost (from sequence numbers on the
                              virtual sensor, from arrival times otherwise) */
    int error;       /* DISCONNECTED, and RECONNECTED (what caused the loss):
                              LEP_E_DISCONNECTED or LEP_E_TIMEOUT; 0 otherwise */
    uint8_t axes;    /* OVERLOAD_*: bit i = axis i saturated; status bits in status */
    uint8_t status;
    double tare[LEP_AXES];   /* TARE: the offsets now in force (counts; zeros when untared) */
    double wrench[LEP_AXES]; /* LIMIT_*: the sample's SI values (N, N m) */
    int64_t row; /* the row of the last read's batch it comes before: sample less the rows
                    returned before that read, plus the rows the batch held already
                    (LEP_EVF_ROW); while stopped, sample */
} lep_session_event;

/* Health, since lep_session_start. */
typedef struct lep_session_health_info {
    double elapsed_s;   /* from the first sample to the last */
    double nominal_hz;  /* as lep_session_options.nominal_hz says */
    double measured_hz; /* (samples received - 1) / elapsed (decimation not applied) */
    double recent_hz;   /* over the last second or so (the run so far in its first second) */
    bool shortfall;     /* measured_hz below 98 % of nominal over at least 1 s */
    uint64_t received;  /* samples received (tare samples included) */
    uint64_t delivered; /* samples returned by lep_session_read (after decimation) */
    uint64_t lost;      /* samples estimated lost in gaps */
    uint64_t gaps;
    uint64_t errors;         /* framing, BCC, invalid messages, timeouts (all connections) */
    uint64_t overloads;      /* overload episodes begun */
    uint64_t limit_episodes; /* limit episodes begun (LEP_EV_LIMIT_EXCEEDED queued) */
    uint64_t disconnects;
    uint64_t reconnects;
    uint64_t events_dropped; /* events pushed out of the full queue (1024) before
                                lep_session_next_event took them */
    double max_gap_s;
    lep_client_stats client; /* the current connection's counters */
} lep_session_health_info;

/* What a recording says about itself. Strings are NUL-terminated. */
typedef struct lep_session_meta {
    lep_product_info info; /* model, serial, firmware, output-rate field */
    char protocol[24];     /* "v1.13 (32-byte info)" or "rate field (38-byte)" */
    lep_rated rated;
    int sensor_filter; /* the sensor's filter code, -1 when it refused or did not answer */
    char sensor_filter_label[24]; /* lep_filter_label, or "not supported by sensor" */
    double nominal_hz;
    double lowpass_hz;      /* host low-pass cut-off, 0 off */
    char lowpass_name[48];  /* the filter's name, "" when off */
    double lowpass_delay_s; /* its group delay at low frequency */
    unsigned decimate;
    double rotation[9];
    double shift_m[3];
    bool tared;
    double tare[LEP_AXES]; /* counts */
    double start_utc;      /* UTC s of the last lep_session_start (of open before one) */
    double start_mono;     /* monotonic s of the same instant */
    char port[256];
    bool sim;
    char library_version[16]; /* lep_version() */
    lep_payload payload;      /* mass 0: none */
    double gravity[3];
    double limit[LEP_AXES]; /* 0: none */
} lep_session_meta;

/* Defaults as documented on each field. o must not be NULL. */
void lep_session_options_init(lep_session_options *o);

/* lep_session_open on a struct (the one implementation). */
int lep_session_open_so(const lep_session_options *o, lep_session **out, char *err, size_t errlen);

/* lep_session_read appending to b (from b->n up to b->cap); b->n counts the
 * samples appended whatever it returns; a b already full returns LEP_OK at
 * once. */
int lep_session_read_batch(lep_session *s, lep_session_batch *b, int timeout_ms);
/* lep_session_read_one appending to b; LEP_E_ARG for a full b. */
int lep_session_read_one_batch(lep_session *s, lep_session_batch *b);
/* lep_session_next_event into a struct; false when none. */
bool lep_session_pop_event(lep_session *s, lep_session_event *ev);

/* The live settings (lep_session_set's by-name options land here). */
int lep_session_set_lowpass(lep_session *s, double cutoff_hz);
int lep_session_set_rotation(lep_session *s, const double rotation[9], const double shift_m[3]);
int lep_session_set_payload(lep_session *s, const lep_payload *p);
int lep_session_set_gravity(lep_session *s, const double gravity[3]);
int lep_session_set_limits(lep_session *s, const double limit[LEP_AXES]);
int lep_session_set_latency(lep_session *s, int latency_ms);
int lep_session_latency(const lep_session *s);

void lep_session_get_health(lep_session *s, lep_session_health_info *out);
void lep_session_get_metadata(lep_session *s, lep_session_meta *out);
/* The metadata JSON (LEP_INFO_METADATA_JSON) into buf[0..cap); *len gets its
 * length; LEP_E_BUFFER when it does not fit. */
int lep_session_metadata_json(lep_session *s, char *buf, size_t cap, size_t *len);
int lep_session_get_serial_info(const lep_session *s, lep_serial_info *out);

/* An event as the public array of doubles (LEP_EVF_COUNT fields), and back. */
void lep_event_to_fields(const lep_session_event *ev, double f[LEP_EVF_COUNT]);
void lep_event_from_fields(const double *f, lep_session_event *ev);

/* ==== the output writer ==== */

typedef struct lep_output_options {
    int format;       /* enum lep_output_format, default CSV */
    int time;         /* enum lep_output_time, default REL */
    unsigned columns; /* LEP_COL_* bits, default LEP_COL_DEFAULT; the time column is always there */
    double t0_mono;   /* origin of t_s; 0 (default): start_mono of the first sensor added */
    bool overwrite;   /* lep_output_open may replace an existing file (default false) */
} lep_output_options;

void lep_output_options_init(lep_output_options *o);
int lep_output_open_opts(const char *path, const lep_output_options *o, lep_output **out, char *err,
                         size_t errlen);
int lep_output_open_fd_opts(int fd, const lep_output_options *o, lep_output **out, char *err,
                            size_t errlen);
/* Rows b[from..b->n) and events ev[0..nev), as lep_output_write. */
int lep_output_write_batch(lep_output *w, int sensor, const lep_session_batch *b, size_t from,
                           const lep_session_event *ev, size_t nev);

/* ==== ROS CDR and recording ==== */

/* lep_ros_wrench_cdr on samples [from, from + n) of b. */
int lep_ros_wrench_cdr_batch(const lep_session_batch *b, size_t from, size_t n,
                             const lep_rated *rated, const char *frame_id, int64_t *last_ns,
                             uint8_t *wrench, uint8_t *wrench_raw, size_t cap, int64_t *stamp_ns);

typedef struct lep_record_batch {
    size_t cap;      /* capacity in samples */
    size_t n;        /* samples filled so far; the call appends from here */
    double *t;       /* [cap] host arrival time, lep_monotonic_seconds() */
    double *si;      /* [cap * 6] N, N m (needs rated) */
    int16_t *raw;    /* [cap * 6] counts */
    uint8_t *status; /* [cap] status bits */
    uint16_t *seq;   /* [cap] the two reserved bytes (sequence number of leptrino-sim) */
} lep_record_batch;

/* lep_record_fill appending to b (from b->n). */
int lep_record_fill_batch(lep_client *c, const lep_rated *rated, lep_record_batch *b,
                          double until_s, int timeout_ms);

#ifdef __cplusplus
}
#endif

#endif
