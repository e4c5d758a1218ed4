/* The option table engine (option_rows.h): parse, check and print one row's
 * member of a struct. */
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "option_rows.h"

/* a equals b, where '_' in a also matches '-' in b. */
static bool name_eq(const char *a, const char *b)
{
    for (; *a != '\0' && *b != '\0'; a++, b++) {
        if (*a != *b && !(*a == '_' && *b == '-'))
            return false;
    }
    return *a == '\0' && *b == '\0';
}

const opt_row *lep_priv_row_find(const opt_row *rows, size_t n, const char *name)
{
    size_t i;
    if (name == NULL)
        return NULL;
    for (i = 0; i < n; i++)
        if (name_eq(name, rows[i].info.name) || name_eq(name, rows[i].public_name) ||
            strcmp(name, rows[i].field) == 0)
            return &rows[i];
    return NULL;
}

void *lep_priv_row_member(void *base, const opt_row *r)
{
    return (unsigned char *)base + r->offset;
}

const void *lep_priv_row_cmember(const void *base, const opt_row *r)
{
    return (const unsigned char *)base + r->offset;
}

/* The value of a numeric member as a double (S_U64: not needed, full range). */
static double number_of(const void *p, const opt_row *r)
{
    switch (r->store) {
    case S_INT:
        return (double)*(const int *)p;
    case S_UNSIGNED:
        return (double)*(const unsigned *)p;
    case S_U8:
        return (double)*(const uint8_t *)p;
    case S_DOUBLE:
        return *(const double *)p;
    default:
        return 0.0;
    }
}

void lep_priv_row_range(const opt_row *r, char *buf, size_t cap)
{
    const lep_sim_option_info *in = &r->info;
    if (in->type == LEP_SIM_OPT_DOUBLE && in->min_exclusive)
        snprintf(buf, cap, "a number > %.15g and <= %.15g", in->min, in->max);
    else if (in->type == LEP_SIM_OPT_DOUBLE)
        snprintf(buf, cap, "a number from %.15g to %.15g", in->min, in->max);
    else if (r->store == S_DOUBLES)
        snprintf(buf, cap, "%zu comma-separated numbers (%s), each from %.15g to %.15g",
                 r->size / sizeof(double), in->arg, in->min, in->max);
    else if (r->store == S_U64 && in->max >= 18446744073709551615.0)
        snprintf(buf, cap, "an integer from 0 to 18446744073709551615");
    else if (r->store == S_U64)
        snprintf(buf, cap, "an integer from 0 to %.0f", in->max);
    else
        snprintf(buf, cap, "an integer from %.0f to %.0f", in->min, in->max);
}

bool lep_priv_row_in_range(const opt_row *r, double v)
{
    const lep_sim_option_info *in = &r->info;
    if (in->min_exclusive ? !(v > in->min) : !(v >= in->min))
        return false;
    return v <= in->max; /* NaN and infinities fail one of the two */
}

static bool known_model(const char *m)
{
    const char *const *n;
    for (n = lep_sim_models(); *n != NULL; n++)
        if (strcmp(*n, m) == 0)
            return true;
    return false;
}

/* Check a text member: terminated, length in range, its rule. */
static int check_text(const opt_row *r, const char *label, const char *t, char *err, size_t errlen)
{
    const lep_sim_option_info *in = &r->info;
    size_t n = 0, i;
    while (n < r->size && t[n] != '\0')
        n++;
    if (n == r->size) {
        lep_priv_set_err(err, errlen, "%s: not NUL-terminated within its %zu bytes", label,
                         r->size);
        return LEP_E_ARG;
    }
    if (r->rule == T_MODEL) {
        if (!known_model(t)) {
            lep_priv_set_err(err, errlen, "%s '%s': unknown (known: %s)", label, t,
                             "CFS018CA201U, CFS034CA301U, PFS055YA501U6, PFS080YS102U6");
            return LEP_E_ARG;
        }
        return LEP_OK;
    }
    if (n == 0 && in->default_text == NULL)
        return LEP_OK; /* an optional text left empty: not used */
    if ((double)n < in->min || (double)n > in->max) {
        lep_priv_set_err(err, errlen, "%s '%s': expected %.0f to %.0f %s", label, t, in->min,
                         in->max, r->rule == T_DIGITS ? "digits" : "characters");
        return LEP_E_ARG;
    }
    for (i = 0; i < n; i++) {
        char c = t[i];
        if ((r->rule == T_DIGITS && (c < '0' || c > '9')) ||
            (r->rule == T_PRINTABLE && (c < 0x20 || c > 0x7E))) {
            lep_priv_set_err(err, errlen, "%s '%s': expected %.0f to %.0f %s", label, t, in->min,
                             in->max,
                             r->rule == T_DIGITS ? "digits" : "printable ASCII characters");
            return LEP_E_ARG;
        }
    }
    return LEP_OK;
}

