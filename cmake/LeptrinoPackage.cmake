# Binary packages with CPack. The Debian package:
#   cmake --workflow --preset deb        (configure with /usr, build, cpack -G DEB)
# gives build/deb/leptrino_<version>-1_<arch>.deb with the shared library (its
# SONAME link), the static library, headers, leptrino.pc, the CMake package,
# the programs, their man pages, the udev rule and the copyright file.
# One package, no maintainer scripts; dependencies come from dpkg-shlibdeps.
if(NOT LEPTRINO_TOP_LEVEL)
  return()
endif()

set(CPACK_PACKAGE_NAME ${PROJECT_NAME})
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "the leptrino authors")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
  "A C99 library (shared and static, with headers, pkg-config and CMake files),\n"
  "the leptrino command-line tool and the leptrino-sim virtual sensor for\n"
  "Leptrino 6-axis force/torque sensors (PFS and CFS lines), which stream at\n"
  "about 1.2 kHz over a 460800-baud serial line. A udev rule gives the dialout\n"
  "group access to USB sensors and sets FTDI adapters' latency timer to 1 ms.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_RESOURCE_FILE_README ${PROJECT_SOURCE_DIR}/README.md)
set(CPACK_PACKAGE_CONTACT "the leptrino authors")
if(PROJECT_HOMEPAGE_URL)
  set(CPACK_PACKAGE_HOMEPAGE_URL ${PROJECT_HOMEPAGE_URL})
endif()
# The package installs where the build was configured to (the deb preset: /usr,
# so that GNUInstallDirs gives the multiarch library directory).
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
set(CPACK_STRIP_FILES ON)
set(CPACK_SOURCE_IGNORE_FILES "/build/;/\\\\.git/;__pycache__;\\\\.egg-info/;/\\\\.venv/")
set(CPACK_RPM_PACKAGE_LICENSE "MIT")

# Debian.
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Debian policy 5.6.2: the Maintainer field is "Name <address>". The default
# address is a placeholder in the reserved .invalid domain (RFC 2606) until the
# project has a real one; packagers set theirs with -DLEPTRINO_MAINTAINER=...
set(LEPTRINO_MAINTAINER "leptrino maintainers <maintainers@leptrino.invalid>"
    CACHE STRING "Maintainer field of the Debian package: Name <address>")
if(NOT LEPTRINO_MAINTAINER MATCHES "^[^<>]+ <[^<>@ ]+@[^<>@ ]+>$")
  message(FATAL_ERROR "LEPTRINO_MAINTAINER must read 'Name <address>', not '${LEPTRINO_MAINTAINER}'")
endif()
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${LEPTRINO_MAINTAINER}")
# dpkg-shlibdeps on every ELF file of the package gives Depends (libc6 ...).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# No maintainer scripts. CPack's own shlibs generation would add postinst and
# postrm scripts that run ldconfig; instead the package carries a shlibs file
# (for packages that link libleptrino: the SONAME from src/CMakeLists.txt) and
# the ldconfig trigger, a dpkg trigger (deb-triggers(5)) rather than a script.
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS OFF)
set(_lep_deb_control ${PROJECT_BINARY_DIR}/debian-control)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${_lep_deb_control}/triggers)
file(WRITE ${_lep_deb_control}/triggers "activate-noawait ldconfig\n")
if(TARGET leptrino)
  # libleptrino.so.<SOVERSION>: shlibs names it "libleptrino <SOVERSION>".
  get_target_property(_lep_soversion leptrino SOVERSION)
  file(WRITE ${_lep_deb_control}/shlibs
    "libleptrino ${_lep_soversion} ${PROJECT_NAME} (>= ${PROJECT_VERSION})\n")
  list(APPEND CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${_lep_deb_control}/shlibs)
endif()
# CPackDeb still adds its ldconfig postinst/postrm for a library in /usr/lib
# (it has no switch for that); this drops them again after packaging.
set(CPACK_POST_BUILD_SCRIPTS ${PROJECT_SOURCE_DIR}/packaging/debian/drop-ldconfig-scripts.cmake)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# Suggested by the programs' help: pkg-config for C consumers.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "pkg-config")

find_program(LEPTRINO_DPKG_DEB dpkg-deb)
if(WIN32)
  # Windows: a zip of the install tree (bin/leptrino.dll, bin/leptrino.exe,
  # lib/libleptrino.dll.a, lib/libleptrino.a, include/, lib/pkgconfig,
  # lib/cmake/leptrino): leptrino-<version>-win64.zip.
  set(CPACK_GENERATOR ZIP)
  set(CPACK_SYSTEM_NAME win64)
  set(CPACK_PACKAGING_INSTALL_PREFIX "")
elseif(LEPTRINO_DPKG_DEB)
  set(CPACK_GENERATOR DEB)
else()
  set(CPACK_GENERATOR TGZ)
endif()

include(CPack)
