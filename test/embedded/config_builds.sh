#!/usr/bin/env bash
# Firmware configurations of the portable core: each compile-time option
# (LEP_CONFIG_*) built for a Cortex-M0+ with the project's warnings as errors,
# and it must really leave code out (a smaller .text than the default build);
# then all of them together. Then each configuration (and all together) is
# built on the host with its CMake option (LEP_CONFIG_NO_X is LEPTRINO_NO_X)
# and its unit tests run: test_config checks the option took its feature out,
# and the tests of what remains (frame, message; client and device with the
# device side; the texts with the strings) must pass.
# usage: config_builds.sh SOURCE_DIR OPTION...
set -uo pipefail
src=$1
shift
cc=arm-none-eabi-gcc
flags=(-std=c99 -mcpu=cortex-m0plus -mthumb -Os -ffunction-sections -fdata-sections
       -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Wstrict-prototypes -Wmissing-prototypes
       -Wundef -Wcast-align -Werror -DLEPTRINO_STATIC -I"$src/include")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

text_of() { # DIR: total .text of the objects built there
  arm-none-eabi-size -t "$1"/*.o | awk 'END {print $1}'
}
build() { # DIR DEFINES...
  local dir=$1 f
  shift
  mkdir -p "$dir"
  for f in "$src"/src/core/*.c; do
    "$cc" "${flags[@]}" "$@" -c "$f" -o "$dir/$(basename "$f" .c).o" || return 1
  done
}

build "$work/default" || { echo "FAIL: default configuration"; exit 1; }
base=$(text_of "$work/default")
echo "default: $base bytes of .text"
fail=0
for opt in "$@"; do
  if ! build "$work/$opt" "-D$opt=1"; then
    echo "FAIL $opt: does not build warning-free"; fail=1; continue
  fi
  size=$(text_of "$work/$opt")
  if [ "$size" -lt "$base" ]; then
    echo "ok   $opt: $size bytes of .text ($((base - size)) left out)"
  else
    echo "FAIL $opt: $size bytes of .text, nothing left out (is the option implemented?)"; fail=1
  fi
done
# All of them together.
all_opts=("$@")
if [ $# -gt 1 ]; then
  defs=()
  for opt in "$@"; do defs+=("-D$opt=1"); done
  if build "$work/all" "${defs[@]}"; then
    echo "ok   all options: $(text_of "$work/all") bytes of .text"
  else
    echo "FAIL all options together: does not build warning-free"; fail=1
  fi
fi
# The unit tests of each configuration, on the host.
host_tests() { # NAME CMAKE_OPTIONS...: configure, build, ctest in build/config-NAME
  local name=$1 dir="$src/build/config-$1" log
  shift
  log="$dir.log"
  if cmake -S "$src" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DLEPTRINO_CORE_ONLY=ON \
       -DLEPTRINO_BUILD_SHARED=OFF -DLEPTRINO_UNIT_TESTS_ONLY=ON "$@" >"$log" 2>&1 &&
     cmake --build "$dir" >>"$log" 2>&1 &&
     ctest --test-dir "$dir" --output-on-failure >>"$log" 2>&1; then
    echo "ok   tests of $name: $(grep -Eo '[0-9]+ tests? failed out of [0-9]+' "$log" | tail -1)"
  else
    cat "$log"
    echo "FAIL tests of $name"
    return 1
  fi
}
cmake_opts=()
for opt in "${all_opts[@]}"; do
  cmake_opt="-DLEPTRINO_${opt#LEP_CONFIG_}=ON"
  cmake_opts+=("$cmake_opt")
  host_tests "$opt" "$cmake_opt" || fail=1
done
if [ ${#all_opts[@]} -gt 1 ]; then
  host_tests all "${cmake_opts[@]}" || fail=1
fi
exit $fail
