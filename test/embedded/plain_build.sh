#!/usr/bin/env bash
# Build the portable core with a plain compiler command, as an IDE project or
# a makefile of one's own would: no CMake, no generated header, just
# include/ on the include path. Then run a small program against it.
# usage: plain_build.sh SOURCE_DIR CC VERSION WORK_DIR
set -euo pipefail
src=$1 cc=$2 version=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
set -x
"$cc" -std=c99 -Os -Wall -Wextra -Wpedantic -Wconversion -Werror -I"$src/include" \
  "$src"/src/core/*.c "$src/test/embedded/plain_main.c" -o "$work/plain_main"
"$work/plain_main" "$version"
