/* Descriptions of library errors and sensor result codes.
 *
 * One string of NUL-separated texts holds both lists, so flash holds the text
 * and no table of pointers: the errors in code order (the codes are
 * contiguous) up to the text for a code outside them, then the result codes'
 * own texts; a result code whose meaning an error text already states (the
 * spec's "length error", "invalid value") shares it. */
#include "leptrino/error.h"

#if LEP_HAVE_ERROR_STRINGS
/* LEP_OK, LEP_E_ARG (-1) .. LEP_E_LOST (-24), unknown error (25); then
 * undefined command (26), state error (27), unknown result code (28). */
#define UNKNOWN_ERROR ((unsigned)-LEP_E_LOST + 1u)
static const char k_texts[] = "success\0"
                              "invalid argument\0"
                              "buffer too small\0"
                              "message too long\0"
                              "bad frame check (BCC)\0"
                              "bad byte after DLE\0"
                              "length error\0"
                              "bad reserved byte\0"
                              "unexpected message\0"
                              "invalid value\0"
                              "sensor reported an error\0"
                              "sensor kept answering NAK\0"
                              "sensor timed out\0"
                              "I/O error\0"
                              "port disconnected\0"
                              "port in use\0"
                              "no such port\0"
                              "permission denied\0"
                              "not a terminal\0"
                              "not allowed in this state\0"
                              "line never went quiet\0"
                              "not supported\0"
                              "duration or count reached\0"
                              "no stream data within the watchdog time\0"
                              "stream lost\0"
                              "unknown error\0"
                              "undefined command\0"
                              "state error\0"
                              "unknown result code";

/* The index in k_texts of result codes 0..4 and of any other. */
static const unsigned char k_result_text[] = { 0u,
                                               (unsigned)-LEP_E_LENGTH,
                                               UNKNOWN_ERROR + 1u,
                                               (unsigned)-LEP_E_VALUE,
                                               UNKNOWN_ERROR + 2u,
                                               UNKNOWN_ERROR + 3u };

/* The text at index i of k_texts. */
static const char *nth(unsigned i)
{
    const char *s = k_texts;
    while (i > 0u) {
        char c;
        do {
            c = *s;
            s++;
        } while (c != '\0');
        i--;
    }
    return s;
}
#endif

const char *lep_strerror(int err)
{
#if !LEP_HAVE_ERROR_STRINGS
    (void)err;
    return "";
#else
    unsigned i = 0u - (unsigned)err; /* 0 .. 24 for the codes; above for the others */
    return nth(i < UNKNOWN_ERROR ? i : UNKNOWN_ERROR);
#endif
}

const char *lep_result_str(uint8_t result)
{
#if !LEP_HAVE_ERROR_STRINGS
    (void)result;
    return "";
#else
    unsigned r = result;
    if (r > LEP_RESULT_STATE + 1u) {
        r = LEP_RESULT_STATE + 1u;
    }
    return nth(k_result_text[r]);
#endif
}
