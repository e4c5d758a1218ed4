#!/usr/bin/env bash
# 100 % branch coverage of src/core under the C suite (gcovr), per file.
# COVERAGE_PENDING may list files to report without failing (none now).
set -euo pipefail
ci_apt gcovr
make coverage COVERAGE_PENDING="${COVERAGE_PENDING-}"
