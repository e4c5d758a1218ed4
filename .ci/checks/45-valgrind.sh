#!/usr/bin/env bash
# The end-to-end C tests (ctest label e2e: serial, sim, record, session ...)
# under valgrind memcheck: any memcheck error or definite leak fails.
set -euo pipefail
ci_apt valgrind
cmake --preset dev >/dev/null
cmake --build --preset dev -j2
cmake --build build/dev --target valgrind
