# Size report of a bare-metal Arm build (cmake/size_report.py), as JSON:
#   cmake --build --preset cortex-m0plus --target size-report   # prints it
#   cmake --build --preset cortex-m0plus --target size-check    # and checks the budgets
# The ceilings (Cortex-M0+, -Os; in size_report.py): the core <= 6144 bytes of
# flash, 0 bytes of .data/.bss, a host-client firmware (examples/mcu) <= 2304
# bytes of leptrino code, a client context <= 256 bytes.
find_package(Python3 COMPONENTS Interpreter)
if(NOT Python3_Interpreter_FOUND OR NOT TARGET leptrino_static)
  message(STATUS "leptrino: no Python 3 or no static library; size report not available")
  return()
endif()
find_program(LEP_SIZE_TOOL NAMES arm-none-eabi-size size)
find_program(LEP_NM_TOOL NAMES arm-none-eabi-nm nm)

# The target's name in the report: the toolchain file's name (cortex-m0plus, ...).
get_filename_component(LEPTRINO_SIZE_TARGET_NAME "${CMAKE_TOOLCHAIN_FILE}" NAME_WE)

add_library(lep_size_contexts OBJECT ${CMAKE_CURRENT_LIST_DIR}/size_contexts.c)
target_link_libraries(lep_size_contexts PRIVATE leptrino_static)

set(_lep_size_args
  --target ${LEPTRINO_SIZE_TARGET_NAME}
  --flags "${CMAKE_C_FLAGS} ${CMAKE_C_FLAGS_${CMAKE_BUILD_TYPE}}"
  --size-tool ${LEP_SIZE_TOOL} --nm-tool ${LEP_NM_TOOL}
  --library $<TARGET_FILE:leptrino_static>
  --contexts $<TARGET_OBJECTS:lep_size_contexts>)
set(_lep_size_deps leptrino_static lep_size_contexts)
if(TARGET mcu_gateway)
  list(APPEND _lep_size_args --firmware $<TARGET_FILE:mcu_gateway>
       --map ${PROJECT_BINARY_DIR}/examples/mcu/mcu_gateway.map)
  list(APPEND _lep_size_deps mcu_gateway)
endif()
add_custom_target(size-report
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/size_report.py ${_lep_size_args}
          --output ${PROJECT_BINARY_DIR}/size-report.json
  DEPENDS ${_lep_size_deps} VERBATIM)
add_custom_target(size-check
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/size_report.py ${_lep_size_args} --check
          --output ${PROJECT_BINARY_DIR}/size-report.json
  DEPENDS ${_lep_size_deps} VERBATIM)
