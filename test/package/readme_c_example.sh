#!/usr/bin/env bash
# Every ```c block of README.md is a complete program: extract each one,
# compile it as shown (C99, warnings as errors) with the given flags (the build
# tree's, or `pkg-config --cflags --libs leptrino` for an installed copy as the
# README says), and, when the virtual sensor program is given (not "-"), run it
# against leptrino-sim and check that it identifies the sensor, reports the
# samples of 1 s and their rate, prints 10 samples and names a missing port.
# usage: readme_c_example.sh README CC LEPTRINO_SIM|- COMPILER_AND_LINKER_FLAGS...
set -eu
readme=$1 cc=$2 sim=$3
shift 3
[ "$sim" = "-" ] && sim=
tmp=$(mktemp -d)
sim_pid=
cleanup() {
  if [ -n "$sim_pid" ]; then kill "$sim_pid" 2>/dev/null || true; wait "$sim_pid" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT

awk -v dir="$tmp" '
  /^```c[[:space:]]*$/ { n++; out = sprintf("%s/example%d.c", dir, n); inblock = 1; next }
  /^```/ && inblock   { inblock = 0; close(out); next }
  inblock             { print > out }
  END                 { print n + 0 > (dir "/count") }
' "$readme"
count=$(cat "$tmp/count")
if [ "$count" -lt 1 ]; then
  echo "FAIL no \`\`\`c block in $readme"; exit 1
fi

for i in $(seq 1 "$count"); do
  src="$tmp/example$i.c"
  if ! "$cc" -std=c99 -Wall -Wextra -Wpedantic -Werror "$src" "$@" -o "$tmp/example$i"; then
    echo "FAIL README.md C block $i does not compile and link as shown:"; cat -n "$src"; exit 1
  fi
done
echo "README.md: $count C block(s) compile and link as shown"

# Run them against the virtual sensor: each must identify it and print samples.
if [ -n "$sim" ]; then
  link="$tmp/sensor"
  "$sim" --link "$link" --exit-after 60 >"$tmp/sim.out" 2>&1 &
  sim_pid=$!
  for _ in $(seq 1 200); do [ -e "$link" ] && break; sleep 0.05; done
  [ -e "$link" ] || { echo "FAIL leptrino-sim did not make $link"; exit 1; }
  for i in $(seq 1 "$count"); do
    if ! timeout 30 "$tmp/example$i" "$link" >"$tmp/run$i.out" 2>&1; then
      echo "FAIL README.md C block $i failed against leptrino-sim:"; cat "$tmp/run$i.out"; exit 1
    fi
    rows=$(grep -c '^Fz ' "$tmp/run$i.out" || true)
    if ! grep -q 'serial' "$tmp/run$i.out" || [ "$rows" -ne 10 ]; then
      echo "FAIL README.md C block $i printed $rows samples (want 10):"; cat "$tmp/run$i.out"; exit 1
    fi
    # 1 s of samples and their rate (not checked for 1200 Hz: a loaded machine
    # starves the virtual sensor; the rate is tested where it is the subject),
    # and the missing port named
    if ! grep -Eq '^[1-9][0-9]* samples, [1-9][0-9]*\.[0-9] Hz$' "$tmp/run$i.out" ||
       ! grep -q '^as expected: /dev/leptrino-none: ' "$tmp/run$i.out"; then
      echo "FAIL README.md C block $i: no rate over 1 s or no message for the missing port:"
      cat "$tmp/run$i.out"; exit 1
    fi
  done
  echo "README.md: $count C block(s) ran against leptrino-sim (10 samples each)"
fi
