#!/usr/bin/env bash
# 100 % branch coverage of src/core under the C suite (gcovr), per file.
# COVERAGE_PENDING lists files reported but not failed while their owner
# finishes their tests (frame.c: the perf engineer's tests).
set -euo pipefail
ci_apt gcovr
make coverage COVERAGE_PENDING="${COVERAGE_PENDING-frame.c}"
