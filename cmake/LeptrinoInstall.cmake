# Install: headers, libraries, leptrino.pc and the CMake package leptrino::leptrino.
include(CMakePackageConfigHelpers)

set(_lep_targets)
if(TARGET leptrino)
  list(APPEND _lep_targets leptrino)
endif()
if(TARGET leptrino_static)
  list(APPEND _lep_targets leptrino_static)
endif()

install(TARGETS ${_lep_targets}
  EXPORT leptrinoTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${LEPTRINO_PUBLIC_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/leptrino)

set(LEPTRINO_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/leptrino)
install(EXPORT leptrinoTargets NAMESPACE leptrino:: DESTINATION ${LEPTRINO_CMAKE_DIR})
configure_package_config_file(cmake/leptrinoConfig.cmake.in
  ${PROJECT_BINARY_DIR}/leptrinoConfig.cmake
  INSTALL_DESTINATION ${LEPTRINO_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/leptrinoConfigVersion.cmake
  COMPATIBILITY ${LEPTRINO_PACKAGE_COMPATIBILITY}) # set beside the SONAME (src/CMakeLists.txt)
install(FILES ${PROJECT_BINARY_DIR}/leptrinoConfig.cmake ${PROJECT_BINARY_DIR}/leptrinoConfigVersion.cmake
  DESTINATION ${LEPTRINO_CMAKE_DIR})

# pkg-config: paths relative to the .pc file so the tree can be relocated.
if(LEPTRINO_CORE_ONLY)
  set(LEPTRINO_PC_LIBS_PRIVATE "")
else()
  set(LEPTRINO_PC_LIBS_PRIVATE "-pthread")
  if(LEPTRINO_LIBM)  # the session's filter and rotation (src/CMakeLists.txt)
    string(APPEND LEPTRINO_PC_LIBS_PRIVATE " -lm")
  endif()
endif()
# A /usr install (the Debian package) says prefix=/usr: pkg-config then
# recognises /usr/include and /usr/lib/<multiarch> as system directories and
# prints no -I/-L for them.
if(CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  set(LEPTRINO_PC_PREFIX "/usr")
else()
  file(RELATIVE_PATH _lep_pc_up "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
  set(LEPTRINO_PC_PREFIX "\${pcfiledir}/${_lep_pc_up}")
endif()
configure_file(pkgconfig/leptrino.pc.in ${PROJECT_BINARY_DIR}/leptrino.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/leptrino.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# The license, as Debian wants it (share/doc/leptrino/copyright, machine-readable
# format), made from LICENSE so that the text lives in one file. (A partial copy
# of the tree without LICENSE or packaging/ installs no copyright file.)
set(_lep_copyright_in ${PROJECT_SOURCE_DIR}/packaging/debian/copyright.in)
if(EXISTS ${PROJECT_SOURCE_DIR}/LICENSE AND EXISTS ${_lep_copyright_in})
  file(STRINGS ${PROJECT_SOURCE_DIR}/LICENSE _lep_license_lines)
  set(LEPTRINO_DEB_LICENSE_TEXT "")
  set(_lep_in_text OFF)
  foreach(_line IN LISTS _lep_license_lines)
    if(_line MATCHES "^Permission is hereby granted")
      set(_lep_in_text ON)
    endif()
    if(_lep_in_text AND _line STREQUAL "")
      string(APPEND LEPTRINO_DEB_LICENSE_TEXT " .\n")
    elseif(_lep_in_text)
      string(APPEND LEPTRINO_DEB_LICENSE_TEXT " ${_line}\n")
    endif()
  endforeach()
  string(STRIP "${LEPTRINO_DEB_LICENSE_TEXT}" LEPTRINO_DEB_LICENSE_TEXT)
  string(PREPEND LEPTRINO_DEB_LICENSE_TEXT " ")
  configure_file(${_lep_copyright_in} ${PROJECT_BINARY_DIR}/copyright @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/copyright DESTINATION ${CMAKE_INSTALL_DOCDIR})
endif()

# The udev rule: where udev reads it for a /usr install (the Debian package),
# else beside the other data, for an administrator to copy to /etc/udev/rules.d.
# -DLEPTRINO_UDEV_RULES_DIR=... (relative to the prefix) chooses another place.
set(_lep_udev_rule ${PROJECT_SOURCE_DIR}/packaging/udev/60-leptrino.rules)
if(NOT LEPTRINO_CORE_ONLY AND NOT WIN32 AND EXISTS ${_lep_udev_rule})
  if(DEFINED LEPTRINO_UDEV_RULES_DIR)
    set(_lep_udev_dir ${LEPTRINO_UDEV_RULES_DIR})
  elseif(CMAKE_INSTALL_PREFIX STREQUAL "/usr")
    set(_lep_udev_dir lib/udev/rules.d)
  else()
    set(_lep_udev_dir ${CMAKE_INSTALL_DATADIR}/leptrino/udev)
  endif()
  install(FILES ${_lep_udev_rule} DESTINATION ${_lep_udev_dir})
endif()

# Man pages from the programs' --help (help2man), installed in share/man/man1.
include(cmake/LeptrinoMan.cmake)
