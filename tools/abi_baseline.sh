#!/usr/bin/env bash
# Regenerate the ABI baseline, abi/libleptrino.abi, from a fresh build of the
# shared library with debug info (in build/abi), as seen through the public
# headers (include/leptrino). Run it on purpose, in the commit that changes
# the API, and commit the new baseline with the change; CI
# (.ci/checks/15-abi.sh) compares every build with it (tools/abi_check.sh).
# An incompatible change needs the SONAME to move first: bump
# project(leptrino VERSION ...) in CMakeLists.txt (and include/leptrino/version.h).
# Needs cmake, ninja, a C compiler, readelf and abigail-tools (abidw).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v abidw >/dev/null || { echo "abi_baseline: abidw not found (apt-get install abigail-tools)" >&2; exit 2; }
lib=$(tools/abi_check.sh build build/abi)
mkdir -p abi
# Where the baseline stands now, to say what the new one changes.
if [ -f abi/libleptrino.abi ]; then
  tools/abi_check.sh compare abi/libleptrino.abi "$lib" include/leptrino || true
fi
tools/abi_check.sh dump "$lib" include/leptrino abi/libleptrino.abi
echo "abi_baseline: wrote abi/libleptrino.abi ($(sed -n "s/^<abi-corpus [^>]*soname='\([^']*\)'.*/\1/p" abi/libleptrino.abi | head -n 1)); commit it with the API change"
