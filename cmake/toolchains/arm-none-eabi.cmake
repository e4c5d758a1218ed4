# Common part of the bare-metal Arm toolchain files (Debian/Ubuntu:
# gcc-arm-none-eabi libnewlib-arm-none-eabi). Included by cortex-m0plus.cmake,
# cortex-m4f.cmake and the QEMU test targets, which set LEP_ARM_CPU_FLAGS first.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
find_program(CMAKE_AR arm-none-eabi-ar)
find_program(CMAKE_RANLIB arm-none-eabi-ranlib)
find_program(CMAKE_SIZE arm-none-eabi-size)
find_program(CMAKE_OBJDUMP arm-none-eabi-objdump)
# No OS to link a test program against: check the compiler with a static library.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# Every function and object in its own section, so that --gc-sections keeps only
# what a firmware uses.
set(CMAKE_C_FLAGS_INIT "${LEP_ARM_CPU_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

# A firmware build is the portable core alone, as a static library.
set(LEPTRINO_CORE_ONLY ON CACHE BOOL "Build only the portable core")
set(LEPTRINO_BUILD_SHARED OFF CACHE BOOL "Build the shared library")
if(NOT LEP_ARM_TEST_IMAGES)
  # Unit tests need a board to run on: the qemu-mps2-* toolchain files.
  set(LEPTRINO_BUILD_TESTS OFF CACHE BOOL "Build the tests")
endif()

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
