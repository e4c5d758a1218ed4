# Windows builds tested under Wine (cmake/toolchains/mingw-w64-x86_64.cmake):
# the Wine prefix of this build, created once here (wineboot, 10-30 s), so
# that the test programs do not each race to create it.
if(NOT (WIN32 AND CMAKE_CROSSCOMPILING AND LEP_WINEPREFIX AND LEPTRINO_BUILD_TESTS))
  return()
endif()
if(NOT EXISTS ${LEP_WINEPREFIX}/system.reg)
  message(STATUS "leptrino: creating the Wine prefix ${LEP_WINEPREFIX}")
  execute_process(COMMAND env WINEDEBUG=-all WINEPREFIX=${LEP_WINEPREFIX} ${LEP_WINE} wineboot -i
                  RESULT_VARIABLE _lep_wineboot OUTPUT_QUIET ERROR_QUIET)
  if(NOT EXISTS ${LEP_WINEPREFIX}/system.reg)
    message(WARNING "leptrino: wineboot (${LEP_WINE}) did not create ${LEP_WINEPREFIX}: the tests cannot run (${_lep_wineboot})")
  endif()
endif()
