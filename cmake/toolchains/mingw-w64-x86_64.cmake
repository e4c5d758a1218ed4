# Windows x86-64 with mingw-w64 (Debian: gcc-mingw-w64-x86-64; the tests run
# under Wine, Debian: wine64). The "posix" thread model of the compiler is
# used: the host layer's threads are winpthreads, linked statically (-static),
# so leptrino.dll and leptrino.exe import only KERNEL32, msvcrt and the
# Windows DLLs the serial backend needs (SetupAPI, ADVAPI32).
#   cmake --workflow --preset mingw        (docs/windows.md)
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(LEP_MINGW_PREFIX x86_64-w64-mingw32)
find_program(LEP_MINGW_GCC NAMES ${LEP_MINGW_PREFIX}-gcc-posix ${LEP_MINGW_PREFIX}-gcc)
if(NOT LEP_MINGW_GCC)
  set(LEP_MINGW_GCC ${LEP_MINGW_PREFIX}-gcc)
endif()
set(CMAKE_C_COMPILER ${LEP_MINGW_GCC})
set(CMAKE_RC_COMPILER ${LEP_MINGW_PREFIX}-windres)
set(CMAKE_FIND_ROOT_PATH /usr/${LEP_MINGW_PREFIX})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# msvcrt's printf does not know %zu: mingw-w64's own stdio does (C99 formats).
# mingw-w64-math.h: gcc builtins for isnan/isinf/isfinite/signbit (see there).
set(CMAKE_C_FLAGS_INIT "-D__USE_MINGW_ANSI_STDIO=1 -include ${CMAKE_CURRENT_LIST_DIR}/mingw-w64-math.h")
# libgcc and winpthreads inside the programs and the DLL: nothing to ship beside them.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "-static")

# ctest runs the test programs under Wine, in a prefix of this build's own
# (created once at configure time by cmake/LeptrinoWine.cmake), quietly.
find_program(LEP_WINE NAMES wine wine64)
if(NOT LEP_WINE)
  set(LEP_WINE wine)
endif()
set(LEP_WINEPREFIX ${CMAKE_BINARY_DIR}/wineprefix)
set(CMAKE_CROSSCOMPILING_EMULATOR env WINEDEBUG=-all WINEPREFIX=${LEP_WINEPREFIX} ${LEP_WINE})
