# Cross-compile the portable core for a Cortex-M0+ (Debian: gcc-arm-none-eabi).
#   cmake -S . -B build/m0 -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/cortex-m0plus.cmake \
#         -DLEPTRINO_CORE_ONLY=ON -DLEPTRINO_BUILD_SHARED=OFF -DLEPTRINO_BUILD_TESTS=OFF
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
set(CMAKE_C_FLAGS_INIT "-mcpu=cortex-m0plus -mthumb -ffunction-sections -fdata-sections")
set(CMAKE_C_FLAGS_MINSIZEREL_INIT "-Os -DNDEBUG")
