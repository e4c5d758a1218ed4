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

/* How a row's value is stored in lep_sim_options. */
enum store { S_BOOL, S_INT, S_U8, S_U64, S_DOUBLE, S_CHARS, S_DOUBLES };

/* Extra checks of a text value beyond its length. */
enum text_rule { T_ANY, T_DIGITS, T_PRINTABLE, T_MODEL };

typedef struct row {
    lep_sim_option_info info; /* first: lep_sim_option_at returns &row.info */
    const char *field;        /* the lep_sim_options member */
    size_t offset, size;
    enum store store;
    enum text_rule rule;
} row;

#define F(m) #m, offsetof(lep_sim_options, m), sizeof(((lep_sim_options *)0)->m)
#define NUM(name, type, arg, help, def, lo, hi, excl, member, store)          \
    {                                                                         \
        { name, type, arg, help, def, lo, hi, excl }, F(member), store, T_ANY \
    }
#define TXT(name, type, arg, help, def, lo, hi, member, rule)                   \
    {                                                                           \
        { name, type, arg, help, def, lo, hi, false }, F(member), S_CHARS, rule \
    }

/* Time options stop well short of 9.2e9 s, where nanoseconds leave int64. */
#define MAX_SECONDS 1e6
#define MAX_MS 86400000.0

