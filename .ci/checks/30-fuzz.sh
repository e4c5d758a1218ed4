#!/usr/bin/env bash
# Fuzzing: each libFuzzer target (test/fuzz/fuzz_*.c) about a minute with clang,
# the library itself instrumented (-DLEPTRINO_FUZZ=ON), seeded from the shared
# vectors and the regression inputs of earlier finds. Fails on any crash, leak,
# sanitizer report or broken invariant. FUZZ_SECONDS overrides the time per target.
set -euo pipefail
ci_apt clang libclang-rt-14-dev llvm python3
seconds=${FUZZ_SECONDS:-60}
build=build/fuzz
CC=clang cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLEPTRINO_FUZZ=ON \
  -DLEPTRINO_CORE_ONLY=ON -DLEPTRINO_BUILD_SHARED=OFF -DLEPTRINO_BUILD_TESTS=ON >/dev/null
cmake --build "$build" -j2 --target fuzz_protocol fuzz_message fuzz_device fuzz_client
rm -rf "$build/seeds" "$build/crashes"
mkdir -p "$build/crashes"
python3 test/fuzz/seeds.py "$build/seeds"
status=0
for t in protocol message device client; do
  corpus="$build/corpus/$t"
  mkdir -p "$corpus"
  seeds=("$build/seeds/$t")
  if [ -d "test/fuzz/regressions/$t" ]; then seeds+=("test/fuzz/regressions/$t"); fi
  log="$build/fuzz-$t.log"
  if "$build/test/fuzz/fuzz_$t" -max_total_time="$seconds" -print_final_stats=1 -timeout=10 \
      -rss_limit_mb=1024 -artifact_prefix="$build/crashes/$t-" "$corpus" "${seeds[@]}" >"$log" 2>&1; then
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    cov=$(grep -Eo 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1)
    echo "fuzz_$t: ${execs:-?} execs in ${seconds} s, ${cov:-cov ?}, corpus $(ls "$corpus" | wc -l), 0 crashes"
  else
    echo "fuzz_$t: FAILED (see $log)"; tail -40 "$log"; status=1
  fi
done
ls "$build/crashes"
exit $status
