#!/usr/bin/env bash
# Embedded and emulated targets: the core's Unity tests on QEMU (Cortex-M3,
# ARMv6-M with unaligned-access traps), big-endian s390x (qemu-user) and -m32,
# each with the host's results; the Cortex-M0+/M4F/AVR builds, the firmware
# configurations, the size budgets, the MCU example under QEMU, and the core
# built without CMake. All are ctest tests labelled "embedded" in build/dev,
# registered once their tools are installed.
set -euo pipefail
ci_apt gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm qemu-user \
  gcc-s390x-linux-gnu libc6-dev-s390x-cross gcc-avr avr-libc libc6-dev-i386 lib32gcc-12-dev
cmake --preset dev >/dev/null
cmake --build --preset dev -j2
# Every embedded test must be registered: a missing tool is a failure here.
ctest --test-dir build/dev -L embedded -N | tee build/embedded-tests.txt
missing=0
for t in emulated_cortex_m3 emulated_armv6m_unaligned_traps emulated_s390x_big_endian host_m32; do
  grep -q " $t\$" build/embedded-tests.txt || { echo "FAIL: $t not registered"; missing=1; }
done
[ $missing -eq 0 ]
if ! ctest --test-dir build/dev -L embedded -V >build/embedded-ctest.log 2>&1; then
  cat build/embedded-ctest.log
  exit 1
fi
# What was measured: test counts per target, sizes and budgets.
grep -E "^[0-9]+: (ok |budget|  )|Unity tests, 0 failures|Test +#|tests passed" build/embedded-ctest.log
