/* Hex strings of the test vectors: "10 02 04 FF" (spaces optional, any case). */
#ifndef LEP_TEST_HEX_H
#define LEP_TEST_HEX_H

#include <stddef.h>
#include <stdint.h>

/* Value of one hex digit (0..15), or -1 if c is not one. */
int lep_hex_digit(char c);

/* Parse hex into out[0..cap); *len gets the byte count. Whitespace between
 * bytes is ignored. Returns 0, or -1 for an odd digit count, a non-hex
 * character or out of room. hex NULL parses as empty. */
int lep_hex_parse(const char *hex, uint8_t *out, size_t cap, size_t *len);

/* Format data as "10 02 04" into out[0..cap) (truncated with "..." if it
 * does not fit); returns out. */
char *lep_hex_format(const uint8_t *data, size_t len, char *out, size_t cap);

#endif
