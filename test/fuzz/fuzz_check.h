/* Shared by the fuzz targets: a broken invariant is a crash libFuzzer reports. */
#ifndef LEP_FUZZ_CHECK_H
#define LEP_FUZZ_CHECK_H

static inline void check(int ok)
{
    if (!ok) {
        __builtin_trap();
    }
}

#endif
