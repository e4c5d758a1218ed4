/* leptrino-soak's parts (private to the tool). */
#ifndef LEPTRINO_SOAK_H
#define LEPTRINO_SOAK_H

#include <stdint.h>

/* Measure how often two flipped bits pass the BCC and the message checks
 * (trials frames of each kind); prints one JSON object. Returns 0. */
int soak_bit_errors(uint64_t trials, uint64_t seed);

#endif
