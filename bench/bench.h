/* leptrino-bench: shared declarations of its parts (streams, the plain
 * baseline decoder, the measurements, the JSON writer). */
#ifndef LEPTRINO_BENCH_H
#define LEPTRINO_BENCH_H

#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

/* ---- streams.c: the byte streams the decoders are measured on ---- */
enum bench_stream { STREAM_REALISTIC = 0, STREAM_ALL_DLE, STREAM_CORRUPT, STREAM_COUNT };

typedef struct bench_bytes {
    uint8_t *data;
    size_t len;
    size_t frames;      /* data frames written (before corruption) */
    size_t payload;     /* message bytes (unstuffed) */
    size_t payload_dle; /* of which 0x10 */
    size_t corrupted;   /* bytes changed (STREAM_CORRUPT) */
} bench_bytes;

const char *bench_stream_name(int which);
/* Build stream `which` of `frames` data frames (malloc'd; free data). 0 or -1. */
int bench_stream_make(int which, size_t frames, bench_bytes *out);

/* ---- plain_decoder.c: the baseline ---- */
typedef struct plain_decoder {
    int state;
    size_t n;
    uint8_t bcc;
    uint8_t buf[256];
} plain_decoder;

void plain_init(plain_decoder *p);
/* One received byte; 1 when it completed a good message (p->buf, p->n). */
int plain_step(plain_decoder *p, uint8_t b);
/* Decode data[0..len) byte by byte; for each good message add its third byte
 * to *sink and count it. Returns the messages completed in this call. */
size_t plain_feed(plain_decoder *p, const uint8_t *data, size_t len, uint32_t *sink);

/* ---- json_out.c: one JSON object on stdout, written as it is measured ---- */
void json_open(const char *key); /* key NULL at the top level and inside arrays */
void json_close(void);
void json_open_array(const char *key);
void json_close_array(void);
void json_num(const char *key, double v); /* non-finite values are written as null */
void json_int(const char *key, long long v);
void json_str(const char *key, const char *v); /* NULL writes null */
void json_bool(const char *key, int v);
void json_null(const char *key);
void json_end(void); /* newline, flush */

/* ---- decode.c: codec measurements (in process, and as callgrind regions) ---- */
enum bench_region {
    REGION_LEPTRINO = 0,
    REGION_FEED,
    REGION_PLAIN,
    REGION_PLAIN_LOOP,
    REGION_CLIENT_STEP,
    REGION_CLIENT_STEP_CALL,
    REGION_COUNT
};
const char *bench_region_name(int which);
/* Run region `which` once over s in chunks of `chunk` bytes; returns messages
 * (samples for the client) and adds to *sink. */
size_t bench_region_run(int which, const bench_bytes *s, size_t chunk, uint32_t *sink);
/* Encoder: frames of data messages per second (median of runs). */
double bench_encode_msgs_per_s(int runs, size_t frames, int whole_sample);

/* ---- util.c ---- */
double bench_now_s(void);
double bench_median(double *v, size_t n);
double bench_percentile(double *sorted, size_t n, double q); /* v sorted ascending */
/* Run argv (argv[0] looked up in PATH), stdout to out_path (NULL: /dev/null);
 * returns the exit status, -1 when it could not run. */
int bench_run(char *const argv[], const char *out_path);
/* Call in a child right after fork(), with parent = getpid() taken before the
 * fork: the child gets SIGTERM when the bench ends (Linux; elsewhere nothing),
 * so a bench killed by ^C or a broken pipe leaves no virtual sensor running;
 * exits at once if the bench is already gone. */
void bench_child_follow_parent(pid_t parent);
int bench_have(const char *prog); /* prog found in PATH */

#endif
