/* Descriptions of library errors and sensor result codes. */
#include "leptrino/error.h"

const char *lep_strerror(int err)
{
#if !LEP_HAVE_ERROR_STRINGS
    (void)err;
    return "";
#else
    switch (err) {
    case LEP_OK: return "success";
    case LEP_E_ARG: return "invalid argument";
    case LEP_E_BUFFER: return "buffer too small";
    case LEP_E_TOO_LONG: return "message longer than 128 bytes";
    case LEP_E_BCC: return "frame check (BCC) mismatch";
    case LEP_E_ESCAPE: return "illegal byte after DLE in a frame";
    case LEP_E_LENGTH: return "wrong message length";
    case LEP_E_RESERVED: return "reserved byte does not hold its fixed value";
    case LEP_E_UNEXPECTED: return "unexpected or unknown message";
    case LEP_E_VALUE: return "invalid field value";
    case LEP_E_SENSOR: return "sensor reported an error";
    case LEP_E_NAK: return "sensor rejected the command (NAK) after all retries";
    case LEP_E_TIMEOUT: return "timed out waiting for the sensor";
    case LEP_E_IO: return "input/output error";
    case LEP_E_DISCONNECTED: return "port disconnected";
    case LEP_E_BUSY: return "port in use by another program";
    case LEP_E_NOT_FOUND: return "no such port";
    case LEP_E_PERMISSION: return "permission denied";
    case LEP_E_NOT_TTY: return "not a terminal device";
    case LEP_E_STATE: return "not allowed in the current state";
    case LEP_E_NO_SYNC: return "line never went quiet during recovery";
    case LEP_E_UNSUPPORTED: return "not supported";
    case LEP_E_END: return "end of the requested duration or count";
    case LEP_E_STALLED: return "no stream data within the watchdog time";
    default: return "unknown error";
    }
#endif
}

const char *lep_result_str(uint8_t result)
{
#if !LEP_HAVE_ERROR_STRINGS
    (void)result;
    return "";
#else
    switch (result) {
    case LEP_RESULT_OK: return "success";
    case LEP_RESULT_LENGTH: return "length error";
    case LEP_RESULT_UNDEFINED: return "undefined command";
    case LEP_RESULT_VALUE: return "invalid setting value";
    case LEP_RESULT_STATE: return "state error";
    default: return "unknown result code";
    }
#endif
}
