# include/leptrino/version.h is kept in the tree so the sources build without
# CMake; project(VERSION) stays the one place the version is decided, and this
# check stops the configure when the header says anything else.
file(READ ${PROJECT_SOURCE_DIR}/include/leptrino/version.h _lep_version_h)
foreach(_part MAJOR MINOR PATCH)
  if(NOT _lep_version_h MATCHES "#define LEP_VERSION_${_part} ([0-9]+)")
    message(FATAL_ERROR "include/leptrino/version.h: no LEP_VERSION_${_part}")
  endif()
  set(_lep_h_${_part} ${CMAKE_MATCH_1})
endforeach()
if(NOT _lep_version_h MATCHES "#define LEP_VERSION_STRING \"([^\"]*)\"")
  message(FATAL_ERROR "include/leptrino/version.h: no LEP_VERSION_STRING")
endif()
set(_lep_h_STRING ${CMAKE_MATCH_1})
set(_lep_h_numbers "${_lep_h_MAJOR}.${_lep_h_MINOR}.${_lep_h_PATCH}")
if(NOT _lep_h_numbers STREQUAL PROJECT_VERSION OR NOT _lep_h_STRING STREQUAL PROJECT_VERSION)
  message(FATAL_ERROR
    "include/leptrino/version.h says ${_lep_h_numbers} (\"${_lep_h_STRING}\") but "
    "project(leptrino VERSION ${PROJECT_VERSION}): set LEP_VERSION_MAJOR/MINOR/PATCH and "
    "LEP_VERSION_STRING to ${PROJECT_VERSION}")
endif()
if(NOT CMAKE_SCRIPT_MODE_FILE)
  # Re-run the check when the header is edited.
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/include/leptrino/version.h)
endif()
