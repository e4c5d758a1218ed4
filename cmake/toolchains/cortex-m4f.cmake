# Cross-compile the portable core for a Cortex-M4F (ARMv7E-M, single-precision FPU).
#   cmake --preset cortex-m4f && cmake --build --preset cortex-m4f
set(LEP_ARM_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
