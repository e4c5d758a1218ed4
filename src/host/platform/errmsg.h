/* Private: one-line error messages for callers' err[errlen] buffers. */
#ifndef LEPTRINO_POSIX_ERRMSG_H
#define LEPTRINO_POSIX_ERRMSG_H

#include <stddef.h>

/* The printf archetype of format attributes: on mingw-w64 plain "printf"
 * means msvcrt's (no %zu), while the build uses its C99 stdio
 * (__USE_MINGW_ANSI_STDIO=1), which is gnu_printf's. */
#if defined(__MINGW32__)
#define LEP_PRIV_PRINTF gnu_printf
#else
#define LEP_PRIV_PRINTF printf
#endif

/* printf into err[0..errlen), truncating; nothing when err is NULL or errlen 0. */
void lep_priv_set_err(char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(LEP_PRIV_PRINTF, 3, 4)))
#endif
    ;

#endif
