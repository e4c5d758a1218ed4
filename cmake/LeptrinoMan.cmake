# Man pages for the installed programs, made at build time by help2man from
# each program's own --help: the help text is the only source, there is no
# second hand-kept copy. Optional: without help2man (or when the programs
# cannot run on the build machine) there are no man pages, and configure says so.
#
# Every installed program gets a page: the project's executables named
# leptrino* (leptrino, leptrino-sim, leptrino-soak, leptrino-bench ...; test
# and example programs have other names), found in every directory, so a new
# program joins by itself. The NAME line's summary, by program name:
set(LEPTRINO_MAN_SUMMARIES
  "leptrino|read, record and configure Leptrino 6-axis force/torque sensors"
  "leptrino-sim|a virtual Leptrino force/torque sensor on a pseudo-terminal"
  "leptrino-soak|soak test of the leptrino client against a faulty virtual sensor"
  "leptrino-bench|measure the leptrino library and print the figures as JSON"
  "leptrino-stamp-error|measure the session's time stamps against the virtual sensor's clock")

option(LEPTRINO_MAN "Generate and install man pages (needs help2man)" ON)
set(LEPTRINO_MAN_PAGES "")

if(NOT LEPTRINO_MAN OR LEPTRINO_CORE_ONLY)
  return()
endif()
if(CMAKE_CROSSCOMPILING)
  message(STATUS "Man pages: not generated when cross-compiling (help2man runs the programs)")
  return()
endif()
set(_lep_man_commands_script ${PROJECT_SOURCE_DIR}/packaging/man/commands.cmake)
if(NOT EXISTS ${_lep_man_commands_script})
  message(STATUS "Man pages: ${_lep_man_commands_script} is missing, so no man pages")
  return()
endif()
find_program(LEPTRINO_HELP2MAN help2man)
if(NOT LEPTRINO_HELP2MAN)
  message(STATUS "Man pages: help2man not found, so no man pages are built or installed "
                 "(install it, e.g. apt-get install help2man, then configure again)")
  return()
endif()
find_program(LEPTRINO_GZIP gzip)

# The programs of this build: executables named leptrino*, in any directory.
set(_lep_man_targets "")
set(_lep_man_names "")
set(_lep_man_summaries "")
set(_lep_dirs ${PROJECT_SOURCE_DIR})
while(_lep_dirs)
  list(POP_FRONT _lep_dirs _dir)
  get_property(_subdirs DIRECTORY ${_dir} PROPERTY SUBDIRECTORIES)
  list(APPEND _lep_dirs ${_subdirs})
  get_property(_targets DIRECTORY ${_dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(_target IN LISTS _targets)
    get_target_property(_type ${_target} TYPE)
    get_target_property(_name ${_target} OUTPUT_NAME)
    if(NOT _name)
      set(_name ${_target})
    endif()
    if(NOT _type STREQUAL "EXECUTABLE" OR NOT _name MATCHES "^leptrino")
      continue()
    endif()
    set(_summary "part of leptrino, the Leptrino force/torque sensor tools")
    foreach(_entry IN LISTS LEPTRINO_MAN_SUMMARIES)
      if(_entry MATCHES "^${_name}\\|(.*)$")
        set(_summary "${CMAKE_MATCH_1}")
      endif()
    endforeach()
    list(APPEND _lep_man_targets ${_target})
    list(APPEND _lep_man_names ${_name})
    list(APPEND _lep_man_summaries "${_summary}")
  endforeach()
endwhile()

# SEE ALSO (every page) and COPYRIGHT, shared by all pages.
set(_lep_man_dir ${PROJECT_BINARY_DIR}/man)
set(_see_also "")
foreach(_name IN LISTS _lep_man_names)
  if(_see_also)
    string(APPEND _see_also ",\n")
  endif()
  string(APPEND _see_also ".BR ${_name} (1)")
endforeach()
file(WRITE ${_lep_man_dir}/common.h2m.new
  "[SEE ALSO]\n${_see_also}\n"
  ".PP\nThe README.md and docs/ of the leptrino source tree have the full documentation.\n"
  "[COPYRIGHT]\nCopyright (c) 2026 the leptrino authors. MIT License: see LICENSE in the source tree,\n"
  "or /usr/share/doc/leptrino/copyright where the Debian package is installed.\n")
# Touched only when it changes, so that a new configure does not remake the pages.
configure_file(${_lep_man_dir}/common.h2m.new ${_lep_man_dir}/common.h2m COPYONLY)

foreach(_target _name _summary IN ZIP_LISTS _lep_man_targets _lep_man_names _lep_man_summaries)
  set(_page ${_lep_man_dir}/man1/${_name}.1)
  # A COMMANDS section with each command's --help (for a program with commands).
  set(_commands ${_lep_man_dir}/${_name}.commands.h2m)
  add_custom_command(OUTPUT ${_commands}
    COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:${_target}> -DOUTPUT=${_commands}
            -P ${_lep_man_commands_script}
    DEPENDS ${_target} ${_lep_man_commands_script}
    VERBATIM)
  # --version-string: the version comes from project(); the program is run
  # only for --help (which must exit 0).
  add_custom_command(OUTPUT ${_page}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${_lep_man_dir}/man1
    COMMAND ${LEPTRINO_HELP2MAN} --no-info --no-discard-stderr --section 1
            --name ${_summary} --source "leptrino ${PROJECT_VERSION}"
            --version-string "${_name} ${PROJECT_VERSION}"
            --include ${_lep_man_dir}/common.h2m --include ${_commands}
            --output ${_page} $<TARGET_FILE:${_target}>
    DEPENDS ${_target} ${_lep_man_dir}/common.h2m ${_commands}
    COMMENT "Man page ${_name}(1) from ${_name} --help"
    VERBATIM)
  if(LEPTRINO_GZIP)
    # Compressed without name or time stamp (reproducible), as Debian installs man pages.
    add_custom_command(OUTPUT ${_page}.gz
      COMMAND ${LEPTRINO_GZIP} -9 -n -f -k ${_page}
      DEPENDS ${_page}
      VERBATIM)
    set(_page ${_page}.gz)
  endif()
  list(APPEND LEPTRINO_MAN_PAGES ${_page})
endforeach()

if(LEPTRINO_MAN_PAGES)
  add_custom_target(leptrino_man ALL DEPENDS ${LEPTRINO_MAN_PAGES})
  install(FILES ${LEPTRINO_MAN_PAGES} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
  list(LENGTH LEPTRINO_MAN_PAGES _n)
  message(STATUS "Man pages: ${_n} made from --help by help2man (${_lep_man_names})")
endif()
