/* Private: one-line error messages for callers' err[errlen] buffers. */
#ifndef LEPTRINO_POSIX_ERRMSG_H
#define LEPTRINO_POSIX_ERRMSG_H

#include <stddef.h>

/* printf into err[0..errlen), truncating; nothing when err is NULL or errlen 0. */
void lep_priv_set_err(char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
