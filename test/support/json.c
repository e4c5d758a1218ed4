/* Minimal JSON reader for the test vectors (see json.h). */
#include "json.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hex.h"

#define MAX_DEPTH 64

struct lep_json {
    int type;
    bool b;
    double num;
    char *str;        /* LEP_JSON_STRING */
    size_t n;         /* elements or members */
    lep_json **items; /* LEP_JSON_ARRAY, LEP_JSON_OBJECT */
    char **keys;      /* LEP_JSON_OBJECT */
};

typedef struct parser {
    const char *p;
    const char *end;
    const char *start;
    char *err;
    size_t errcap;
    bool failed;
} parser;

static void fail(parser *ps, const char *what)
{
    const char *q;
    unsigned line = 1;
    if (ps->failed) {
        return;
    }
    ps->failed = true;
    for (q = ps->start; q < ps->p && q < ps->end; q++) {
        if (*q == '\n') {
            line++;
        }
    }
    if (ps->err != NULL && ps->errcap > 0) {
        snprintf(ps->err, ps->errcap, "line %u: %s", line, what);
    }
}

static void skip_ws(parser *ps)
{
    while (ps->p < ps->end &&
           (*ps->p == ' ' || *ps->p == '\t' || *ps->p == '\n' || *ps->p == '\r')) {
        ps->p++;
    }
}

static lep_json *new_value(parser *ps, int type)
{
    lep_json *v = (lep_json *)calloc(1, sizeof(*v));
    if (v == NULL) {
        fail(ps, "out of memory");
        return NULL;
    }
    v->type = type;
    return v;
}

static bool literal(parser *ps, const char *word)
{
    size_t n = strlen(word);
    if ((size_t)(ps->end - ps->p) >= n && memcmp(ps->p, word, n) == 0) {
        ps->p += n;
        return true;
    }
    return false;
}

static bool read_u4(parser *ps, unsigned long *out)
{
    unsigned long v = 0;
    int i;
    if (ps->end - ps->p < 4) {
        fail(ps, "short \\u escape");
        return false;
    }
    for (i = 0; i < 4; i++) {
        int d = lep_hex_digit(ps->p[i]);
        if (d < 0) {
            fail(ps, "bad \\u escape");
            return false;
        }
        v = (v << 4) | (unsigned long)d;
    }
    ps->p += 4;
    *out = v;
    return true;
}

