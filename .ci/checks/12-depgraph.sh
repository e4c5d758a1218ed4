#!/usr/bin/env bash
# Files depend one way: a file-level dependency graph of the library's
# (src/core, src/host/*) and the CLI's (tools/leptrino) object files, built
# from their symbols with nm (who defines, who references), must have no
# cycle; a cycle is named with the symbols that make it (test/checks/depgraph.py).
# The objects are the dev build's, one per tracked source file (no stale ones).
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
start=$(date +%s)
if ! [ -d build/dev/src/CMakeFiles/leptrino_static.dir ] || ! [ -d build/dev/tools/leptrino/CMakeFiles/leptrino_cli.dir ]; then
  cmake --preset dev >/dev/null && cmake --build --preset dev >/dev/null
fi
objs() { # objects dir, then sources relative to the dir they are compiled from
  local dir=$1 base=$2; shift 2
  # The Win32 files (*_win32.c) are built by the mingw preset, not here.
  for f in $(git ls-files "$@" | grep -v '_win32\.c$'); do
    o="$dir/${f#"$base"/}.o"
    [ -f "$o" ] || { echo "depgraph: no object $o for $f (build first)" >&2; exit 2; }
    printf '%s\n' "$o"
  done
}
lib=$(objs build/dev/src/CMakeFiles/leptrino_static.dir src 'src/core/*.c' 'src/host/*/*.c')
cli=$(objs build/dev/tools/leptrino/CMakeFiles/leptrino_cli.dir tools/leptrino 'tools/leptrino/*.c')
# shellcheck disable=SC2086
python3 test/checks/depgraph.py --dot build/dev/depgraph.dot --group library $lib --group cli $cli
# (The session's map of who writes what, test/checks/unit_fields.py, is a
# ctest of its own: every build's suite runs it with its one set of arguments.)
echo "depgraph: no cycle ($(( $(date +%s) - start )) s; graph in $root/build/dev/depgraph.dot)"
