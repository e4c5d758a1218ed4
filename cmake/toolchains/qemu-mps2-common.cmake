# Shared by the QEMU mps2-an385 test toolchains: the runtime of the test
# images (test/embedded/mps2) and the emulator ctest runs them with.
find_program(LEP_QEMU_SYSTEM_ARM qemu-system-arm)
if(NOT LEP_QEMU_SYSTEM_ARM)
  set(LEP_QEMU_SYSTEM_ARM qemu-system-arm)
endif()
# -icount: guest time follows the instructions executed, not the host's clock,
# so a loaded machine cannot make the MCU example miss ticks or deadlines (the
# runs are deterministic), and sleep=off skips the time the CPU waits in WFI.
set(CMAKE_CROSSCOMPILING_EMULATOR
  ${LEP_QEMU_SYSTEM_ARM} -M mps2-an385 -nographic -monitor none -serial none
  -icount shift=5,align=off,sleep=off
  -semihosting-config enable=on,target=native -kernel)
set(LEPTRINO_TEST_PLATFORM mps2 CACHE STRING "Runtime of the test images (test/embedded/<name>)")
set(LEPTRINO_UNIT_TESTS_ONLY ON CACHE BOOL "Register only the Unity tests")
set(LEPTRINO_TEST_TRAP_UNALIGNED ${LEP_TEST_TRAP_UNALIGNED} CACHE BOOL "Test images fault on unaligned accesses")
set(LEPTRINO_TEST_NEWLIB_NANO ${LEP_TEST_NEWLIB_NANO} CACHE BOOL "Link the test images with newlib-nano")
