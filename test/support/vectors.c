/* Locating and loading the shared test vectors (see vectors.h). */
#include "vectors.h"

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
