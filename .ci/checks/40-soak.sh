#!/usr/bin/env bash
# leptrino-soak for 60 s: the client against the virtual sensor with every fault
# on; fails on any wrong, duplicated or out-of-order sample (docs/soak.md).
set -euo pipefail
cmake --preset dev >/dev/null
cmake --build build/dev -j2 --target leptrino_soak
build/dev/tools/leptrino-soak/leptrino-soak --duration 60 --seed "${LEPTRINO_SOAK_SEED:-1}"
build/dev/tools/leptrino-soak/leptrino-soak --bit-errors 200000
