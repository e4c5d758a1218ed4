/* Hex strings of the test vectors (see hex.h). */
#include "hex.h"

#include <stdio.h>
#include <string.h>

int lep_hex_digit(char c)
{
    if (c >= '0' && c <= '9') {
        return c - '0';
    }
    if (c >= 'a' && c <= 'f') {
        return c - 'a' + 10;
    }
    if (c >= 'A' && c <= 'F') {
        return c - 'A' + 10;
    }
    return -1;
}

int lep_hex_parse(const char *hex, uint8_t *out, size_t cap, size_t *len)
{
    size_t n = 0;
    int high = -1;
    *len = 0;
    if (hex == NULL) {
        return 0;
    }
    for (; *hex != '\0'; hex++) {
        int d;
        if (*hex == ' ' || *hex == '\t' || *hex == '\n' || *hex == '\r') {
            if (high >= 0) {
                return -1; /* a lone digit */
            }
            continue;
        }
        d = lep_hex_digit(*hex);
        if (d < 0) {
            return -1;
        }
        if (high < 0) {
            high = d;
            continue;
        }
        if (n >= cap) {
            return -1;
        }
        out[n++] = (uint8_t)((high << 4) | d);
        high = -1;
    }
    if (high >= 0) {
        return -1;
    }
    *len = n;
    return 0;
}

char *lep_hex_format(const uint8_t *data, size_t len, char *out, size_t cap)
{
    size_t i;
    size_t n = 0;
    if (cap == 0) {
        return out;
    }
    out[0] = '\0';
    for (i = 0; i < len; i++) {
        if (n + 3u + 4u > cap) {
            if (n + 4u <= cap) {
                memcpy(out + n, "...", 4);
            }
            return out;
        }
        snprintf(out + n, cap - n, i == 0 ? "%02X" : " %02X", (unsigned)data[i]);
        n += i == 0 ? 2u : 3u;
    }
    return out;
}
