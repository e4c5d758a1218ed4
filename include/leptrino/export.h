/* Symbol visibility for libleptrino: LEP_API marks the public ABI.
 *
 * On Windows (_WIN32: mingw-w64, MSVC, clang-cl) the rule is, first match wins:
 *   LEPTRINO_STATIC defined   -> nothing: the library is linked statically
 *                                (libleptrino.a / leptrino_static.lib), or its
 *                                sources are compiled into the program;
 *   LEPTRINO_BUILDING defined -> __declspec(dllexport): compiling leptrino.dll;
 *   neither                   -> __declspec(dllimport): using leptrino.dll
 *                                through its import library (libleptrino.dll.a
 *                                or leptrino.lib).
 * So a program that links the static library, or compiles the sources itself,
 * defines LEPTRINO_STATIC on its compiler command line (-DLEPTRINO_STATIC,
 * /DLEPTRINO_STATIC) before any leptrino header. CMake's imported target
 * leptrino::static sets it already (an INTERFACE definition); pkg-config's
 * `--static` flags do not, so add it yourself there. A dllimport declaration
 * with a static library gives "redeclared without dllimport" (gcc) or
 * unresolved __imp_lep_... symbols at link time.
 *
 * Elsewhere (gcc, clang) LEP_API is default visibility in a library built with
 * -fvisibility=hidden, and LEPTRINO_STATIC changes nothing that matters. */
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
