/* Force-included (-include) in every C file of a mingw-w64 build by
 * mingw-w64-x86_64.cmake. mingw-w64's <math.h> classifies with type-generic
 * macros (__builtin_choose_expr over __isnanf, __isnan, __isnanl) whose
 * float branch, though never taken for a double, converts it to float and
 * fails -Werror=float-conversion. gcc's own type-generic builtins do the same
 * job without a conversion. */
#ifndef LEPTRINO_MINGW_W64_MATH_H
#define LEPTRINO_MINGW_W64_MATH_H
#include <math.h>
#undef isnan
#undef isinf
#undef isfinite
#undef signbit
#define isnan(x) __builtin_isnan(x)
#define isinf(x) __builtin_isinf(x)
#define isfinite(x) __builtin_isfinite(x)
#define signbit(x) __builtin_signbit(x)
#endif
