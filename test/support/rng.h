/* The tests' deterministic random numbers (xorshift32), so a failure can be
 * replayed from its seed. *s must not be 0. */
#ifndef LEP_TEST_RNG_H
#define LEP_TEST_RNG_H

#include <stdint.h>

static inline uint32_t rng_next(uint32_t *s)
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *s = x;
    return x;
}

#endif
