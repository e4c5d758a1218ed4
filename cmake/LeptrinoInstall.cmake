# Install: headers, libraries, leptrino.pc and the CMake package leptrino::leptrino.
include(CMakePackageConfigHelpers)

set(_lep_targets)
if(TARGET leptrino)
  list(APPEND _lep_targets leptrino)
endif()
if(TARGET leptrino_static)
  list(APPEND _lep_targets leptrino_static)
endif()

install(TARGETS ${_lep_targets}
  EXPORT leptrinoTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${LEPTRINO_PUBLIC_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/leptrino)

set(LEPTRINO_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/leptrino)
install(EXPORT leptrinoTargets NAMESPACE leptrino:: DESTINATION ${LEPTRINO_CMAKE_DIR})
configure_package_config_file(cmake/leptrinoConfig.cmake.in
  ${PROJECT_BINARY_DIR}/leptrinoConfig.cmake
  INSTALL_DESTINATION ${LEPTRINO_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/leptrinoConfigVersion.cmake
  COMPATIBILITY ${LEPTRINO_PACKAGE_COMPATIBILITY}) # set beside the SONAME (src/CMakeLists.txt)
install(FILES ${PROJECT_BINARY_DIR}/leptrinoConfig.cmake ${PROJECT_BINARY_DIR}/leptrinoConfigVersion.cmake
  DESTINATION ${LEPTRINO_CMAKE_DIR})

# pkg-config: paths relative to the .pc file so the tree can be relocated.
if(LEPTRINO_CORE_ONLY)
  set(LEPTRINO_PC_LIBS_PRIVATE "")
else()
  set(LEPTRINO_PC_LIBS_PRIVATE "-pthread")
endif()
file(RELATIVE_PATH LEPTRINO_PC_TO_PREFIX "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
configure_file(pkgconfig/leptrino.pc.in ${PROJECT_BINARY_DIR}/leptrino.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/leptrino.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
