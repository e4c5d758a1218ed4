#!/usr/bin/env bash
# Build the portable core with a plain compiler command, as an IDE project or
# a makefile of one's own would: no CMake, no generated header, just
# include/ on the include path. Then run a small program against it.
# A Windows compiler also gets -DLEPTRINO_STATIC, as include/leptrino/export.h
# asks of a program that compiles the sources itself (else: dllimport).
# usage: plain_build.sh SOURCE_DIR CC VERSION WORK_DIR [EMULATOR...]
set -euo pipefail
src=$1 cc=$2 version=$3 work=$4
shift 4
rm -rf "$work" && mkdir -p "$work"
defs=()
case "$("$cc" -dumpmachine)" in
  *mingw* | *windows* | *cygwin*) defs=(-DLEPTRINO_STATIC) ;;
esac
set -x
"$cc" -std=c99 -Os -Wall -Wextra -Wpedantic -Wconversion -Werror "${defs[@]}" -I"$src/include" \
  "$src"/src/core/*.c "$src/test/embedded/plain_main.c" -o "$work/plain_main"
exe=$work/plain_main
[ -e "$exe.exe" ] && exe=$exe.exe   # a Windows compiler adds .exe
"$@" "$exe" "$version"
