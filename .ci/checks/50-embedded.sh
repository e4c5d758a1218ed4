#!/usr/bin/env bash
# Embedded and emulated targets (docs/embedded.md):
#  1. ctest -L embedded in build/dev: the core's Unity tests on QEMU (Cortex-M3;
#     ARMv6-M with unaligned-access traps, newlib-nano) with the MCU example
#     against a scripted sensor, big-endian s390x (qemu-user) and -m32, each
#     with the host's results; the core built by a plain compiler command;
#  2. the Cortex-M4F and AVR (16-bit int) builds, warnings as errors;
#  3. each firmware configuration option built and leaving code out, and its
#     unit tests run on the host (test/embedded/config_builds.sh);
#  4. the Cortex-M0+ size report and its budgets.
# Every step runs and prints its figures; the check fails if any failed.
set -uo pipefail
ci_apt gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm qemu-user \
  gcc-s390x-linux-gnu libc6-dev-s390x-cross gcc-avr avr-libc libc6-dev-i386 lib32gcc-12-dev
failed=()
step() { # NAME COMMAND...: run, keep going, remember a failure
  local name=$1
  shift
  echo "-- $name"
  "$@" || { echo "-- $name: FAILED"; failed+=("$name"); }
}

emulated() {
  cmake --preset dev >/dev/null && cmake --build --preset dev -j2 >/dev/null || return 1
  # Every emulated target must be registered: a missing tool is a failure here.
  local listed t
  listed=$(ctest --test-dir build/dev -L embedded -N)
  for t in emulated_cortex_m3 emulated_armv6m_unaligned_traps emulated_s390x_big_endian \
           emulated_s390x_catches_byte_order_bug host_m32; do
    grep -q " $t\$" <<<"$listed" || { echo "$t not registered"; return 1; }
  done
  if ! ctest --test-dir build/dev -L embedded -V >build/embedded-ctest.log 2>&1; then
    cat build/embedded-ctest.log
    return 1
  fi
  grep -E "^[0-9]+: +(ok |qemu|s390x|host)|Unity tests, 0 failures|mcu example|Test +#|tests passed" \
    build/embedded-ctest.log
}
quiet_workflow() { # PRESET: configure + build, the log only on failure
  cmake --workflow --preset "$1" >"build/$1.log" 2>&1 || { cat "build/$1.log"; return 1; }
  echo "$1: built with warnings as errors"
}
size_check() {
  quiet_workflow cortex-m0plus || return 1
  cmake --build --preset cortex-m0plus --target size-check
}

step "emulated targets (ctest -L embedded)" emulated
step "Cortex-M4F build" quiet_workflow cortex-m4f
step "AVR build (16-bit int)" quiet_workflow avr
step "firmware configurations" bash test/embedded/config_builds.sh "$PWD" \
  LEP_CONFIG_NO_DEVICE LEP_CONFIG_NO_ERROR_STRINGS
step "Cortex-M0+ size report and budgets" size_check

if [ ${#failed[@]} -gt 0 ]; then
  printf 'embedded: FAILED: %s\n' "${failed[@]}"
  exit 1
fi
echo "embedded: all steps passed"
