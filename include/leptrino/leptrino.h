/* leptrino: talk to Leptrino 6-axis force/torque sensors.
 *
 * Umbrella header of the portable core: frame codec, message codec, host
 * client, sensor-side device. Not thread-safe; one context per port.
 * OS backends have their own headers (leptrino/serial.h, leptrino/sim.h).
 *
 * NULL arguments, one rule for every function of the core (frame.h,
 * message.h, client.h, device.h, error.h): a NULL pointer where a function
 * needs an object is never dereferenced and the call has no other effect
 * (but an output count or length it was given may be set to 0). A function
 * that returns an int status then returns LEP_E_ARG; one that returns a
 * count, a flag, a code or a text returns 0, 0, 0 or "" unless its
 * header names another value; a void function does nothing. A pointer with
 * a length of 0 may be NULL, and a pointer its header calls optional ("may
 * be NULL", "when not NULL") means "not wanted" when NULL. A call that
 * reports through an event (lep_frame_event, lep_device_event) also says so
 * in the event when the event pointer is not NULL.
 *
 * For FFIs, the core's declarations hold no bool: a flag is an int (returned)
 * or a uint8_t (a struct member) holding 0 or 1; and every constant of those
 * headers is an enumerator of a named enum, not a macro (config.h's build
 * switches and version.h's macros aside). Languages that do not read C structs
 * allocate a context as lep_*_sizeof() bytes. */
#ifndef LEPTRINO_H
#define LEPTRINO_H

#include "client.h"
#include "device.h"
#include "error.h"
#include "export.h"
#include "frame.h"
#include "message.h"
#include "leptrino/version.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Version of the library actually loaded, e.g. "0.1.0" (static string). */
LEP_API const char *lep_version(void);

#ifdef __cplusplus
}
#endif

#endif
