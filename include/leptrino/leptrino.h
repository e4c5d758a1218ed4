/* leptrino: talk to Leptrino 6-axis force/torque sensors.
 *
 * Umbrella header of the portable core: frame codec, message codec, host
 * client, sensor-side device. Not thread-safe; one context per port.
 * OS backends have their own headers (leptrino/serial.h, leptrino/sim.h). */
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
