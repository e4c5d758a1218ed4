/* Test header of public_abi_lint.py: LEP_API as in include/leptrino/export.h. */
#ifndef LEPTRINO_EXPORT_H
#define LEPTRINO_EXPORT_H
#if defined(_WIN32)
#define LEP_API __declspec(dllexport)
#else
#define LEP_API
#endif
#endif
