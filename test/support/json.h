/* Minimal JSON reader for the test vectors (test-only code: uses malloc).
 *
 * Objects, arrays, strings (with \u escapes, stored as UTF-8), numbers,
 * true/false/null. A parsed document is a tree owned by its root: free it
 * with lep_json_free(). Accessors accept NULL and then return NULL / 0 /
 * false, so lookups can be chained and checked once. */
#ifndef LEP_TEST_JSON_H
#define LEP_TEST_JSON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

enum lep_json_type {
    LEP_JSON_NULL = 0,
    LEP_JSON_BOOL,
    LEP_JSON_NUMBER,
    LEP_JSON_STRING,
    LEP_JSON_ARRAY,
    LEP_JSON_OBJECT
};

typedef struct lep_json lep_json;

/* Parse text[0..len). NULL on error, with a message ("line N: ...") in err. */
lep_json *lep_json_parse(const char *text, size_t len, char *err, size_t errcap);

/* Read and parse a whole file. NULL on error (message in err). */
lep_json *lep_json_parse_file(const char *path, char *err, size_t errcap);

void lep_json_free(lep_json *v);

/* Type of v; LEP_JSON_NULL for a NULL pointer. */
int lep_json_type(const lep_json *v);

/* Member key of an object (NULL if v is not an object or has no such key). */
const lep_json *lep_json_get(const lep_json *obj, const char *key);
bool lep_json_has(const lep_json *obj, const char *key);

/* Elements of an array or members of an object. */
size_t lep_json_len(const lep_json *v);
const lep_json *lep_json_at(const lep_json *v, size_t i);
const char *lep_json_key_at(const lep_json *obj, size_t i);

/* Values: NULL / 0 / false when v has another type. */
const char *lep_json_str(const lep_json *v);
double lep_json_num(const lep_json *v);
bool lep_json_bool(const lep_json *v);
bool lep_json_is_null(const lep_json *v);

/* Shorthands for a member of an object. */
const char *lep_json_get_str(const lep_json *obj, const char *key);
double lep_json_get_num(const lep_json *obj, const char *key, double fallback);
long lep_json_get_int(const lep_json *obj, const char *key, long fallback);
bool lep_json_get_bool(const lep_json *obj, const char *key, bool fallback);

#endif
