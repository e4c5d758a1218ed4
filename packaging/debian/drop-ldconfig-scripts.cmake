# CPack post-build script (CPACK_POST_BUILD_SCRIPTS) for the Debian package.
# CPackDeb adds postinst and postrm scripts that only run ldconfig to every
# package with a shared library under /usr/lib, and has no switch to turn
# that off. The leptrino package is maintainer-script free: it declares the
# ldconfig trigger instead (DEBIAN/triggers: activate-noawait ldconfig).
# So: unpack, check that the scripts are those ldconfig calls and nothing
# else, remove them, and build the package again with root ownership.
find_program(_dpkg_deb dpkg-deb REQUIRED)
foreach(_deb IN LISTS CPACK_PACKAGE_FILES)
  if(NOT _deb MATCHES "\\.deb$")
    continue()
  endif()
  set(_dir ${_deb}.tree)
  file(REMOVE_RECURSE ${_dir})
  execute_process(COMMAND ${_dpkg_deb} --raw-extract ${_deb} ${_dir} RESULT_VARIABLE _rc)
  if(_rc)
    message(FATAL_ERROR "dpkg-deb --raw-extract ${_deb} failed")
  endif()
  foreach(_script postinst postrm)
    if(EXISTS ${_dir}/DEBIAN/${_script})
      file(STRINGS ${_dir}/DEBIAN/${_script} _lines)
      foreach(_line IN LISTS _lines)
        if(NOT _line MATCHES "^(#!/bin/sh|set -e|if \\[ \"\\$1\" = \"(configure|remove)\" \\]; then|[ \t]*ldconfig|fi|)$")
          message(FATAL_ERROR "${_deb}: DEBIAN/${_script} does more than run ldconfig: '${_line}'")
        endif()
      endforeach()
      file(REMOVE ${_dir}/DEBIAN/${_script})
    endif()
  endforeach()
  file(STRINGS ${_dir}/DEBIAN/triggers _triggers)
  if(NOT "activate-noawait ldconfig" IN_LIST _triggers)
    message(FATAL_ERROR "${_deb}: no ldconfig trigger, so the ldconfig scripts cannot go")
  endif()
  execute_process(COMMAND ${_dpkg_deb} --root-owner-group --build ${_dir} ${_deb}
    OUTPUT_QUIET RESULT_VARIABLE _rc)
  if(_rc)
    message(FATAL_ERROR "dpkg-deb --build ${_dir} failed")
  endif()
  file(REMOVE_RECURSE ${_dir})
  message(STATUS "${_deb}: no maintainer scripts (ldconfig runs by trigger)")
endforeach()