/* Order: identity, signal, faults, port (the order of help screens). */
static const row rows[] = {
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

/* a equals b, where '_' in a also matches '-' in b. */
static bool name_eq(const char *a, const char *b)
{
    for (; *a != '\0' && *b != '\0'; a++, b++) {
        if (*a != *b && !(*a == '_' && *b == '-'))
            return false;
    }
    return *a == '\0' && *b == '\0';
}

static const row *find_row(const char *name)
{
    size_t i;
    if (name == NULL)
        return NULL;
    for (i = 0; i < N_ROWS; i++)
        if (name_eq(name, rows[i].info.name) || strcmp(name, rows[i].field) == 0)
            return &rows[i];
    return NULL;
}

const lep_sim_option_info *lep_sim_option_find(const char *name)
{
    const row *r = find_row(name);
    return r ? &r->info : NULL;
}

/* ---- reading and writing a row's member ---- */

static void *member(lep_sim_options *o, const row *r)
{
    return (unsigned char *)o + r->offset;
}

static const void *cmember(const lep_sim_options *o, const row *r)
{
    return (const unsigned char *)o + r->offset;
}

/* The value of a numeric member as a double (S_U64: not needed, full range). */
static double number_of(const lep_sim_options *o, const row *r)
{
    const void *p = cmember(o, r);
    switch (r->store) {
    case S_INT:
        return (double)*(const int *)p;
    case S_U8:
        return (double)*(const uint8_t *)p;
    case S_DOUBLE:
        return *(const double *)p;
    default:
        return 0.0;
    }
}

/* ---- checks ---- */

static void range_text(const row *r, char *buf, size_t cap)
{
    const lep_sim_option_info *in = &r->info;
    if (in->type == LEP_SIM_OPT_DOUBLE && in->min_exclusive)
        snprintf(buf, cap, "a number > %.15g and <= %.15g", in->min, in->max);
    else if (in->type == LEP_SIM_OPT_DOUBLE)
        snprintf(buf, cap, "a number from %.15g to %.15g", in->min, in->max);
    else if (r->store == S_DOUBLES)
        snprintf(buf, cap, "%zu comma-separated numbers (%s), each from %.15g to %.15g",
                 r->size / sizeof(double), in->arg, in->min, in->max);
    else if (in->type == LEP_SIM_OPT_UINT && r->store == S_U64)
        snprintf(buf, cap, "an integer from 0 to 18446744073709551615");
    else
        snprintf(buf, cap, "an integer from %.0f to %.0f", in->min, in->max);
}

static bool in_range(const lep_sim_option_info *in, double v)
{
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
static int check_text(const row *r, const char *t, char *err, size_t errlen)
{
    const lep_sim_option_info *in = &r->info;
    size_t n = 0, i;
    while (n < r->size && t[n] != '\0')
        n++;
    if (n == r->size) {
        lep_priv_set_err(err, errlen, "%s: not NUL-terminated within its %zu bytes", in->name,
                         r->size);
        return LEP_E_ARG;
    }
    if (r->rule == T_MODEL) {
        if (!known_model(t)) {
            lep_priv_set_err(err, errlen, "%s '%s': unknown (known: %s)", in->name, t,
                             "CFS018CA201U, CFS034CA301U, PFS055YA501U6, PFS080YS102U6");
            return LEP_E_ARG;
        }
        return LEP_OK;
    }
    if (n == 0 && in->default_text == NULL)
        return LEP_OK; /* an optional text left empty: not used */
    if ((double)n < in->min || (double)n > in->max) {
        lep_priv_set_err(err, errlen, "%s '%s': expected %.0f to %.0f %s", in->name, t, in->min,
                         in->max, r->rule == T_DIGITS ? "digits" : "characters");
        return LEP_E_ARG;
    }
    for (i = 0; i < n; i++) {
        char c = t[i];
        if ((r->rule == T_DIGITS && (c < '0' || c > '9')) ||
            (r->rule == T_PRINTABLE && (c < 0x20 || c > 0x7E))) {
            lep_priv_set_err(err, errlen, "%s '%s': expected %.0f to %.0f %s", in->name, t, in->min,
                             in->max,
                             r->rule == T_DIGITS ? "digits" : "printable ASCII characters");
            return LEP_E_ARG;
        }
    }
    return LEP_OK;
}

/* Check one row's member in o. */
static int check_row(const lep_sim_options *o, const row *r, char *err, size_t errlen)
{
    char range[160];
    double v;
    switch (r->store) {
    case S_BOOL:
    case S_U64:
        return LEP_OK;
    case S_CHARS:
        return check_text(r, (const char *)cmember(o, r), err, errlen);
    case S_DOUBLES: {
        const double *d = (const double *)cmember(o, r);
        size_t i;
        for (i = 0; i < r->size / sizeof(double); i++) {
            if (!in_range(&r->info, d[i])) {
                range_text(r, range, sizeof range);
                lep_priv_set_err(err, errlen, "%s: value %zu is %g: expected %s", r->info.name,
                                 i + 1, d[i], range);
                return LEP_E_ARG;
            }
        }
        return LEP_OK;
    }
    default:
        break;
    }
    v = number_of(o, r);
    if (in_range(&r->info, v))
        return LEP_OK;
    range_text(r, range, sizeof range);
    lep_priv_set_err(err, errlen, "%s %g: expected %s", r->info.name, v, range);
    return LEP_E_ARG;
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
        int rc = check_row(o, &rows[i], err, errlen);
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
    if (o->stall_after_s > 0 && o->stall_ms == 0) {
        lep_priv_set_err(err, errlen, "stall-after needs stall (how many ms to stall)");
        return LEP_E_ARG;
    }
    return LEP_OK;
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

/* Parse v into the member of tmp; -1 when it is not of the row's type. */
static int parse_value(lep_sim_options *tmp, const row *r, const char *v)
{
    void *p = member(tmp, r);
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
            if (end == q || blank_start(q) || errno == ERANGE || !in_range(&r->info, d[i]) ||
                (i + 1 < n ? *end != ',' : *end != '\0'))
                return -1; /* also NaN and inf */
            q = end + 1;
        }
        return 0;
    }
    errno = 0;
    if (r->store == S_DOUBLE) {
        double d = strtod(v, &end);
        if (*end != '\0' || !in_range(&r->info, d))
            return -1; /* also NaN, inf and overflow (HUGE_VAL) */
        *(double *)p = d;
        return 0;
    }
    if (r->store == S_U64 || r->store == S_U8) {
        unsigned long long u;
        if (v[0] == '-' || v[0] == '+')
            return -1;
        u = strtoull(v, &end, 10);
        if (*end != '\0' || errno != 0)
            return -1;
        if (r->store == S_U64) {
            *(uint64_t *)p = (uint64_t)u;
            return 0;
        }
        if ((double)u > r->info.max)
            return -1;
        *(uint8_t *)p = (uint8_t)u;
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

int lep_sim_option_set(lep_sim_options *o, const char *name, const char *value, char *err,
                       size_t errlen)
{
    const row *r;
    lep_sim_options tmp;
    int rc;
    if (err != NULL && errlen > 0)
        err[0] = '\0';
    if (o == NULL || name == NULL) {
        lep_priv_set_err(err, errlen, "no options or no option name given");
        return LEP_E_ARG;
    }
    r = find_row(name);
    if (r == NULL) {
        lep_priv_set_err(err, errlen, "unknown virtual sensor option '%s'", name);
        return LEP_E_ARG;
    }
    tmp = *o;
    if (parse_value(&tmp, r, value) != 0) {
        char range[160];
        const lep_sim_option_info *in = &r->info;
        if (r->store == S_BOOL) {
            lep_priv_set_err(err, errlen, "%s '%s': a flag takes no value, or 1, 0, true, false",
                             in->name, value);
        } else if (value == NULL) {
            lep_priv_set_err(err, errlen, "%s: needs a value (%s)", in->name,
                             in->arg ? in->arg : "text");
        } else if (r->store == S_CHARS) {
            lep_priv_set_err(err, errlen, "%s: longer than %.0f bytes", in->name,
                             r->rule == T_MODEL ? (double)(r->size - 1) : in->max);
        } else {
            range_text(r, range, sizeof range);
            lep_priv_set_err(err, errlen, "%s '%s': expected %s", in->name, value, range);
        }
        return LEP_E_ARG;
    }
    rc = check_row(&tmp, r, err, errlen);
    if (rc != LEP_OK)
        return rc;
    *o = tmp;
    return LEP_OK;
}

/* The shortest of %.15g/%.17g that reads back as the same number. */
static int shortest(char *buf, size_t buflen, double d)
{
    char tmp[40];
    snprintf(tmp, sizeof tmp, "%.15g", d);
    if (strtod(tmp, NULL) != d)
        snprintf(tmp, sizeof tmp, "%.17g", d);
    return snprintf(buf, buflen, "%s", tmp);
}

int lep_sim_option_get(const lep_sim_options *o, const char *name, char *buf, size_t buflen)
{
    const row *r = find_row(name);
    const void *p;
    int n;
    if (o == NULL || r == NULL || buf == NULL || buflen == 0)
        return LEP_E_ARG;
    p = cmember(o, r);
    switch (r->store) {
    case S_BOOL:
        n = snprintf(buf, buflen, "%d", *(const bool *)p ? 1 : 0);
        break;
    case S_INT:
        n = snprintf(buf, buflen, "%d", *(const int *)p);
        break;
    case S_U8:
        n = snprintf(buf, buflen, "%u", (unsigned)*(const uint8_t *)p);
        break;
    case S_U64:
        n = snprintf(buf, buflen, "%llu", (unsigned long long)*(const uint64_t *)p);
        break;
    case S_DOUBLE:
        n = shortest(buf, buflen, *(const double *)p);
        break;
    case S_DOUBLES: {
        const double *d = (const double *)p;
        size_t i, at = 0;
        n = 0;
        for (i = 0; i < r->size / sizeof(double) && n >= 0 && at < buflen; i++) {
            if (i > 0)
                buf[at++] = ',';
            n = at < buflen ? shortest(buf + at, buflen - at, d[i]) : -1;
            at += n >= 0 ? (size_t)n : 0u;
        }
        if (n >= 0)
            n = (int)at;
        break;
    }
    default:
        n = snprintf(buf, buflen, "%.*s", (int)(r->size - 1), (const char *)p);
        break;
    }
    if (n < 0 || (size_t)n >= buflen) {
        buf[0] = '\0';
        return LEP_E_BUFFER;
    }
    return LEP_OK;
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