static size_t put_utf8(char *dst, unsigned long cp)
{
    if (cp < 0x80u) {
        dst[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800u) {
        dst[0] = (char)(0xC0u | (cp >> 6));
        dst[1] = (char)(0x80u | (cp & 0x3Fu));
        return 2;
    }
    if (cp < 0x10000u) {
        dst[0] = (char)(0xE0u | (cp >> 12));
        dst[1] = (char)(0x80u | ((cp >> 6) & 0x3Fu));
        dst[2] = (char)(0x80u | (cp & 0x3Fu));
        return 3;
    }
    dst[0] = (char)(0xF0u | (cp >> 18));
    dst[1] = (char)(0x80u | ((cp >> 12) & 0x3Fu));
    dst[2] = (char)(0x80u | ((cp >> 6) & 0x3Fu));
    dst[3] = (char)(0x80u | (cp & 0x3Fu));
    return 4;
}

/* Parse a string at ps->p (on the opening quote); malloc'd, NUL-terminated. */
static char *parse_string_raw(parser *ps)
{
    const char *q;
    char *out;
    size_t n = 0;
    if (ps->p >= ps->end || *ps->p != '"') {
        fail(ps, "expected a string");
        return NULL;
    }
    ps->p++;
    /* Decoded text is never longer than the source text. */
    for (q = ps->p; q < ps->end && *q != '"'; q++) {
        if (*q == '\\') {
            q++;
        }
    }
    out = (char *)malloc((size_t)(q - ps->p) + 1u);
    if (out == NULL) {
        fail(ps, "out of memory");
        return NULL;
    }
    while (ps->p < ps->end && *ps->p != '"') {
        char c = *ps->p++;
        if ((unsigned char)c < 0x20u) {
            fail(ps, "control character in string");
            free(out);
            return NULL;
        }
        if (c != '\\') {
            out[n++] = c;
            continue;
        }
        if (ps->p >= ps->end) {
            break;
        }
        c = *ps->p++;
        switch (c) {
        case '"':
            out[n++] = '"';
            break;
        case '\\':
            out[n++] = '\\';
            break;
        case '/':
            out[n++] = '/';
            break;
        case 'b':
            out[n++] = '\b';
            break;
        case 'f':
            out[n++] = '\f';
            break;
        case 'n':
            out[n++] = '\n';
            break;
        case 'r':
            out[n++] = '\r';
            break;
        case 't':
            out[n++] = '\t';
            break;
        case 'u': {
            unsigned long cp;
            if (!read_u4(ps, &cp)) {
                free(out);
                return NULL;
            }
            if (cp >= 0xD800u && cp < 0xDC00u && ps->end - ps->p >= 6 && ps->p[0] == '\\' &&
                ps->p[1] == 'u') {
                unsigned long lo;
                ps->p += 2;
                if (!read_u4(ps, &lo)) {
                    free(out);
                    return NULL;
                }
                if (lo >= 0xDC00u && lo < 0xE000u) {
                    cp = 0x10000u + ((cp - 0xD800u) << 10) + (lo - 0xDC00u);
                } else {
                    fail(ps, "bad surrogate pair");
                    free(out);
                    return NULL;
                }
            }
            /* At most 6 source characters give at most 4 bytes. */
            n += put_utf8(out + n, cp);
            break;
        }
        default:
            fail(ps, "bad escape in string");
            free(out);
            return NULL;
        }
    }
    if (ps->p >= ps->end) {
        fail(ps, "unterminated string");
        free(out);
        return NULL;
    }
    ps->p++; /* closing quote */
    out[n] = '\0';
    return out;
}

static lep_json *parse_value(parser *ps, int depth);

static bool push(parser *ps, lep_json *v, lep_json *item, char *key)
{
    lep_json **items = (lep_json **)realloc(v->items, (v->n + 1u) * sizeof(*items));
    if (items == NULL) {
        fail(ps, "out of memory");
        return false;
    }
    v->items = items;
    if (v->type == LEP_JSON_OBJECT) {
        char **keys = (char **)realloc(v->keys, (v->n + 1u) * sizeof(*keys));
        if (keys == NULL) {
            fail(ps, "out of memory");
            return false;
        }
        v->keys = keys;
        v->keys[v->n] = key;
    }
    v->items[v->n++] = item;
    return true;
}

static lep_json *parse_container(parser *ps, int depth, int type)
{
    char close = type == LEP_JSON_ARRAY ? ']' : '}';
    lep_json *v = new_value(ps, type);
    if (v == NULL) {
        return NULL;
    }
    ps->p++; /* [ or { */
    skip_ws(ps);
    if (ps->p < ps->end && *ps->p == close) {
        ps->p++;
        return v;
    }
    for (;;) {
        char *key = NULL;
        lep_json *item;
        skip_ws(ps);
        if (type == LEP_JSON_OBJECT) {
            key = parse_string_raw(ps);
            if (key == NULL) {
                break;
            }
            skip_ws(ps);
            if (ps->p >= ps->end || *ps->p != ':') {
                fail(ps, "expected ':'");
                free(key);
                break;
            }
            ps->p++;
        }
        item = parse_value(ps, depth + 1);
        if (item == NULL) {
            free(key);
            break;
        }
        if (!push(ps, v, item, key)) {
            free(key);
            lep_json_free(item);
            break;
        }
        skip_ws(ps);
        if (ps->p < ps->end && *ps->p == ',') {
            ps->p++;
            continue;
        }
        if (ps->p < ps->end && *ps->p == close) {
            ps->p++;
            return v;
        }
        fail(ps, type == LEP_JSON_ARRAY ? "expected ',' or ']'" : "expected ',' or '}'");
        break;
    }
    lep_json_free(v);
    return NULL;
}

static lep_json *parse_number(parser *ps)
{
    char buf[64];
    size_t n = 0;
    char *endp;
    lep_json *v;
    while (ps->p + n < ps->end && n < sizeof(buf) - 1u &&
           strchr("+-0123456789.eE", ps->p[n]) != NULL) {
        buf[n] = ps->p[n];
        n++;
    }
    buf[n] = '\0';
    if (n == 0) {
        fail(ps, "unexpected character");
        return NULL;
    }
    v = new_value(ps, LEP_JSON_NUMBER);
    if (v == NULL) {
        return NULL;
    }
    v->num = strtod(buf, &endp);
    if (*endp != '\0') {
        fail(ps, "bad number");
        free(v);
        return NULL;
    }
    ps->p += n;
    return v;
}

static lep_json *parse_value(parser *ps, int depth)
{
    lep_json *v;
    if (depth > MAX_DEPTH) {
        fail(ps, "nesting too deep");
        return NULL;
    }
    skip_ws(ps);
    if (ps->p >= ps->end) {
        fail(ps, "unexpected end of input");
        return NULL;
    }
    switch (*ps->p) {
    case '{':
        return parse_container(ps, depth, LEP_JSON_OBJECT);
    case '[':
        return parse_container(ps, depth, LEP_JSON_ARRAY);
    case '"': {
        char *s = parse_string_raw(ps);
        if (s == NULL) {
            return NULL;
        }
        v = new_value(ps, LEP_JSON_STRING);
        if (v == NULL) {
            free(s);
            return NULL;
        }
        v->str = s;
        return v;
    }
    default:
        break;
    }
    if (literal(ps, "true")) {
        v = new_value(ps, LEP_JSON_BOOL);
        if (v != NULL) {
            v->b = true;
        }
        return v;
    }
    if (literal(ps, "false")) {
        return new_value(ps, LEP_JSON_BOOL);
    }
    if (literal(ps, "null")) {
        return new_value(ps, LEP_JSON_NULL);
    }
    return parse_number(ps);
}

lep_json *lep_json_parse(const char *text, size_t len, char *err, size_t errcap)
{
    parser ps;
    lep_json *v;
    if (err != NULL && errcap > 0) {
        err[0] = '\0';
    }
    if (text == NULL) {
        if (err != NULL && errcap > 0) {
            snprintf(err, errcap, "no input");
        }
        return NULL;
    }
    ps.p = text;
    ps.start = text;
    ps.end = text + len;
    ps.err = err;
    ps.errcap = errcap;
    ps.failed = false;
    v = parse_value(&ps, 0);
    if (v != NULL) {
        skip_ws(&ps);
        if (ps.p != ps.end) {
            fail(&ps, "trailing characters after the document");
            lep_json_free(v);
            v = NULL;
        }
    }
    return v;
}

lep_json *lep_json_parse_file(const char *path, char *err, size_t errcap)
{
    FILE *f;
    char *text = NULL;
    size_t len = 0;
    size_t cap = 0;
    lep_json *v;
    if (path == NULL || (f = fopen(path, "rb")) == NULL) {
        if (err != NULL && errcap > 0) {
            snprintf(err, errcap, "cannot open %s", path != NULL ? path : "(null)");
        }
        return NULL;
    }
    for (;;) {
        size_t got;
        if (cap - len < 4096u) {
            char *bigger = (char *)realloc(text, cap + 65536u);
            if (bigger == NULL) {
                free(text);
                fclose(f);
                if (err != NULL && errcap > 0) {
                    snprintf(err, errcap, "out of memory reading %s", path);
                }
                return NULL;
            }
            text = bigger;
            cap += 65536u;
        }
        got = fread(text + len, 1, cap - len, f);
        len += got;
        if (got == 0) {
            break;
        }
    }
    if (ferror(f)) {
        free(text);
        fclose(f);
        if (err != NULL && errcap > 0) {
            snprintf(err, errcap, "read error on %s", path);
        }
        return NULL;
    }
    fclose(f);
    v = lep_json_parse(text, len, err, errcap);
    free(text);
    return v;
}

void lep_json_free(lep_json *v)
{
    size_t i;
    if (v == NULL) {
        return;
    }
    for (i = 0; i < v->n; i++) {
        lep_json_free(v->items[i]);
        if (v->keys != NULL) {
            free(v->keys[i]);
        }
    }
    free(v->items);
    free(v->keys);
    free(v->str);
    free(v);
}

int lep_json_type(const lep_json *v)
{
    return v != NULL ? v->type : LEP_JSON_NULL;
}

const lep_json *lep_json_get(const lep_json *obj, const char *key)
{
    size_t i;
    if (obj == NULL || obj->type != LEP_JSON_OBJECT || key == NULL) {
        return NULL;
    }
    for (i = 0; i < obj->n; i++) {
        if (strcmp(obj->keys[i], key) == 0) {
            return obj->items[i];
        }
    }
    return NULL;
}

bool lep_json_has(const lep_json *obj, const char *key)
{
    return lep_json_get(obj, key) != NULL;
}

size_t lep_json_len(const lep_json *v)
{
    if (v == NULL || (v->type != LEP_JSON_ARRAY && v->type != LEP_JSON_OBJECT)) {
        return 0;
    }
    return v->n;
}

const lep_json *lep_json_at(const lep_json *v, size_t i)
{
    if (v == NULL || (v->type != LEP_JSON_ARRAY && v->type != LEP_JSON_OBJECT) || i >= v->n) {
        return NULL;
    }
    return v->items[i];
}

const char *lep_json_key_at(const lep_json *obj, size_t i)
{
    if (obj == NULL || obj->type != LEP_JSON_OBJECT || i >= obj->n) {
        return NULL;
    }
    return obj->keys[i];
}

const char *lep_json_str(const lep_json *v)
{
    return (v != NULL && v->type == LEP_JSON_STRING) ? v->str : NULL;
}

double lep_json_num(const lep_json *v)
{
    return (v != NULL && v->type == LEP_JSON_NUMBER) ? v->num : 0.0;
}

bool lep_json_bool(const lep_json *v)
{
    return v != NULL && v->type == LEP_JSON_BOOL && v->b;
}

bool lep_json_is_null(const lep_json *v)
{
    return v != NULL && v->type == LEP_JSON_NULL;
}

const char *lep_json_get_str(const lep_json *obj, const char *key)
{
    return lep_json_str(lep_json_get(obj, key));
}

double lep_json_get_num(const lep_json *obj, const char *key, double fallback)
{
    const lep_json *v = lep_json_get(obj, key);
    return (v != NULL && v->type == LEP_JSON_NUMBER) ? v->num : fallback;
}

long lep_json_get_int(const lep_json *obj, const char *key, long fallback)
{
    const lep_json *v = lep_json_get(obj, key);
    return (v != NULL && v->type == LEP_JSON_NUMBER) ? (long)v->num : fallback;
}

bool lep_json_get_bool(const lep_json *obj, const char *key, bool fallback)
{
    const lep_json *v = lep_json_get(obj, key);
    return (v != NULL && v->type == LEP_JSON_BOOL) ? v->b : fallback;
}
