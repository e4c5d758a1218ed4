# The core's Unity tests as a 32-bit x86 program on an x86-64 host (Debian:
# libc6-dev-i386 lib32gcc-12-dev; not gcc-multilib, which conflicts with the
# s390x cross compiler).
#   cmake --workflow --preset host-m32
set(CMAKE_C_FLAGS_INIT "-m32")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-m32")
set(LEPTRINO_CORE_ONLY ON CACHE BOOL "Build only the portable core")
set(LEPTRINO_BUILD_SHARED OFF CACHE BOOL "Build the shared library")
set(LEPTRINO_UNIT_TESTS_ONLY ON CACHE BOOL "Register only the Unity tests")
