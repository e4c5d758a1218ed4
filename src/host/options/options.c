/* The options handle (leptrino/options.h): the session's and the virtual
 * sensor's tables behind one set of functions by name. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "leptrino/options.h"
#include "options_priv.h"

/* ---- the two tables as one ---- */

static const opt_row *row_at(size_t i, int *is_sim)
{
    size_t ns, nm;
    const opt_row *s = lep_priv_session_rows(&ns);
    const opt_row *m = lep_priv_sim_rows(&nm);
    if (i < ns) {
        *is_sim = 0;
        return &s[i];
    }
    if (i - ns < nm) {
        *is_sim = 1;
        return &m[i - ns];
    }
    return NULL;
}

/* a equals b, where '_' in a also matches '-' in b. */
static bool same_name(const char *a, const char *b)
{
    for (; *a != '\0' && *b != '\0'; a++, b++) {
        if (*a != *b && !(*a == '_' && *b == '-'))
            return false;
    }
    return *a == '\0' && *b == '\0';
}

const opt_row *lep_priv_options_find(const lep_options *o, const char *name, const void **base)
{
    size_t i;
    if (name == NULL)
        return NULL;
    for (i = 0; i < lep_option_count(); i++) {
        int is_sim = 0;
        const opt_row *r = row_at(i, &is_sim);
        if (same_name(name, r->public_name)) {
            if (base != NULL)
                *base = is_sim ? (o != NULL ? (const void *)&o->so.sim : NULL) : (const void *)o;
            return r;
        }
    }
    return NULL;
}

static void sync_port(lep_options *o)
{
    o->so.port = o->port[0] != '\0' ? o->port : NULL;
}

void lep_priv_options_from(lep_options *o, const lep_session_options *so)
{
    o->so = *so;
    snprintf(o->port, sizeof o->port, "%s", so->port != NULL ? so->port : "");
    sync_port(o);
}

/* ---- the handle ---- */

lep_options *lep_options_new(void)
{
    lep_options *o = calloc(1, sizeof *o);
    if (o == NULL)
        return NULL;
    lep_session_options_init(&o->so);
    sync_port(o);
    return o;
}

lep_options *lep_options_copy(const lep_options *o)
{
    lep_options *c;
    if (o == NULL)
        return NULL;
    c = malloc(sizeof *c);
    if (c == NULL)
        return NULL;
    *c = *o;
    sync_port(c);
    return c;
}

void lep_options_free(lep_options *o)
{
    free(o);
}

static void clear_err(char *err, size_t errlen)
{
    if (err != NULL && errlen > 0)
        err[0] = '\0';
}

static const opt_row *find_or_say(const lep_options *o, const char *name, const void **base,
                                  char *err, size_t errlen)
{
    const opt_row *r;
    if (o == NULL || name == NULL) {
        lep_priv_set_err(err, errlen, "no options handle or no option name given");
        return NULL;
    }
    r = lep_priv_options_find(o, name, base);
    if (r == NULL)
        lep_priv_set_err(err, errlen, "unknown option '%s'", name);
    return r;
}

int lep_options_set(lep_options *o, const char *name, const char *value, char *err, size_t errlen)
{
    const void *base;
    const opt_row *r;
    clear_err(err, errlen);
    r = find_or_say(o, name, &base, err, errlen);
    if (r == NULL)
        return LEP_E_ARG;
    if (r->scope != LEP_SCOPE_SIM && strcmp(r->public_name, "limit") == 0 && value != NULL &&
        strchr(value, '=') != NULL) {
        double limit[LEP_AXES];
        if (lep_limits_parse(value, limit) != LEP_OK) {
            lep_priv_set_err(err, errlen,
                             "limit '%s': expected AXIS=VALUE pairs separated by commas, AXIS one "
                             "of fx fy fz mx my mz (each once), VALUE a number > 0",
                             value);
            return LEP_E_ARG;
        }
        memcpy(o->so.limit, limit, sizeof limit);
        return LEP_OK;
    }
    {
        void *mbase = r->scope == LEP_SCOPE_SIM ? (void *)&o->so.sim : (void *)o;
        int rc = lep_priv_row_set(mbase, r, r->public_name, value, err, errlen);
        sync_port(o);
        return rc;
    }
}

/* The text of one number as the table reads it back. */
static void number_text(char *buf, size_t cap, double v)
{
    snprintf(buf, cap, "%.17g", v);
}

int lep_options_set_int(lep_options *o, const char *name, int64_t value, char *err, size_t errlen)
{
    const opt_row *r;
    char text[32];
    clear_err(err, errlen);
    r = find_or_say(o, name, NULL, err, errlen);
    if (r == NULL)
        return LEP_E_ARG;
    if (r->info.type == LEP_SIM_OPT_FLAG && value != 0 && value != 1) {
        lep_priv_set_err(err, errlen, "%s %lld: a flag is 0 or 1", r->public_name,
                         (long long)value);
        return LEP_E_ARG;
    }
    if (r->info.type == LEP_SIM_OPT_STRING || r->info.type == LEP_SIM_OPT_CHOICE ||
        r->info.type == LEP_SIM_OPT_NUMBERS) {
        lep_priv_set_err(err, errlen, "%s: not an integer option (%s)", r->public_name,
                         r->info.type == LEP_SIM_OPT_NUMBERS ? "numbers: set_doubles" : "text");
        return LEP_E_ARG;
    }
    snprintf(text, sizeof text, "%lld", (long long)value);
    return lep_options_set(o, name, text, err, errlen);
}

