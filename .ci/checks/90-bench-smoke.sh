#!/usr/bin/env bash
# Smoke run of leptrino-bench (a minute at most): it builds with the project,
# runs every measurement briefly, and prints one JSON object that must parse
# and hold every key BENCHMARKS.md describes. Never fails on speed.
set -euo pipefail
ci_apt valgrind strace python3
cmake --preset dev >/dev/null
cmake --build build/dev -j2 --target leptrino-bench leptrino-sim
out=build/dev/bench-smoke.json
timeout 300 build/dev/bench/leptrino-bench --smoke >"$out"
python3 bench/check_bench_json.py "$out"
