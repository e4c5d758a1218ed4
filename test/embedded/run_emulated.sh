#!/usr/bin/env bash
# Build the core's Unity tests for another target (a toolchain file of
# cmake/toolchains), run them there through ctest (QEMU system or user mode,
# or natively for -m32), and require the same results as the host build:
# every test program reports the same number of tests, 0 failures, and the
# same number ignored.
# usage: run_emulated.sh CMAKE CTEST SOURCE_DIR BUILD_DIR TOOLCHAIN HOST_TEST_DIR TEST...
set -uo pipefail
cmake=$1 ctest=$2 src=$3 build=$4 toolchain=$5 host=$6
shift 6

summary() { grep -Eo '[0-9]+ Tests [0-9]+ Failures [0-9]+ Ignored' | tail -n 1; }

if [ ! -f "$build/CMakeCache.txt" ]; then
  "$cmake" -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=MinSizeRel \
    -DCMAKE_TOOLCHAIN_FILE="$src/cmake/toolchains/$toolchain.cmake" >"$build.configure.log" 2>&1 ||
    { cat "$build.configure.log"; echo "FAIL: configure for $toolchain"; exit 1; }
fi
"$cmake" --build "$build" -j2 >"$build.build.log" 2>&1 ||
  { cat "$build.build.log"; echo "FAIL: build for $toolchain"; exit 1; }

fail=0
total=0
for t in "$@"; do
  out=$("$ctest" --test-dir "$build" -R "^$t\$" -V --timeout 300 2>&1)
  rc=$?
  got=$(summary <<<"$out")
  want=$("$host/$t" 2>&1 | summary)
  if [ $rc -ne 0 ] || [ -z "$got" ] || [ "$got" != "$want" ]; then
    echo "$out" | tail -n 40
    echo "FAIL $toolchain $t: '$got' (ctest $rc), host: '$want'"
    fail=1
  else
    echo "ok   $toolchain $t: $got (as on the host)"
    total=$((total + ${got%% *}))
  fi
done
# Tests of the target runtime itself (e.g. the unaligned-access trap is on).
out=$("$ctest" --test-dir "$build" -E "^($(IFS='|'; echo "$*"))\$" --timeout 120 2>&1)
rc=$?
if ! grep -q "No tests were found" <<<"$out"; then
  if [ $rc -ne 0 ]; then echo "$out"; echo "FAIL $toolchain: target runtime checks"; fail=1
  else grep -E "Test +#" <<<"$out" | sed "s/^/     $toolchain /"; fi
fi
[ $fail -eq 0 ] && echo "$toolchain: $total Unity tests, 0 failures, same as the host"
exit $fail