static int check_member(const void *p, const opt_row *r, const char *label, char *err,
                        size_t errlen)
{
    char range[160];
    double v;
    switch (r->store) {
    case S_BOOL:
    case S_U64:
        return LEP_OK;
    case S_CHARS:
        return check_text(r, label, (const char *)p, err, errlen);
    case S_DOUBLES: {
        const double *d = (const double *)p;
        size_t i;
        for (i = 0; i < r->size / sizeof(double); i++) {
            if (!lep_priv_row_in_range(r, d[i])) {
                lep_priv_row_range(r, range, sizeof range);
                lep_priv_set_err(err, errlen, "%s: value %zu is %g: expected %s", label, i + 1,
                                 d[i], range);
                return LEP_E_ARG;
            }
        }
        return LEP_OK;
    }
    default:
        break;
    }
    v = number_of(p, r);
    if (lep_priv_row_in_range(r, v))
        return LEP_OK;
    lep_priv_row_range(r, range, sizeof range);
    lep_priv_set_err(err, errlen, "%s %g: expected %s", label, v, range);
    return LEP_E_ARG;
}

int lep_priv_row_check(const void *base, const opt_row *r, char *err, size_t errlen)
{
    return check_member(lep_priv_row_cmember(base, r), r, r->info.name, err, errlen);
}

/* ---- from and to text ---- */

static int parse_flag(const char *v, bool *out)
{
    if (v == NULL || strcmp(v, "1") == 0 || strcmp(v, "true") == 0 || strcmp(v, "True") == 0) {
        *out = true;
        return 0;
    }
    if (strcmp(v, "0") == 0 || strcmp(v, "false") == 0 || strcmp(v, "False") == 0) {
        *out = false;
        return 0;
    }
    return -1;
}

static bool blank_start(const char *v)
{
    return v[0] == ' ' || v[0] == '\t' || v[0] == '\n' || v[0] == '\r' || v[0] == '\f' ||
           v[0] == '\v';
}

/* Parse v into p (a copy of the member); -1 when it is not of the row's type. */
static int parse_value(void *p, const opt_row *r, const char *v)
{
    char *end = NULL;
    if (r->store == S_BOOL)
        return parse_flag(v, (bool *)p);
    if (v == NULL)
        return -1;
    if (r->store == S_CHARS) {
        size_t n = strlen(v);
        if (n >= r->size)
            return -1;
        memcpy(p, v, n + 1);
        return 0;
    }
    if (v[0] == '\0' || blank_start(v))
        return -1;
    if (r->store == S_DOUBLES) {
        double *d = (double *)p;
        size_t i, n = r->size / sizeof(double);
        const char *q = v;
        for (i = 0; i < n; i++) {
            errno = 0;
            d[i] = strtod(q, &end);
            if (end == q || blank_start(q) || errno == ERANGE || !lep_priv_row_in_range(r, d[i]) ||
                (i + 1 < n ? *end != ',' : *end != '\0'))
                return -1; /* also NaN and inf */
            q = end + 1;
        }
        return 0;
    }
    errno = 0;
    if (r->store == S_DOUBLE) {
        double d = strtod(v, &end);
        if (*end != '\0' || !lep_priv_row_in_range(r, d))
            return -1; /* also NaN, inf and overflow (HUGE_VAL) */
        *(double *)p = d;
        return 0;
    }
    if (r->store == S_U64 || r->store == S_U8 || r->store == S_UNSIGNED) {
        unsigned long long u;
        if (v[0] == '-' || v[0] == '+')
            return -1;
        u = strtoull(v, &end, 10);
        if (*end != '\0' || errno != 0)
            return -1;
        if (r->store == S_U64) {
            if ((double)u > r->info.max)
                return -1;
            *(uint64_t *)p = (uint64_t)u;
            return 0;
        }
        if ((double)u > r->info.max || (double)u < r->info.min)
            return -1;
        if (r->store == S_U8)
            *(uint8_t *)p = (uint8_t)u;
        else
            *(unsigned *)p = (unsigned)u;
        return 0;
    }
    {
        long l = strtol(v, &end, 10);
        if (*end != '\0' || errno != 0 || (double)l < r->info.min || (double)l > r->info.max)
            return -1;
        *(int *)p = (int)l;
        return 0;
    }
}

