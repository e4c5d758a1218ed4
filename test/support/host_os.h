/* Test support: what the host tests expect where Windows differs from POSIX
 * by design (docs/windows.md), in one place. */
#ifndef LEP_TEST_HOST_OS_H
#define LEP_TEST_HOST_OS_H

#include <stdio.h>
#include <string.h>

#if defined(_WIN32)
#include <direct.h>
#include <io.h>
/* A COM port is a HANDLE: lep_session_fd / lep_serial_fd say -1. */
#define LEP_TEST_PORT_FD_OK(fd) ((fd) == -1)
/* Listed ports are COM ports. */
#define LEP_TEST_PORT_PATH_OK(p) (strncmp((p), "COM", 3) == 0)
#else
#define LEP_TEST_PORT_FD_OK(fd) ((fd) >= 0)
#define LEP_TEST_PORT_PATH_OK(p) ((p)[0] == '/')
#endif

/* mkdtemp: make a new directory from a template ending in XXXXXX; the
 * template, or NULL. On Windows _mktemp names it and _mkdir makes it; under
 * Wine "/tmp/..." is Z:\\tmp, the Linux /tmp. */
#if defined(_WIN32)
static inline char *lep_test_mkdtemp(char *tmpl)
{
    return _mktemp(tmpl) != NULL && _mkdir(tmpl) == 0 ? tmpl : NULL;
}
#else
#define lep_test_mkdtemp(tmpl) mkdtemp(tmpl)
#endif

#endif
