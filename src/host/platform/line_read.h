/* Private: reading one line of any length from a stdio stream. */
#ifndef LEPTRINO_LINE_READ_H
#define LEPTRINO_LINE_READ_H

#include <stddef.h>
#include <stdio.h>

/* As POSIX getline(): the next line of f, with its '\n', into *line (grown
 * with realloc; *cap its size), NUL-terminated. Returns its length, or -1 at
 * the end of the file or on an error (errno ENOMEM when out of memory).
 * line_read_posix.c calls getline(); line_read_win32.c, where the C runtime
 * has none, reads with getc(). */
long lep_priv_getline(char **line, size_t *cap, FILE *f);

#endif
