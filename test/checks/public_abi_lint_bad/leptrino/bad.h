/* Test header of public_abi_lint.py: each rule broken at least once (the
 * rule in brackets); `public_abi_lint.py --include public_abi_lint_bad
 * --expect-rules ...` checks that exactly these rules fire. */
#ifndef LEPTRINO_BAD_H
#define LEPTRINO_BAD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <leptrino/export.h>

#define LEP_BAD_LIMIT 5u          /* [macro] a constant FFIs cannot see */
#define LEP_BAD_SCALE (2.0 * 3.0) /* [macro] */
#define LEP_BAD_TWICE(x) ((x)*2)  /* function-like: not a finding */

typedef struct lep_bad_handle lep_bad_handle;

typedef struct lep_bad_point {
    double x, y;
    bool valid; /* [bool] */
} lep_bad_point;

typedef struct lep_bad_options { /* [unsized]: nested and pointer members, no size */
    const char *port;            /* [pointer] */
    lep_bad_point origin;        /* [nested] */
    char path[256];              /* [char-array] */
    char name[64];               /* fine: 64 bytes at most */
} lep_bad_options;

typedef struct lep_bad_sized { /* starts with its size: not [unsized], but still [pointer] */
    size_t size;
    const char *label; /* [pointer] */
} lep_bad_sized;

/* A caller-allocated context (CONTEXTS) may nest, but needs
 * lep_device_sizeof(), which is missing here: [context]. */
typedef struct lep_device {
    lep_bad_point last;
    const uint8_t *buf;
} lep_device;

typedef int (*lep_bad_callback)(void *user, bool last); /* [bool] */

LEP_API bool lep_bad_ready(const lep_bad_handle *h);                 /* [bool] */
LEP_API int lep_bad_get_flag(const lep_bad_handle *h, bool *out);    /* [bool] */
LEP_API int lep_bad_set_count(lep_bad_handle *h, unsigned n);        /* [unsigned] */
LEP_API unsigned int lep_bad_count(const lep_bad_handle *h);         /* [unsigned] */
LEP_API lep_bad_point lep_bad_position(const lep_bad_handle *h);     /* [by-value] */
LEP_API int lep_bad_move(lep_bad_handle *h, lep_bad_point to);       /* [by-value] */
LEP_API int lep_bad_log(lep_bad_handle *h, const char *format, ...); /* [variadic] */
LEP_API int lep_bad_open(const lep_bad_options *o, lep_bad_handle **out);

#endif
