#!/bin/sh
# Run ctest with two busy loops beside it (issue 29: the suite must hold on a
# loaded machine; CI check 47 runs it). The busy loops are this script's
# children: killed when it exits (a failure included) or is interrupted, and
# each ends by itself once this script is gone (even killed by SIGKILL).
# usage: tools/test_under_load.sh [BUILD_DIR] [ctest args...]
#   e.g. tools/test_under_load.sh build/dev -L e2e
#   LEPTRINO_BUSY_LOOPS=N  how many busy loops (default 2)
set -eu
build=${1:-build/dev}
[ $# -gt 0 ] && shift
loops=${LEPTRINO_BUSY_LOOPS:-2}
case $loops in '' | *[!0-9]*)
    echo "test_under_load.sh: LEPTRINO_BUSY_LOOPS must be a number (got '$loops')" >&2
    exit 2 ;;
esac
self=$$
pids=""
ct=""
cleanup() {
    # ctest and the test it runs (its own process group), then the loops
    if [ -n "$ct" ]; then kill -TERM "-$ct" 2>/dev/null || kill -TERM "$ct" 2>/dev/null || true; fi
    for p in $pids; do kill "$p" 2>/dev/null || true; done
    for p in $pids $ct; do wait "$p" 2>/dev/null || true; done
    pids=""
    ct=""
}
trap cleanup EXIT
trap 'cleanup; exit 130' INT
trap 'cleanup; exit 143' TERM HUP
# A busy loop: all CPU, a look every few ms whether this script still runs.
busy() {
    while kill -0 "$self" 2>/dev/null; do
        i=0
        while [ $i -lt 20000 ]; do i=$((i + 1)); done
    done
}
n=0
while [ $n -lt "$loops" ]; do
    busy &
    pids="$pids $!"
    n=$((n + 1))
done
echo "test_under_load.sh: $loops busy loop(s) beside ctest (pids$pids)"
# ctest in the background, in a process group of its own, waited for: a
# signal to this script is handled at once (the loops, ctest and its test
# killed), not after ctest has finished
setsid ctest --test-dir "$build" --output-on-failure "$@" &
ct=$!
rc=0
wait "$ct" || rc=$?
ct=""
exit "$rc"
