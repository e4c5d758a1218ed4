/* A minimal streaming JSON writer for leptrino-bench's single output object. */
#include <math.h>
#include <stdio.h>

#include "bench.h"

static int g_first[32] = { 1 };
static int g_depth;

static void key_of(const char *key)
{
    if (!g_first[g_depth]) {
        fputc(',', stdout);
    }
    g_first[g_depth] = 0;
    if (key != NULL) {
        const char *c;
        fputc('"', stdout);
        for (c = key; *c; c++) {
            if (*c == '"' || *c == '\\') {
                fputc('\\', stdout);
            }
            fputc(*c, stdout);
        }
        fputs("\":", stdout);
    }
}

static void push(char open)
{
    fputc(open, stdout);
    if (g_depth < 31) {
        g_depth++;
    }
    g_first[g_depth] = 1;
}

void json_open(const char *key)
{
    key_of(key);
    push('{');
}

void json_close(void)
{
    fputc('}', stdout);
    g_depth--;
}

void json_open_array(const char *key)
{
    key_of(key);
    push('[');
}

void json_close_array(void)
{
    fputc(']', stdout);
    g_depth--;
}

void json_num(const char *key, double v)
{
    key_of(key);
    if (isfinite(v)) {
        printf("%.6g", v);
    } else {
        fputs("null", stdout);
    }
}

void json_int(const char *key, long long v)
{
    key_of(key);
    printf("%lld", v);
}

void json_str(const char *key, const char *v)
{
    const unsigned char *c;
    key_of(key);
    if (v == NULL) {
        fputs("null", stdout);
        return;
    }
    fputc('"', stdout);
    for (c = (const unsigned char *)v; *c; c++) {
        if (*c == '"' || *c == '\\') {
            printf("\\%c", *c);
        } else if (*c < 0x20) {
            printf("\\u%04x", *c);
        } else {
            fputc(*c, stdout);
        }
    }
    fputc('"', stdout);
}

void json_bool(const char *key, int v)
{
    key_of(key);
    fputs(v ? "true" : "false", stdout);
}

void json_null(const char *key)
{
    key_of(key);
    fputs("null", stdout);
}

void json_end(void)
{
    fputc('\n', stdout);
    fflush(stdout);
}