int lep_options_set_double(lep_options *o, const char *name, double value, char *err, size_t errlen)
{
    const opt_row *r;
    char text[40];
    clear_err(err, errlen);
    r = find_or_say(o, name, NULL, err, errlen);
    if (r == NULL)
        return LEP_E_ARG;
    if (r->info.type != LEP_SIM_OPT_DOUBLE && r->info.type != LEP_SIM_OPT_INT &&
        r->info.type != LEP_SIM_OPT_UINT) {
        lep_priv_set_err(err, errlen, "%s: not a number option", r->public_name);
        return LEP_E_ARG;
    }
    if (r->info.type != LEP_SIM_OPT_DOUBLE) {
        if (!isfinite(value) || value != floor(value) || fabs(value) > 9007199254740992.0) {
            lep_priv_set_err(err, errlen, "%s %g: expected an integer", r->public_name, value);
            return LEP_E_ARG;
        }
        snprintf(text, sizeof text, "%.0f", value);
    } else {
        if (!isfinite(value)) {
            lep_priv_set_err(err, errlen, "%s %g: expected a finite number", r->public_name, value);
            return LEP_E_ARG;
        }
        number_text(text, sizeof text, value);
    }
    return lep_options_set(o, name, text, err, errlen);
}

int lep_options_set_doubles(lep_options *o, const char *name, const double *values, size_t n,
                            char *err, size_t errlen)
{
    const opt_row *r;
    char text[40 * 16];
    size_t i, at = 0, want;
    clear_err(err, errlen);
    r = find_or_say(o, name, NULL, err, errlen);
    if (r == NULL)
        return LEP_E_ARG;
    if (r->info.type == LEP_SIM_OPT_DOUBLE && n == 1 && values != NULL)
        return lep_options_set_double(o, name, values[0], err, errlen);
    if (r->store != S_DOUBLES) {
        lep_priv_set_err(err, errlen, "%s: not a list of numbers", r->public_name);
        return LEP_E_ARG;
    }
    want = r->size / sizeof(double);
    if (values == NULL || n != want) {
        lep_priv_set_err(err, errlen, "%s: expected %zu numbers (%s), got %zu", r->public_name,
                         want, r->info.arg, values == NULL ? (size_t)0 : n);
        return LEP_E_ARG;
    }
    for (i = 0; i < n; i++) {
        if (!isfinite(values[i])) {
            lep_priv_set_err(err, errlen, "%s: value %zu is %g: expected a finite number",
                             r->public_name, i + 1, values[i]);
            return LEP_E_ARG;
        }
        if (i > 0)
            text[at++] = ',';
        number_text(text + at, sizeof text - at, values[i]);
        at += strlen(text + at);
    }
    return lep_options_set(o, name, text, err, errlen);
}

int lep_options_get(const lep_options *o, const char *name, char *buf, size_t cap, size_t *len)
{
    const void *base;
    const opt_row *r = o != NULL ? lep_priv_options_find(o, name, &base) : NULL;
    if (len != NULL)
        *len = 0;
    if (r == NULL)
        return LEP_E_ARG;
    return lep_priv_row_get(base, r, buf, cap, len);
}

int lep_options_get_int(const lep_options *o, const char *name, int64_t *out)
{
    const void *base;
    const opt_row *r = o != NULL ? lep_priv_options_find(o, name, &base) : NULL;
    const void *p;
    if (r == NULL || out == NULL)
        return LEP_E_ARG;
    p = lep_priv_row_cmember(base, r);
    switch (r->store) {
    case S_BOOL:
        *out = *(const bool *)p ? 1 : 0;
        return LEP_OK;
    case S_INT:
        *out = *(const int *)p;
        return LEP_OK;
    case S_UNSIGNED:
        *out = (int64_t) * (const unsigned *)p;
        return LEP_OK;
    case S_U8:
        *out = *(const uint8_t *)p;
        return LEP_OK;
    case S_U64:
        if (*(const uint64_t *)p > (uint64_t)INT64_MAX)
            return LEP_E_ARG;
        *out = (int64_t) * (const uint64_t *)p;
        return LEP_OK;
    default:
        return LEP_E_ARG;
    }
}

int lep_options_get_double(const lep_options *o, const char *name, double *out)
{
    const void *base;
    const opt_row *r = o != NULL ? lep_priv_options_find(o, name, &base) : NULL;
    int64_t i;
    if (r == NULL || out == NULL)
        return LEP_E_ARG;
    if (r->store == S_DOUBLE) {
        *out = *(const double *)lep_priv_row_cmember(base, r);
        return LEP_OK;
    }
    if (r->store == S_BOOL || r->store == S_CHARS || r->store == S_DOUBLES ||
        lep_options_get_int(o, name, &i) != LEP_OK)
        return LEP_E_ARG;
    *out = (double)i;
    return LEP_OK;
}

