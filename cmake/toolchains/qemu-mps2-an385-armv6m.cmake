# The core's Unity tests as ARMv6-M code (what a Cortex-M0/M0+ runs), on QEMU's
# mps2-an385 with unaligned-access traps on: the start-up code sets
# CCR.UNALIGN_TRP, so any unaligned word or halfword access faults as it would
# on a Cortex-M0+ (QEMU's only Cortex-M0 board, microbit, has 16 KiB of RAM:
# too little for the tests). Linked with newlib-nano, as most firmware is.
#   cmake --workflow --preset qemu-armv6m
set(LEP_ARM_CPU_FLAGS "-mcpu=cortex-m0plus -mthumb -mfloat-abi=soft")
set(LEP_TEST_TRAP_UNALIGNED ON)
set(LEP_TEST_NEWLIB_NANO ON)
set(LEP_ARM_TEST_IMAGES ON)
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/qemu-mps2-common.cmake)
