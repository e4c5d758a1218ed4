# Extra tests of the mps2 test images (included from test/CMakeLists.txt).
if(LEPTRINO_TEST_TRAP_UNALIGNED)
  # The trap must be on: an unaligned load ends in the fault handler.
  add_executable(unaligned_probe ${CMAKE_CURRENT_LIST_DIR}/unaligned_probe.c)
  target_link_libraries(unaligned_probe PRIVATE lep_test_platform)
  add_test(NAME unaligned_trap_is_on COMMAND unaligned_probe)
  set_tests_properties(unaligned_trap_is_on PROPERTIES
    PASS_REGULAR_EXPRESSION "FAULT: .*\\(unaligned access\\)" TIMEOUT 30)
endif()
