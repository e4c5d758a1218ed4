#!/usr/bin/env bash
# Firmware configurations of the portable core: each compile-time option
# (LEP_CONFIG_*) built for a Cortex-M0+ with the project's warnings as errors,
# and it must really leave code out (a smaller .text than the default build);
# then all of them together.
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
if [ $# -gt 1 ]; then
  defs=()
  for opt in "$@"; do defs+=("-D$opt=1"); done
  if build "$work/all" "${defs[@]}"; then
    echo "ok   all options: $(text_of "$work/all") bytes of .text"
  else
    echo "FAIL all options together: does not build warning-free"; fail=1
  fi
fi
exit $fail
