/* Symbol visibility for libleptrino: LEP_API marks the public ABI. */
#ifndef LEPTRINO_EXPORT_H
#define LEPTRINO_EXPORT_H

#if defined(LEPTRINO_STATIC)
#define LEP_API
#elif defined(_WIN32)
#if defined(LEPTRINO_BUILDING)
#define LEP_API __declspec(dllexport)
#else
#define LEP_API __declspec(dllimport)
#endif
#elif defined(__GNUC__) && __GNUC__ >= 4
#define LEP_API __attribute__((visibility("default")))
#else
#define LEP_API
#endif

#endif
