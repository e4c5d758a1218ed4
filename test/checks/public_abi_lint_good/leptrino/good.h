/* Test header of public_abi_lint.py: what the rules allow, and no finding. */
#ifndef LEPTRINO_GOOD_H
#define LEPTRINO_GOOD_H

#include <stddef.h>
#include <stdint.h>

#include <leptrino/export.h>

#define LEP_GOOD_TWICE(x) ((x)*2) /* function-like: allowed */

/* Constants as enumerators: FFIs see those. */
enum lep_good_limits { LEP_GOOD_LIMIT = 5, LEP_GOOD_NAME_LEN = 64 };

typedef enum lep_good_mode { LEP_GOOD_OFF = 0, LEP_GOOD_ON = 1 } lep_good_mode;

typedef struct lep_good_handle lep_good_handle; /* opaque: a handle */

typedef struct lep_good_point { /* flat: scalars and fixed arrays of scalars */
    double xyz[3];
    int32_t counts[6];
    uint8_t valid; /* 0/1 */
    lep_good_mode mode;
    char name[LEP_GOOD_NAME_LEN]; /* 64 bytes: the most a struct may hold */
} lep_good_point;

typedef struct lep_good_options { /* starts with its size: may grow at its end */
    size_t size;
    double rate_hz;
    uint32_t retries;
} lep_good_options;

/* A caller-allocated context (CONTEXTS): nests and holds pointers by design,
 * and has its lep_client_sizeof(). */
typedef struct lep_client {
    lep_good_point last;
    const uint8_t *rx;
    size_t rx_len;
} lep_client;

typedef int (*lep_good_callback)(void *user, int32_t last, double value);

LEP_API size_t lep_client_sizeof(void);
LEP_API int lep_good_open(const lep_good_options *o, lep_good_handle **out);
LEP_API int lep_good_open_port(const char *port, lep_good_handle **out);
LEP_API int lep_good_ready(const lep_good_handle *h); /* 0/1 */
LEP_API int lep_good_position(const lep_good_handle *h, lep_good_point *out);
LEP_API int lep_good_read(lep_good_handle *h, double *si, size_t n, size_t *got);
LEP_API int lep_good_on_sample(lep_good_handle *h, lep_good_callback cb, void *user);
LEP_API const char *lep_good_name(const lep_good_handle *h);
LEP_API void lep_good_close(lep_good_handle *h);

#endif
