/* Locating and loading the shared test vectors (the JSON files in test/vectors).
 *
 * The directory is LEPTRINO_VECTORS_DIR from the environment when set, else
 * LEP_TEST_VECTORS_DIR compiled in by CMake. */
#ifndef LEP_TEST_VECTORS_H
#define LEP_TEST_VECTORS_H

#include <stddef.h>

#include "json.h"

/* The vectors directory (never NULL; "." when nothing is configured). */
const char *lep_vectors_dir(void);

/* Write "<dir>/<file>" into out[0..cap); returns out, or NULL if it does not fit. */
char *lep_vectors_path(const char *file, char *out, size_t cap);

/* Parse a vectors file; on failure prints the reason to stderr and returns NULL. */
lep_json *lep_vectors_load(const char *file);

#endif
