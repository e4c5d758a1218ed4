#!/bin/sh
# Run ctest with two busy loops beside it (issue 29: the suite must hold on a
# loaded machine). The busy loops are this script's children, killed on exit.
# usage: tools/test_under_load.sh [BUILD_DIR] [ctest args...]
#   e.g. tools/test_under_load.sh build/dev -L e2e
set -eu
build=${1:-build/dev}
[ $# -gt 0 ] && shift
pids=""
cleanup() {
    for p in $pids; do kill "$p" 2>/dev/null || true; done
    for p in $pids; do wait "$p" 2>/dev/null || true; done
}
trap cleanup EXIT INT TERM
for i in 1 2; do
    (while :; do :; done) &
    pids="$pids $!"
done
ctest --test-dir "$build" --output-on-failure "$@"
