# The core's Unity tests on a big-endian CPU: s390x, statically linked, run by
# qemu-user (Debian: gcc-s390x-linux-gnu libc6-dev-s390x-cross qemu-user).
#   cmake --workflow --preset qemu-s390x
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR s390x)
set(CMAKE_C_COMPILER s390x-linux-gnu-gcc)
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
find_program(LEP_QEMU_S390X NAMES qemu-s390x qemu-s390x-static)
if(NOT LEP_QEMU_S390X)
  set(LEP_QEMU_S390X qemu-s390x)
endif()
set(CMAKE_CROSSCOMPILING_EMULATOR ${LEP_QEMU_S390X})
set(LEPTRINO_CORE_ONLY ON CACHE BOOL "Build only the portable core")
set(LEPTRINO_BUILD_SHARED OFF CACHE BOOL "Build the shared library")
set(LEPTRINO_UNIT_TESTS_ONLY ON CACHE BOOL "Register only the Unity tests")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
