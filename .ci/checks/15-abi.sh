#!/usr/bin/env bash
# The shared library's ABI against the committed baseline abi/libleptrino.abi
# (libabigail; the rule is tools/abi_check.sh's): a compatible change (an
# addition) passes with a warning that the baseline is stale; an incompatible
# one fails unless the SONAME moved with it (bump project(VERSION) in
# CMakeLists.txt, then tools/abi_baseline.sh). First the checker itself is
# shown to decide right on a throwaway library (test/checks/abi_selftest.sh).
# The library is built alone with debug info, without tests, in build/abi.
set -euo pipefail
cd "$(dirname "$0")/../.."
ci_apt abigail-tools binutils gcc cmake ninja-build python3
start=$(date +%s)
bash test/checks/abi_selftest.sh
arch=$(sed -n "s/^<abi-corpus [^>]*architecture='\([^']*\)'.*/\1/p" abi/libleptrino.abi | head -n 1)
if [ "$arch" = elf-amd-x86_64 ] && [ "$(uname -m)" != x86_64 ]; then
  echo "abi: the baseline is for $arch, this is $(uname -m): library not compared"
  exit 0
fi
lib=$(tools/abi_check.sh build build/abi)
tools/abi_check.sh compare abi/libleptrino.abi "$lib" include/leptrino
echo "abi: $(abidiff --version) ($(( $(date +%s) - start )) s)"
