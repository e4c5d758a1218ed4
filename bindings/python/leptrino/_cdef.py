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

typedef struct lep_frame_decoder {
    uint8_t state;
    uint8_t bcc;
    uint16_t len;
    uint16_t raw;
    uint8_t buf[128];
    lep_frame_stats stats;
} lep_frame_decoder;

uint8_t lep_bcc(const uint8_t *msg, size_t len);
int lep_frame_encode(const uint8_t *msg, size_t len, uint8_t *out, size_t cap, size_t *out_len);
void lep_frame_decoder_init(lep_frame_decoder *d);
size_t lep_frame_decoder_feed(lep_frame_decoder *d, const uint8_t *data, size_t len,
                              lep_frame_event *ev);
bool lep_frame_decoder_busy(const lep_frame_decoder *d);

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

/* client.h (the context is allocated as lep_client_size() bytes) */
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

size_t lep_client_size(void);
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
    const char *model;
    const char *serial;
    const char *firmware;
    bool output_rate_field;
    double rate_hz;
    uint8_t filter;
    uint64_t seed;
    double amplitude;
    double noise;
    bool constant;
    const char *replay_csv;
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
    const char *link;
} lep_sim_options;

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
"""
