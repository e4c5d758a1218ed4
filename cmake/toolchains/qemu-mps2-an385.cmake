# The core's Unity tests on an emulated Cortex-M3: QEMU's mps2-an385 board
# (Debian: qemu-system-arm), output, exit status and the vector files through
# semihosting. ctest runs each test image with the emulator below.
#   cmake --workflow --preset qemu-cortex-m3
set(LEP_ARM_CPU_FLAGS "-mcpu=cortex-m3 -mthumb")
set(LEP_ARM_TEST_IMAGES ON)
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/qemu-mps2-common.cmake)
