/* Sensor text made safe to print on a terminal (cli.h): the same on every OS. */
#include <stdio.h>

#include "cli.h"

size_t cli_safe_text(const char *s, char *out, size_t cap)
{
    static const char hex[] = "0123456789abcdef";
    size_t used = 0;
    if (cap == 0)
        return 0;
    for (; *s != '\0'; ++s) {
        unsigned char c = (unsigned char)*s;
        if (c >= 0x20 && c < 0x7f && c != '\\') {
            if (used + 1 >= cap)
                break;
            out[used++] = (char)c;
        } else if (c == '\\') {
            if (used + 2 >= cap)
                break;
            out[used++] = '\\';
            out[used++] = '\\';
        } else {
            /* A control byte (ESC starts a terminal command) or a non-ASCII
             * byte: shown as \xNN, never written as is. */
            if (used + 4 >= cap)
                break;
            out[used++] = '\\';
            out[used++] = 'x';
            out[used++] = hex[c >> 4];
            out[used++] = hex[c & 0x0f];
        }
    }
    out[used] = '\0';
    return used;
}