int lep_priv_row_set(void *base, const opt_row *r, const char *label, const char *value, char *err,
                     size_t errlen)
{
    unsigned char tmp[LEP_SIM_PATH_SIZE]; /* the largest member of any table */
    const lep_sim_option_info *in = &r->info;
    int rc;
    if (r->size > sizeof tmp)
        return LEP_E_ARG;
    memcpy(tmp, lep_priv_row_cmember(base, r), r->size);
    if (parse_value(tmp, r, value) != 0) {
        char range[160];
        if (r->store == S_BOOL) {
            lep_priv_set_err(err, errlen, "%s '%s': a flag takes no value, or 1, 0, true, false",
                             label, value);
        } else if (value == NULL) {
            lep_priv_set_err(err, errlen, "%s: needs a value (%s)", label,
                             in->arg ? in->arg : "text");
        } else if (r->store == S_CHARS) {
            lep_priv_set_err(err, errlen, "%s: longer than %.0f bytes", label,
                             r->rule == T_MODEL ? (double)(r->size - 1) : in->max);
        } else {
            lep_priv_row_range(r, range, sizeof range);
            lep_priv_set_err(err, errlen, "%s '%s': expected %s", label, value, range);
        }
        return LEP_E_ARG;
    }
    rc = check_member(tmp, r, label, err, errlen);
    if (rc != LEP_OK)
        return rc;
    memcpy(lep_priv_row_member(base, r), tmp, r->size);
    return LEP_OK;
}

/* The shortest of %.15g/%.17g that reads back as the same number. */
static void shortest(char *buf, size_t cap, double d)
{
    snprintf(buf, cap, "%.15g", d);
    if (strtod(buf, NULL) != d)
        snprintf(buf, cap, "%.17g", d);
}

int lep_priv_row_get(const void *base, const opt_row *r, char *buf, size_t cap, size_t *len)
{
    const void *p = lep_priv_row_cmember(base, r);
    char text[LEP_SIM_PATH_SIZE + 16];
    switch (r->store) {
    case S_BOOL:
        snprintf(text, sizeof text, "%d", *(const bool *)p ? 1 : 0);
        break;
    case S_INT:
        snprintf(text, sizeof text, "%d", *(const int *)p);
        break;
    case S_UNSIGNED:
        snprintf(text, sizeof text, "%u", *(const unsigned *)p);
        break;
    case S_U8:
        snprintf(text, sizeof text, "%u", (unsigned)*(const uint8_t *)p);
        break;
    case S_U64:
        snprintf(text, sizeof text, "%llu", (unsigned long long)*(const uint64_t *)p);
        break;
    case S_DOUBLE:
        shortest(text, sizeof text, *(const double *)p);
        break;
    case S_DOUBLES: {
        const double *d = (const double *)p;
        size_t i, at = 0;
        text[0] = '\0';
        for (i = 0; i < r->size / sizeof(double); i++) {
            if (i > 0)
                text[at++] = ',';
            shortest(text + at, sizeof text - at, d[i]);
            at += strlen(text + at);
        }
        break;
    }
    default:
        snprintf(text, sizeof text, "%.*s", (int)(r->size - 1), (const char *)p);
        break;
    }
    return lep_priv_text_out(text, buf, cap, len);
}

int lep_priv_text_out(const char *text, char *buf, size_t cap, size_t *len)
{
    size_t n = strlen(text);
    if (len != NULL)
        *len = n;
    if (buf == NULL || cap <= n) {
        if (buf != NULL && cap > 0)
            buf[0] = '\0';
        return LEP_E_BUFFER;
    }
    memcpy(buf, text, n + 1);
    return LEP_OK;
}
