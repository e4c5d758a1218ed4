# `cmake --build <dir> --target valgrind`: the end-to-end C tests (ctest label
# e2e) under valgrind memcheck; fails on any memcheck error or definite leak.
# Not with LEPTRINO_SANITIZE (AddressSanitizer and valgrind exclude each other).
if(LEPTRINO_SANITIZE OR LEPTRINO_CORE_ONLY OR CMAKE_CROSSCOMPILING)
  return()
endif()
find_program(LEPTRINO_VALGRIND valgrind)
find_program(LEPTRINO_BASH bash)
if(NOT LEPTRINO_VALGRIND OR NOT LEPTRINO_BASH)
  message(STATUS "valgrind not found: no valgrind target (apt-get install valgrind)")
  return()
endif()
add_custom_target(valgrind
  COMMAND ${LEPTRINO_BASH} ${PROJECT_SOURCE_DIR}/test/package/valgrind_e2e.sh
          ${PROJECT_BINARY_DIR} ${CMAKE_CTEST_COMMAND} ${LEPTRINO_VALGRIND} e2e
  USES_TERMINAL
  COMMENT "End-to-end tests (label e2e) under valgrind memcheck")
