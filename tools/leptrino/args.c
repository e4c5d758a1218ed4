/* Command-line parsing for the leptrino tool: one element at a time, with
 * one clear error line for every bad argument. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

void cli_args_init(cli_args *a, int argc, char **argv, const char *cmd)
{
    memset(a, 0, sizeof *a);
    a->argc = argc;
    a->argv = argv;
    a->next = 1; /* argv[0] is the command name */
    a->cmd = cmd;
}

void cli_args_error(cli_args *a, const char *fmt, ...)
{
    va_list ap;
    if (a->failed)
        return; /* one line per run */
    fprintf(stderr, "leptrino: %s: ", a->cmd);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, " (see 'leptrino %s --help')\n", a->cmd);
    a->failed = true;
}

bool cli_args_next(cli_args *a)
{
    if (a->failed)
        return false;
    for (;;) {
        const char *s;
        if (a->next >= a->argc)
            return false;
        s = a->argv[a->next++];
        a->cur = s;
        a->inline_value = NULL;
        a->name[0] = '\0';
        a->matched = false;
        if (!a->only_positional && strcmp(s, "--") == 0) {
            a->only_positional = true;
            continue;
        }
        a->positional = a->only_positional || s[0] != '-' || s[1] == '\0';
        if (!a->positional) {
            const char *eq = s[1] == '-' ? strchr(s, '=') : NULL;
            size_t n = eq != NULL ? (size_t)(eq - s) : strlen(s);
            if (n >= sizeof a->name)
                n = sizeof a->name - 1;
            memcpy(a->name, s, n);
            a->name[n] = '\0';
            if (eq != NULL)
                a->inline_value = eq + 1;
        }
        return true;
    }
}

bool cli_args_is(cli_args *a, const char *short_name, const char *long_name)
{
    if (a->positional || a->failed)
        return false;
    if ((short_name != NULL && strcmp(a->name, short_name) == 0) ||
        (long_name != NULL && strcmp(a->name, long_name) == 0)) {
        a->matched = true;
        return true;
    }
    return false;
}

bool cli_args_flag(cli_args *a)
{
    if (a->inline_value != NULL)
        cli_args_error(a, "option %s takes no value", a->name);
    return true;
}

const char *cli_args_value(cli_args *a)
{
    const char *v = a->inline_value;
    if (v == NULL) {
        if (a->next >= a->argc) {
            cli_args_error(a, "option %s needs a value", a->name);
            return NULL;
        }
        v = a->argv[a->next++];
    }
    if (v[0] == '\0') {
        cli_args_error(a, "option %s needs a non-empty value", a->name);
        return NULL;
    }
    return v;
}

double cli_args_double(cli_args *a, double lo, double hi, bool lo_exclusive)
{
    char *end = NULL;
    double d;
    const char *v = cli_args_value(a);
    if (v == NULL)
        return 0.0;
    errno = 0;
    d = strtod(v, &end);
    if (end == v || *end != '\0' || errno == ERANGE || !isfinite(d)) {
        cli_args_error(a, "option %s: '%s' is not a number", a->name, v);
        return 0.0;
    }
    if ((lo_exclusive ? d <= lo : d < lo) || d > hi) {
        cli_args_error(a, "option %s: %s is out of range (%s %g .. %g)", a->name, v,
                       lo_exclusive ? "above" : "from", lo, hi);
        return 0.0;
    }
    return d;
}

uint64_t cli_args_uint(cli_args *a, uint64_t lo, uint64_t hi)
{
    char *end = NULL;
    unsigned long long u;
    const char *v = cli_args_value(a);
    if (v == NULL)
        return 0;
    if (v[0] == '-') {
        cli_args_error(a, "option %s: %s is out of range (%llu .. %llu)", a->name, v,
                       (unsigned long long)lo, (unsigned long long)hi);
        return 0;
    }
    errno = 0;
    u = strtoull(v, &end, 10);
    if (end == v || *end != '\0' || v[0] == '+' || v[0] == ' ') {
        cli_args_error(a, "option %s: '%s' is not a whole number", a->name, v);
        return 0;
    }
    if (errno == ERANGE || u < lo || u > hi) {
        cli_args_error(a, "option %s: %s is out of range (%llu .. %llu)", a->name, v,
                       (unsigned long long)lo, (unsigned long long)hi);
        return 0;
    }
    return (uint64_t)u;
}

void cli_args_unknown(cli_args *a)
{
    if (a->positional)
        cli_args_error(a, "unexpected argument '%s'", a->cur);
    else
        cli_args_error(a, "unknown option '%s'", a->name);
}

bool cli_args_doubles(cli_args *a, double *out, size_t n)
{
    const char *v = cli_args_value(a);
    const char *p = v;
    size_t i;
    if (v == NULL)
        return false;
    for (i = 0; i < n; ++i) {
        char *end = NULL;
        errno = 0;
        out[i] = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(out[i]) ||
            (i + 1 < n ? *end != ',' : *end != '\0')) {
            cli_args_error(a, "option %s: '%s' is not %lu comma-separated numbers", a->name, v,
                           (unsigned long)n);
            return false;
        }
        p = end + 1;
    }
    return true;
}

bool cli_args_help(cli_args *a)
{
    if (!cli_args_is(a, "-h", "--help"))
        return false;
    cli_args_flag(a);
    if (!a->failed && a->next < a->argc) /* docs/cli.md: anything after --help is exit 2 */
        cli_args_error(a, "unexpected argument '%s' after %s", a->argv[a->next], a->name);
    return !a->failed;
}
