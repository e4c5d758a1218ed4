"""C declarations of the libleptrino subset the bindings use, for cffi.

Types and prototypes are copied from include/leptrino/*.h (array sizes
spelled out, since cffi's parser does not evaluate the header macros).
tests/test_declarations.py parses the headers and fails when anything here
differs from them. The ctypes backend has its own declarations, checked by
the same test.
"""

from __future__ import annotations

CDEF = """
/* error.h */
const char *lep_strerror(int err);
const char *lep_result_str(uint8_t result);

/* leptrino.h */
const char *lep_version(void);

/* frame.h */
typedef struct lep_frame_event {
    int type;
    int error;
    const uint8_t *msg;
    size_t len;
} lep_frame_event;

typedef struct lep_frame_stats {
    uint32_t messages;
    uint32_t naks;
    uint32_t bcc_errors;
    uint32_t escape_errors;
    uint32_t overruns;
    uint32_t restarts;
    uint32_t bytes_discarded;
} lep_frame_stats;

/* (allocated as lep_frame_decoder_sizeof() bytes) */
typedef struct lep_frame_decoder lep_frame_decoder;

uint8_t lep_bcc(const uint8_t *msg, size_t len);
int lep_frame_encode(const uint8_t *msg, size_t len, uint8_t *out, size_t cap, size_t *out_len);
size_t lep_frame_decoder_sizeof(void);
void lep_frame_decoder_init(lep_frame_decoder *d);
size_t lep_frame_decoder_feed(lep_frame_decoder *d, const uint8_t *data, size_t len,
                              lep_frame_event *ev);
bool lep_frame_decoder_busy(const lep_frame_decoder *d);
void lep_frame_decoder_get_stats(const lep_frame_decoder *d, lep_frame_stats *out);

/* message.h */
typedef struct lep_command {
    uint8_t code;
    uint8_t filter;
} lep_command;

typedef struct lep_product_info {
    char model[17];
    char serial[9];
    char firmware[5];
    char output_rate[7];
    bool has_output_rate;
    uint32_t output_rate_hz;
} lep_product_info;

typedef struct lep_rated {
    float axis[6];
} lep_rated;

typedef struct lep_sample {
    int16_t raw[6];
    uint16_t reserved;
    uint8_t status;
} lep_sample;

typedef struct lep_response {
    uint8_t code;
    uint8_t result;
    bool stream;
    union {
        lep_product_info info;
        lep_rated rated;
        uint8_t filter;
        lep_sample sample;
    } u;
} lep_response;

int lep_command_encode(const lep_command *cmd, uint8_t *msg, size_t cap, size_t *len);
int lep_command_decode(const uint8_t *msg, size_t len, lep_command *cmd, uint8_t *result);
int lep_response_decode(const uint8_t *msg, size_t len, lep_response *r);
int lep_command_frame(const lep_command *cmd, uint8_t *out, size_t cap, size_t *len);
void lep_sample_to_si(const lep_sample *s, const lep_rated *rated, double *si);
uint8_t lep_sample_saturated(const lep_sample *s, int16_t limit);
const char *lep_filter_label(uint8_t code);
const char *lep_command_name(uint8_t code);

/* client.h (the context is allocated as lep_client_sizeof() bytes) */
typedef struct lep_client lep_client;

typedef struct lep_client_stats {
    uint32_t messages;
    uint32_t bcc_errors;
    uint32_t frame_errors;
    uint32_t bytes_discarded;
    uint32_t naks;
    uint32_t retries;
    uint32_t unexpected;
    uint32_t invalid;
    uint32_t timeouts;
    uint32_t samples;
    uint32_t resent_after_timeout;
    uint32_t resent_confirmed;
    uint32_t recoveries;
    uint32_t reserved_nonzero;
    uint32_t stalls;
} lep_client_stats;

size_t lep_client_sizeof(void);
int lep_client_set_timeout(lep_client *c, int timeout_ms);
int lep_client_set_retries(lep_client *c, unsigned retries);
void lep_client_get_stats(const lep_client *c, lep_client_stats *out);
uint8_t lep_client_last_result(const lep_client *c);
bool lep_client_streaming(const lep_client *c);
int lep_client_sync(lep_client *c, int quiet_ms, lep_product_info *info);
int lep_client_product_info(lep_client *c, lep_product_info *out);
int lep_client_rated(lep_client *c, lep_rated *out);
int lep_client_filter_get(lep_client *c, uint8_t *code);
int lep_client_filter_set(lep_client *c, uint8_t code);
int lep_client_sample(lep_client *c, lep_sample *out);
int lep_client_start(lep_client *c);
int lep_client_next_sample(lep_client *c, lep_sample *out, int timeout_ms);
int lep_client_stop(lep_client *c);

/* serial.h */
typedef struct lep_serial lep_serial;

typedef struct lep_serial_info {
    bool low_latency;
    int ftdi_latency_ms;
    bool ftdi_lowered;
} lep_serial_info;

typedef struct lep_port_info {
    char path[256];
    char by_id[256];
    char description[128];
    uint16_t vid;
    uint16_t pid;
    bool likely_sensor;
} lep_port_info;

int lep_serial_open(const char *path, lep_serial **out, char *err, size_t errlen);
void lep_serial_close(lep_serial *s);
int lep_serial_client_init(lep_client *c, lep_serial *s);
void lep_serial_get_info(const lep_serial *s, lep_serial_info *info);
const char *lep_serial_path(const lep_serial *s);
double lep_monotonic_seconds(void);
int lep_serial_list(lep_port_info *out, size_t max, size_t *n);

/* sim.h */
typedef struct lep_sim lep_sim;

typedef struct lep_sim_options {
    char model[32];
    char serial[16];
    char firmware[8];
    bool output_rate_field;
    double rate_hz;
    uint8_t filter;
    uint64_t seed;
    double amplitude;
    double noise;
    bool constant;
    char replay_csv[512];
    double overload_every_s;
    double overload_duration_s;
    double p_nak;
    double p_corrupt;
    double p_garbage;
    double p_drop;
    int stall_ms;
    double stall_after_s;
    double hangup_after_s;
    int reopen_after_ms;
    bool start_streaming;
    char link[512];
    double payload[4];
    double gravity[3];
} lep_sim_options;

typedef struct lep_sim_option_info {
    const char *name;
    int type;
    const char *arg;
    const char *help;
    const char *default_text;
    double min, max;
    bool min_exclusive;
} lep_sim_option_info;

typedef struct lep_sim_stats {
    uint64_t samples_sent;
    uint64_t samples_dropped;
    uint64_t commands;
    uint64_t naks;
    uint64_t bytes_corrupted;
    uint64_t hangups;
    bool streaming;
    uint8_t filter;
    uint8_t filter_pending;
    bool hung_up;
    uint16_t sequence;
    uint64_t responses;
    uint64_t faked_naks;
    uint64_t samples_skipped;
    uint64_t samples_blocked;
    uint64_t garbage_bytes;
    uint64_t bytes_received;
    uint64_t reopens;
    uint64_t power_cycles;
    uint64_t stalls;
} lep_sim_stats;

void lep_sim_options_init(lep_sim_options *o);
const char *const *lep_sim_models(void);
int lep_sim_model_rated(const char *model, lep_rated *out);
int lep_sim_start(const lep_sim_options *o, lep_sim **out, char *err, size_t errlen);
const char *lep_sim_port(const lep_sim *s);
void lep_sim_power_cycle(lep_sim *s);
void lep_sim_hangup(lep_sim *s);
void lep_sim_stall(lep_sim *s, int ms);
void lep_sim_get_stats(lep_sim *s, lep_sim_stats *out);
void lep_sim_stop(lep_sim *s);
const char *lep_sim_pty_path(const lep_sim *s);
size_t lep_sim_option_count(void);
const lep_sim_option_info *lep_sim_option_at(size_t i);
const lep_sim_option_info *lep_sim_option_find(const char *name);
int lep_sim_option_set(lep_sim_options *o, const char *name, const char *value, char *err,
                       size_t errlen);
int lep_sim_option_get(const lep_sim_options *o, const char *name, char *buf, size_t buflen);
int lep_sim_options_check(const lep_sim_options *o, char *err, size_t errlen);
int lep_sim_stream_sample(const lep_sim *s, uint64_t k, uint8_t filter, lep_sample *out);

/* record.h */
typedef struct lep_record_batch {
    size_t cap;
    size_t n;
    double *t;
    double *si;
    int16_t *raw;
    uint8_t *status;
    uint16_t *seq;
} lep_record_batch;

int lep_record_fill(lep_client *c, const lep_rated *rated, lep_record_batch *b, double until_s,
                    int timeout_ms);

/* payload.h */
typedef struct lep_payload {
    double mass_kg;
    double com_m[3];
} lep_payload;

typedef struct lep_payload_fit {
    lep_payload payload;
    double force_bias_N[3];
    double torque_bias_Nm[3];
    double residual[6];
    double spread;
    size_t poses;
} lep_payload_fit;

int lep_payload_wrench(const lep_payload *p, const double gravity[3], double wrench[6]);
int lep_payload_identify(const double *gravity, const double *wrench, size_t n,
                         lep_payload_fit *out, char *err, size_t errlen);
int lep_payload_pose_read(const char *path, double mean[6], uint64_t *samples, char *err,
                          size_t errlen);

/* session.h */
typedef struct lep_session lep_session;

typedef struct lep_session_options {
    const char *port;
    bool use_sim;
    lep_sim_options sim;
    int timeout_ms;
    int sync_quiet_ms;
    int data_timeout_ms;
    double gap_periods;
    double nominal_hz;
    bool reconnect;
    int reconnect_min_ms;
    int reconnect_max_ms;
    int reconnect_give_up_ms;
    int latency_ms;
    unsigned tare_samples;
    double lowpass_hz;
    unsigned decimate;
    double rotation[9];
    double shift_m[3];
    double duration_s;
    uint64_t count;
    lep_payload payload;
    double gravity[3];
    double limit[6];
} lep_session_options;

typedef struct lep_session_batch {
    size_t cap;
    size_t n;
    double *t_mono;
    double *t_utc;
    int16_t *raw;
    double *zeroed;
    double *si;
    uint8_t *status;
    uint8_t *flags;
    uint16_t *seq;
} lep_session_batch;

typedef struct lep_session_event {
    int type;
    uint64_t sample;
    double t_mono;
    double t_utc;
    double gap_from;
    double gap_to;
    uint32_t lost;
    int error;
    uint8_t axes;
    uint8_t status;
    double tare[6];
    double wrench[6];
} lep_session_event;

typedef struct lep_session_health {
    double elapsed_s;
    double nominal_hz;
    double measured_hz;
    double recent_hz;
    bool shortfall;
    uint64_t received;
    uint64_t delivered;
    uint64_t lost;
    uint64_t gaps;
    uint64_t errors;
    uint64_t overloads;
    uint64_t disconnects;
    uint64_t reconnects;
    uint64_t events_dropped;
    double max_gap_s;
    lep_client_stats client;
} lep_session_health;

typedef struct lep_session_metadata {
    lep_product_info info;
    char protocol[24];
    lep_rated rated;
    int sensor_filter;
    char sensor_filter_label[24];
    double nominal_hz;
    double lowpass_hz;
    char lowpass_name[48];
    double lowpass_delay_s;
    unsigned decimate;
    double rotation[9];
    double shift_m[3];
    bool tared;
    double tare[6];
    double start_utc;
    double start_mono;
    char port[256];
    bool sim;
    char library_version[16];
    lep_payload payload;
    double gravity[3];
    double limit[6];
} lep_session_metadata;

void lep_session_options_init(lep_session_options *o);
void lep_rotation_from_rpy(double roll, double pitch, double yaw, double *r);
int lep_session_open(const lep_session_options *o, lep_session **out, char *err, size_t errlen);
void lep_session_close(lep_session *s);
int lep_session_start(lep_session *s);
int lep_session_stop(lep_session *s);
int lep_session_read(lep_session *s, lep_session_batch *b, int timeout_ms);
int lep_session_read_one(lep_session *s, lep_session_batch *b);
int lep_session_serial_info(const lep_session *s, lep_serial_info *out);
bool lep_session_next_event(lep_session *s, lep_session_event *ev);
int lep_session_tare(lep_session *s, unsigned n, double duration_s);
int lep_session_untare(lep_session *s);
int lep_session_set_tare(lep_session *s, const double *offset);
bool lep_session_get_tare(lep_session *s, double *offset);
bool lep_session_taring(lep_session *s);
int lep_session_set_lowpass(lep_session *s, double cutoff_hz);
int lep_session_set_payload(lep_session *s, const lep_payload *p);
int lep_session_set_gravity(lep_session *s, const double gravity[3]);
int lep_session_set_limits(lep_session *s, const double limit[6]);
int lep_session_set_latency(lep_session *s, int latency_ms);
int lep_session_latency(const lep_session *s);
int lep_session_set_rotation(lep_session *s, const double *rotation, const double *shift_m);
void lep_session_get_health(lep_session *s, lep_session_health *out);
void lep_session_get_metadata(lep_session *s, lep_session_metadata *out);
int lep_session_metadata_json(lep_session *s, char *buf, size_t cap, size_t *len);
lep_client *lep_session_client(lep_session *s);
lep_sim *lep_session_sim(lep_session *s);
const char *lep_session_port(const lep_session *s);
int lep_session_fd(const lep_session *s);
bool lep_session_streaming(const lep_session *s);

/* output.h */
typedef struct lep_output_options {
    int format;
    int time;
    unsigned columns;
    double t0_mono;
    bool overwrite;
} lep_output_options;

typedef struct lep_output lep_output;

void lep_output_options_init(lep_output_options *o);
int lep_output_open(const char *path, const lep_output_options *o, lep_output **out, char *err,
                    size_t errlen);
int lep_output_open_fd(int fd, const lep_output_options *o, lep_output **out, char *err,
                       size_t errlen);
int lep_output_add_session(lep_output *w, lep_session *s, const char *name);
int lep_output_add_sensor(lep_output *w, const char *name, const char *metadata_json,
                          double start_mono);
int lep_output_write(lep_output *w, int sensor, const lep_session_batch *b, size_t from,
                     const lep_session_event *ev, size_t nev);
int lep_output_flush(lep_output *w);
int lep_output_errno(const lep_output *w);
int lep_output_close(lep_output *w);
"""
