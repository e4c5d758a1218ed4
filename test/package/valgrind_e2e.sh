#!/usr/bin/env bash
# The end-to-end C tests (ctest label "e2e": the Unity programs of test/posix)
# under valgrind memcheck. A test fails on any memcheck error or a definite
# leak (--error-exitcode), or when it fails by itself under the slowdown;
# the memcheck log of every test that fails is printed.
# usage: valgrind_e2e.sh BUILD_DIR CTEST VALGRIND [LABEL]
set -euo pipefail
build=$1 ctest=$2 valgrind=$3 label=${4:-e2e}
valgrind=$(command -v "$valgrind") || { echo "FAIL valgrind not found"; exit 1; }
opts="--error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite --show-leak-kinds=definite --num-callers=30 --track-origins=yes"
logs="$build/Testing/Temporary"
rm -f "$logs"/MemoryChecker.*.log

n=$("$ctest" --test-dir "$build" -L "$label" -N | sed -n 's/^Total Tests: //p')
if [ "${n:-0}" -lt 1 ]; then
  echo "FAIL no test has the label '$label'"; exit 1
fi
echo "valgrind memcheck ($("$valgrind" --version)) on $n test(s) labelled $label: $opts"

# No include(CTest) here, so no DartConfiguration.tcl: the memcheck command
# and its options are given on the command line (ctest then says it cannot
# find that file, which is expected and filtered out).
set +e
"$ctest" --test-dir "$build" -L "$label" -T memcheck --output-on-failure \
  --overwrite MemoryCheckCommand="$valgrind" \
  --overwrite MemoryCheckCommandOptions="$opts" 2>&1 \
  | grep --line-buffered -v -e 'DartConfiguration.tcl' -e '^   Site: $' -e '^   Build name: (empty)$'
status=${PIPESTATUS[0]}
set -e

bad=0
for log in "$logs"/MemoryChecker.*.log; do
  [ -e "$log" ] || continue
  if grep -Eq 'ERROR SUMMARY: [1-9]|definitely lost: [1-9]' "$log"; then
    bad=1
    echo "---- $log"
    cat "$log"
  fi
done
if [ "$status" -ne 0 ] || [ "$bad" -ne 0 ]; then
  echo "FAIL valgrind: see above (ctest status $status)"
  exit 1
fi
echo "valgrind: $n end-to-end test(s) clean (no memcheck error, no definite leak)"
