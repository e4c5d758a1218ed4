/* lep_priv_getline (line_read.h) on Windows, whose C runtime has no
 * getline(): getc() into a buffer doubled as needed. */
#include <errno.h>
#include <limits.h>
#include <stdlib.h>

#include "line_read.h"

long lep_priv_getline(char **line, size_t *cap, FILE *f)
{
    size_t n = 0;
    int c;
    if (line == NULL || cap == NULL || f == NULL) {
        errno = EINVAL;
        return -1;
    }
    if (*line == NULL)
        *cap = 0;
    for (;;) {
        c = getc(f);
        if (c == EOF)
            break;
        if (n + 2 > *cap) {
            size_t want = *cap < 128 ? 128 : *cap * 2;
            char *p = realloc(*line, want);
            if (p == NULL || want > (size_t)LONG_MAX) {
                errno = ENOMEM;
                return -1;
            }
            *line = p;
            *cap = want;
        }
        (*line)[n++] = (char)c;
        if (c == '\n')
            break;
    }
    if (n == 0)
        return -1;
    (*line)[n] = '\0';
    return (long)n;
}
