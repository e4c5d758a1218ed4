/* Locating and loading the shared test vectors (the JSON files in test/vectors).
 *
 * The directory is LEPTRINO_VECTORS_DIR from the environment when set, else
 * LEP_TEST_VECTORS_DIR compiled in by CMake. */
#ifndef LEP_TEST_VECTORS_H
#define LEP_TEST_VECTORS_H

#include <stddef.h>
#include <stdint.h>

#include "json.h"

/* The vectors directory (never NULL; "." when nothing is configured). */
const char *lep_vectors_dir(void);

/* Write "<dir>/<file>" into out[0..cap); returns out, or NULL if it does not fit. */
char *lep_vectors_path(const char *file, char *out, size_t cap);

/* Parse a vectors file; on failure prints the reason to stderr and returns NULL. */
lep_json *lep_vectors_load(const char *file);

/* Assertion helpers for vector-driven tests: each fails the running Unity
 * test with a message naming the problem. */

/* "vector '<name>' (<how>)", in a static buffer reused by the next call. */
const char *lep_vectors_ctx(const char *name, const char *how);
/* Parse a hex field into out[0..cap); returns the byte count. */
size_t lep_vectors_hex(const char *hex, uint8_t *out, size_t cap);
/* The non-empty array member name of root (root must have loaded). */
const lep_json *lep_vectors_section(const lep_json *root, const char *name);
/* The LEP_E_* code for an error name of the vectors ("bcc", "length", ...). */
int lep_vectors_error(const char *name);

#endif
