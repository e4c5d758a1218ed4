/* Descriptions of library errors and sensor result codes.
 *
 * One string of NUL-separated texts holds both lists in code order (the codes
 * are contiguous), so flash holds the text and no table of pointers; each
 * list ends with the text for a code outside it, and "success" serves both. */
#include "leptrino/error.h"

#if LEP_HAVE_ERROR_STRINGS
/* LEP_OK, LEP_E_ARG (-1) .. LEP_E_STALLED (-23), unknown error; then
 * LEP_RESULT_LENGTH (1) .. LEP_RESULT_STATE (4), unknown result code. */
#define UNKNOWN_ERROR ((unsigned)-LEP_E_STALLED + 1u)
#define RESULTS UNKNOWN_ERROR /* result code r (1..4) is at RESULTS + r */
static const char k_texts[] = "success\0"
                              "invalid argument\0"
                              "buffer too small\0"
                              "message over 128 bytes\0"
                              "bad frame check (BCC)\0"
                              "bad byte after DLE\0"
                              "wrong message length\0"
                              "bad reserved byte\0"
                              "unexpected or unknown message\0"
                              "invalid field value\0"
                              "sensor reported an error\0"
                              "sensor kept answering NAK\0"
                              "timed out waiting for the sensor\0"
                              "I/O error\0"
                              "port disconnected\0"
                              "port in use elsewhere\0"
                              "no such port\0"
                              "permission denied\0"
                              "not a terminal\0"
                              "not allowed in this state\0"
                              "line never went quiet\0"
                              "not supported\0"
                              "duration or count reached\0"
                              "no stream data within the watchdog time\0"
                              "unknown error\0"
                              "length error\0"
                              "undefined command\0"
                              "invalid setting value\0"
                              "state error\0"
                              "unknown result code";

/* The text at index i of k_texts (one copy in size builds). */
#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__)
__attribute__((noinline))
#endif
static const char *nth(unsigned i)
{
    const char *s = k_texts;
    while (i > 0u) {
        while (*s++ != '\0') {
        }
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
    return nth(err > 0 || err < LEP_E_STALLED ? UNKNOWN_ERROR : (unsigned)-err);
#endif
}

const char *lep_result_str(uint8_t result)
{
#if !LEP_HAVE_ERROR_STRINGS
    (void)result;
    return "";
#else
    return nth(result == LEP_RESULT_OK      ? 0u
               : result > LEP_RESULT_STATE ? RESULTS + LEP_RESULT_STATE + 1u
                                            : RESULTS + result);
#endif
}
