/* Locating and loading the shared test vectors (see vectors.h). */
#include "vectors.h"

#include "hex.h"
#include "leptrino/error.h"
#include "unity.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *lep_vectors_dir(void)
{
    const char *env = getenv("LEPTRINO_VECTORS_DIR");
    if (env != NULL && env[0] != '\0') {
        return env;
    }
#ifdef LEP_TEST_VECTORS_DIR
    return LEP_TEST_VECTORS_DIR;
#else
    return ".";
#endif
}

char *lep_vectors_path(const char *file, char *out, size_t cap)
{
    int n = snprintf(out, cap, "%s/%s", lep_vectors_dir(), file);
    if (n < 0 || (size_t)n >= cap) {
        return NULL;
    }
    return out;
}

lep_json *lep_vectors_load(const char *file)
{
    char path[4096];
    char err[256];
    lep_json *v;
    if (lep_vectors_path(file, path, sizeof(path)) == NULL) {
        fprintf(stderr, "vectors: path too long for %s\n", file);
        return NULL;
    }
    v = lep_json_parse_file(path, err, sizeof(err));
    if (v == NULL) {
        fprintf(stderr, "vectors: %s: %s\n", path, err);
    }
    return v;
}

const char *lep_vectors_ctx(const char *name, const char *how)
{
    static char buf[512];
    snprintf(buf, sizeof(buf), "vector '%s' (%s)", name != NULL ? name : "?", how);
    return buf;
}

size_t lep_vectors_hex(const char *hex, uint8_t *out, size_t cap)
{
    size_t n = 0;
    TEST_ASSERT_NOT_NULL_MESSAGE(hex, "vector without a hex field");
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, lep_hex_parse(hex, out, cap, &n), hex);
    return n;
}

const lep_json *lep_vectors_section(const lep_json *root, const char *name)
{
    const lep_json *s;
    TEST_ASSERT_NOT_NULL_MESSAGE(root, "the vectors file did not load");
    s = lep_json_get(root, name);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_JSON_ARRAY, lep_json_type(s), name);
    TEST_ASSERT_GREATER_THAN_size_t_MESSAGE(0u, lep_json_len(s), name);
    return s;
}

int lep_vectors_error(const char *name)
{
    static const struct {
        const char *name;
        int code;
    } map[] = { { "arg", LEP_E_ARG },           { "buffer", LEP_E_BUFFER },
                { "too_long", LEP_E_TOO_LONG }, { "bcc", LEP_E_BCC },
                { "escape", LEP_E_ESCAPE },     { "length", LEP_E_LENGTH },
                { "reserved", LEP_E_RESERVED }, { "unexpected", LEP_E_UNEXPECTED },
                { "value", LEP_E_VALUE },       { "sensor", LEP_E_SENSOR } };
    size_t i;
    TEST_ASSERT_NOT_NULL_MESSAGE(name, "vector without an error name");
    for (i = 0; i < sizeof(map) / sizeof(map[0]); i++) {
        if (strcmp(map[i].name, name) == 0) {
            return map[i].code;
        }
    }
    TEST_FAIL_MESSAGE(name);
    return 0;
}
