# The portable core for an 8-bit AVR (16-bit int; Debian: gcc-avr avr-libc):
# proves the core makes no assumption about the width of int. Library only.
#   cmake --preset avr && cmake --build --preset avr
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR avr)
set(CMAKE_C_COMPILER avr-gcc)
find_program(CMAKE_AR avr-ar)
find_program(CMAKE_RANLIB avr-ranlib)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
set(CMAKE_C_FLAGS_INIT "-mmcu=atmega2560 -ffunction-sections -fdata-sections")
set(LEPTRINO_CORE_ONLY ON CACHE BOOL "Build only the portable core")
set(LEPTRINO_BUILD_SHARED OFF CACHE BOOL "Build the shared library")
set(LEPTRINO_BUILD_TESTS OFF CACHE BOOL "Build the tests")
