/* lep_priv_getline (line_read.h) on POSIX: getline(). */
#if defined(__APPLE__)
#define _DARWIN_C_SOURCE
#else
#define _DEFAULT_SOURCE
#endif

#include <stdio.h>
#include <sys/types.h>

#include "line_read.h"

long lep_priv_getline(char **line, size_t *cap, FILE *f)
{
    ssize_t n = getline(line, cap, f);
    return n < 0 ? -1 : (long)n;
}
