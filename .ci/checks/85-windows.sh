#!/usr/bin/env bash
# Windows (docs/windows.md): the mingw preset cross-built with mingw-w64 and
# tested under Wine: 1. `cmake --workflow --preset mingw` (configure, build
# with warnings as errors, ctest through Wine: the core's unit tests and the
# host tests that apply, then the zip); 2. leptrino.exe under Wine against
# the Linux leptrino-sim through a COM port that Wine maps to its pty
# ($WINEPREFIX/dosdevices/com5 -> /dev/pts/N): `info COM5`, `stream COM5
# --duration 2` with the rate and zero gaps checked, a missing port's exit
# code; 3. the in-process virtual sensor: `stream --sim --duration 2` (rate,
# zero gaps) and `example_stream --sim`. A persistent wineserver keeps each
# wine start cheap.
set -euo pipefail
ci_apt gcc-mingw-w64-x86-64 wine64 cmake ninja-build
root=$(pwd)
build=$root/build/mingw
export WINEDEBUG=-all WINEPREFIX=$build/wineprefix

start=$(date +%s)
if ! cmake --workflow --preset mingw >build/mingw-workflow.log 2>&1; then
  cat build/mingw-workflow.log
  exit 1
fi
grep -E "tests passed|Skipped|package: " build/mingw-workflow.log
echo "windows: mingw workflow in $(( $(date +%s) - start )) s"

# The Linux virtual sensor (the dev build's; built here when missing).
sim=$root/build/dev/tools/leptrino-sim/leptrino-sim
if ! [ -x "$sim" ]; then
  cmake --preset dev >/dev/null && cmake --build --preset dev -j2 --target leptrino_sim >/dev/null
fi
exe=$build/tools/leptrino/leptrino.exe
wineserver -p 60 >/dev/null 2>&1 </dev/null || true   # one server for every wine start below
simlog=$(mktemp)
"$sim" >"$simlog" 2>&1 &
simpid=$!
cleanup() {
  kill "$simpid" 2>/dev/null || true
  rm -f "$WINEPREFIX/dosdevices/com5" "$simlog"
  wineserver -k >/dev/null 2>&1 || true
}
trap cleanup EXIT
for _ in $(seq 50); do [ -s "$simlog" ] && break; sleep 0.1; done
pty=$(head -n 1 "$simlog")
case "$pty" in /dev/*) ;; *) echo "windows: leptrino-sim printed no port: $pty"; exit 1 ;; esac
ln -sfn "$pty" "$WINEPREFIX/dosdevices/com5"
fail=0
# wine's output goes to files, never through $(...): the Wine services it
# starts keep a pipe open long after the program has ended.
tmp=$(mktemp -d)
w() { # NAME ARGS...: run leptrino.exe ARGS under Wine, stdout/stderr in $tmp/NAME.{out,err}
  local name=$1
  shift
  set +e
  wine "$exe" "$@" >"$tmp/$name.out" 2>"$tmp/$name.err" </dev/null
  local rc=$?
  set -e
  tr -d '\r' <"$tmp/$name.err" >"$tmp/$name.txt"
  return $rc
}
wine cmd /c exit >/dev/null 2>&1 </dev/null || true   # start Wine's services once

w info info COM5 || { cat "$tmp/info.txt"; echo "windows: info COM5 FAILED"; fail=1; }
tr -d '\r' <"$tmp/info.out" | grep -E "^(model|serial|firmware):" || true
grep -q "PFS055YA501U6" "$tmp/info.out" || { echo "windows: info COM5: no model"; fail=1; }

# A 2 s stream's output (NAME.out, NAME.txt) holds ~1200 Hz, 0 gaps, >= 2300 rows.
check_stream() { # NAME LABEL
  local rows hz gaps
  cat "$tmp/$1.txt"
  rows=$(grep -c '^[0-9]' "$tmp/$1.out" || true)
  hz=$(sed -nE 's/.* ([0-9.]+) Hz measured.*/\1/p' "$tmp/$1.txt" | head -n 1)
  gaps=$(sed -nE 's/.*, ([0-9]+) gaps.*/\1/p' "$tmp/$1.txt" | head -n 1)
  echo "windows: $2 2 s: $rows rows, ${hz:-?} Hz, ${gaps:-?} gaps"
  if [ "${gaps:-x}" != 0 ] || ! awk -v h="${hz:-0}" 'BEGIN { exit !(h >= 1180 && h <= 1220) }' ||
     [ "$rows" -lt 2300 ]; then
    echo "windows: $2: want ~1200 Hz, 0 gaps, >= 2300 rows"
    fail=1
  fi
}

w stream stream COM5 --duration 2 || { echo "windows: stream FAILED"; fail=1; }
check_stream stream "stream COM5"

rc=0
w missing info COM9 || rc=$?
echo "windows: info COM9 (no such port): exit $rc: $(head -n 1 "$tmp/missing.txt")"
[ "$rc" = 6 ] || { echo "windows: want exit 6 (port not found)"; fail=1; }

# The in-process virtual sensor (a loopback port, no hardware, no pty).
w sim stream --sim --duration 2 || { echo "windows: stream --sim FAILED"; fail=1; }
check_stream sim "stream --sim"
set +e
wine "$build/examples/example_stream.exe" --sim >"$tmp/example.out" 2>&1 </dev/null
rc=$?
set -e
echo "windows: example_stream --sim: exit $rc: $(tr -d '\r' <"$tmp/example.out" | sed -n 2p)"
[ "$rc" = 0 ] && grep -q "after the tare" "$tmp/example.out" ||
  { tr -d '\r' <"$tmp/example.out"; echo "windows: example_stream --sim FAILED"; fail=1; }
rm -rf "$tmp"

echo "windows: done in $(( $(date +%s) - start )) s"
exit "$fail"
