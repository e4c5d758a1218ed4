# Cross-compile the portable core for a Cortex-M0+ (ARMv6-M, no FPU).
#   cmake --preset cortex-m0plus && cmake --build --preset cortex-m0plus
# or by hand:
#   cmake -S . -B build/cortex-m0plus -G Ninja -DCMAKE_BUILD_TYPE=MinSizeRel \
#         -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/cortex-m0plus.cmake
set(LEP_ARM_CPU_FLAGS "-mcpu=cortex-m0plus -mthumb -mfloat-abi=soft")
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
