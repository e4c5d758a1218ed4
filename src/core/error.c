/* Descriptions of library errors and sensor result codes.
 *
 * Each list is one string of NUL-separated texts in code order (the codes are
 * contiguous), so flash holds the text and no table of pointers; the last
 * entry is the text for a code outside the list. */
#include "leptrino/error.h"

#if LEP_HAVE_ERROR_STRINGS
/* LEP_OK, then LEP_E_ARG (-1) .. LEP_E_STALLED (-23), then unknown. */
static const char k_errors[] = "success\0"
                               "invalid argument\0"
                               "buffer too small\0"
                               "message longer than 128 bytes\0"
                               "frame check (BCC) mismatch\0"
                               "illegal byte after DLE in a frame\0"
                               "wrong message length\0"
                               "reserved byte does not hold its fixed value\0"
                               "unexpected or unknown message\0"
                               "invalid field value\0"
                               "sensor reported an error\0"
                               "sensor rejected the command (NAK) after all retries\0"
                               "timed out waiting for the sensor\0"
                               "input/output error\0"
                               "port disconnected\0"
                               "port in use by another program\0"
                               "no such port\0"
                               "permission denied\0"
                               "not a terminal device\0"
                               "not allowed in the current state\0"
                               "line never went quiet during recovery\0"
                               "not supported\0"
                               "end of the requested duration or count\0"
                               "no stream data within the watchdog time\0"
                               "unknown error";

/* LEP_RESULT_OK (0) .. LEP_RESULT_STATE (4), then unknown. */
static const char k_results[] = "success\0"
                                "length error\0"
                                "undefined command\0"
                                "invalid setting value\0"
                                "state error\0"
                                "unknown result code";

/* The text at index i of a NUL-separated list (i within the list). */
static const char *nth(const char *list, unsigned i)
{
    while (i > 0u) {
        while (*list++ != '\0') {
        }
        i--;
    }
    return list;
}
#endif

const char *lep_strerror(int err)
{
#if !LEP_HAVE_ERROR_STRINGS
    (void)err;
    return "";
#else
    unsigned i = err > 0 || err < LEP_E_STALLED ? (unsigned)-LEP_E_STALLED + 1u : (unsigned)-err;
    return nth(k_errors, i);
#endif
}

const char *lep_result_str(uint8_t result)
{
#if !LEP_HAVE_ERROR_STRINGS
    (void)result;
    return "";
#else
    return nth(k_results, result > LEP_RESULT_STATE ? LEP_RESULT_STATE + 1u : result);
#endif
}
