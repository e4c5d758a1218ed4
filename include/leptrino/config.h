/* Compile-time options of the portable core, for firmware builds.
 *
 * Define each to 0 (the default when undefined) or 1, on the compiler's
 * command line or with the CMake options of the same meaning
 * (LEPTRINO_NO_DEVICE, LEPTRINO_NO_ERROR_STRINGS), identically for the
 * library and its users:
 *  - LEP_CONFIG_NO_DEVICE: leave out the sensor side (device.c compiles to
 *    nothing; device.h declares no functions). The OS layer, the virtual
 *    sensor and the tests need it, so it is for core-only builds.
 *  - LEP_CONFIG_NO_ERROR_STRINGS: lep_strerror() and lep_result_str() return
 *    "" instead of a description (the texts are left out).
 * Each is built and its tests run in CI (test/embedded/config_builds.sh). */
#ifndef LEPTRINO_CONFIG_H
#define LEPTRINO_CONFIG_H

#ifdef LEP_CONFIG_NO_DEVICE
#if (0 - LEP_CONFIG_NO_DEVICE - 1) == 1
#error "LEP_CONFIG_NO_DEVICE is defined empty: define it to 0 or 1"
#elif (LEP_CONFIG_NO_DEVICE + 0) != 0 && (LEP_CONFIG_NO_DEVICE + 0) != 1
#error "LEP_CONFIG_NO_DEVICE must be 0 or 1"
#endif
#define LEP_HAVE_DEVICE (LEP_CONFIG_NO_DEVICE == 0)
#else
#define LEP_HAVE_DEVICE 1
#endif

#ifdef LEP_CONFIG_NO_ERROR_STRINGS
#if (0 - LEP_CONFIG_NO_ERROR_STRINGS - 1) == 1
#error "LEP_CONFIG_NO_ERROR_STRINGS is defined empty: define it to 0 or 1"
#elif (LEP_CONFIG_NO_ERROR_STRINGS + 0) != 0 && (LEP_CONFIG_NO_ERROR_STRINGS + 0) != 1
#error "LEP_CONFIG_NO_ERROR_STRINGS must be 0 or 1"
#endif
#define LEP_HAVE_ERROR_STRINGS (LEP_CONFIG_NO_ERROR_STRINGS == 0)
#else
#define LEP_HAVE_ERROR_STRINGS 1
#endif

#endif