int lep_options_get_doubles(const lep_options *o, const char *name, double *out, size_t cap,
                            size_t *n)
{
    const void *base;
    const opt_row *r = o != NULL ? lep_priv_options_find(o, name, &base) : NULL;
    size_t count, i;
    const double *d;
    if (n != NULL)
        *n = 0;
    if (r == NULL || (out == NULL && cap > 0))
        return LEP_E_ARG;
    if (r->store == S_DOUBLE) {
        if (n != NULL)
            *n = 1;
        if (cap > 0)
            return lep_options_get_double(o, name, out);
        return LEP_OK;
    }
    if (r->store != S_DOUBLES)
        return LEP_E_ARG;
    count = r->size / sizeof(double);
    d = (const double *)lep_priv_row_cmember(base, r);
    for (i = 0; i < count && i < cap; i++)
        out[i] = d[i];
    if (n != NULL)
        *n = count;
    return LEP_OK;
}

int lep_options_check(const lep_options *o, char *err, size_t errlen)
{
    size_t i;
    int rc;
    clear_err(err, errlen);
    if (o == NULL) {
        lep_priv_set_err(err, errlen, "no options handle given");
        return LEP_E_ARG;
    }
    for (i = 0; i < lep_option_count(); i++) {
        int is_sim = 0;
        const opt_row *r = row_at(i, &is_sim);
        rc =
            lep_priv_row_check(is_sim ? (const void *)&o->so.sim : (const void *)o, r, err, errlen);
        if (rc != LEP_OK)
            return rc;
    }
    rc = lep_sim_options_check(&o->so.sim, err, errlen);
    if (rc != LEP_OK)
        return rc;
    return lep_priv_session_options_check(&o->so, err, errlen);
}

/* ---- the table ---- */

size_t lep_option_count(void)
{
    size_t ns, nm;
    (void)lep_priv_session_rows(&ns);
    (void)lep_priv_sim_rows(&nm);
    return ns + nm;
}

int lep_option_index(const char *name)
{
    size_t i;
    const opt_row *r = lep_priv_options_find(NULL, name, NULL);
    if (r == NULL)
        return LEP_E_ARG;
    for (i = 0; i < lep_option_count(); i++) {
        int is_sim = 0;
        if (row_at(i, &is_sim) == r)
            return (int)i;
    }
    return LEP_E_ARG;
}

const char *lep_option_name(size_t i)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    return r != NULL ? r->public_name : NULL;
}

int lep_option_type(size_t i)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    if (r == NULL)
        return LEP_E_ARG;
    switch (r->info.type) {
    case LEP_SIM_OPT_FLAG:
        return LEP_OPT_FLAG;
    case LEP_SIM_OPT_INT:
    case LEP_SIM_OPT_UINT:
        return LEP_OPT_INT;
    case LEP_SIM_OPT_DOUBLE:
        return LEP_OPT_DOUBLE;
    case LEP_SIM_OPT_CHOICE:
        return LEP_OPT_CHOICE;
    case LEP_SIM_OPT_NUMBERS:
        return LEP_OPT_NUMBERS;
    default:
        return LEP_OPT_STRING;
    }
}

int lep_option_scope(size_t i)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    return r != NULL ? r->scope : LEP_E_ARG;
}

const char *lep_option_arg(size_t i)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    return r != NULL && r->info.arg != NULL ? r->info.arg : "";
}

const char *lep_option_help(size_t i)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    return r != NULL ? r->info.help : "";
}

const char *lep_option_default(size_t i)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    return r != NULL && r->info.default_text != NULL ? r->info.default_text : "";
}

double lep_option_min(size_t i)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    return r != NULL ? r->info.min : 0.0;
}

double lep_option_max(size_t i)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    return r != NULL ? r->info.max : 0.0;
}

int lep_option_min_exclusive(size_t i)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    return r != NULL && r->info.min_exclusive ? 1 : 0;
}

size_t lep_option_numbers(size_t i)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    if (r == NULL)
        return 0;
    if (r->store == S_DOUBLES)
        return r->size / sizeof(double);
    if (r->info.type == LEP_SIM_OPT_INT || r->info.type == LEP_SIM_OPT_UINT ||
        r->info.type == LEP_SIM_OPT_DOUBLE)
        return 1;
    return 0;
}

const char *lep_option_choice(size_t i, size_t j)
{
    int is_sim = 0;
    const opt_row *r = row_at(i, &is_sim);
    const char *const *m;
    size_t k;
    if (r == NULL || r->info.type != LEP_SIM_OPT_CHOICE)
        return NULL;
    m = lep_sim_models(); /* the only choice: the model presets */
    for (k = 0; k < j && m[k] != NULL; k++)
        ;
    return m[k];
}
