#!/usr/bin/env bash
# The timing-sensitive tests (ctest label e2e: ptys, threads, the virtual
# sensor, the session's timeline) with two busy loops beside them
# (tools/test_under_load.sh), as a loaded CI machine runs them. The whole
# suite that way takes longer than CI allows; the unit tests have no timing.
set -euo pipefail
cmake --preset dev >/dev/null
cmake --build --preset dev -j2
tools/test_under_load.sh build/dev -L e2e -j2
