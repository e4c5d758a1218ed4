#!/usr/bin/env bash
# Install the build into a temporary prefix, then build and run a small
# consumer against it through pkg-config and through find_package.
# usage: install_consumer.sh BUILD_DIR CONSUMER_DIR CMAKE CC VERSION
set -eu
build=$1 consumer=$2 cmake=$3 cc=$4 version=$5
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"
"$cmake" --install "$build" --prefix "$prefix" >/dev/null

pc=$(find "$prefix" -name leptrino.pc | head -n 1)
[ -n "$pc" ] || { echo "FAIL leptrino.pc not installed"; exit 1; }
export PKG_CONFIG_PATH=$(dirname "$pc")
[ "$(pkg-config --modversion leptrino)" = "$version" ] || { echo "FAIL pkg-config version"; exit 1; }
libdir=$(pkg-config --variable=libdir leptrino)

# 1. pkg-config, shared library.
# shellcheck disable=SC2046
"$cc" -std=c99 -Wall -Wextra -Werror "$consumer/consumer.c" -o "$tmp/consumer_pc" \
  $(pkg-config --cflags --libs leptrino) -Wl,-rpath,"$libdir"
"$tmp/consumer_pc" "$version"

# 2. pkg-config, static library.
# shellcheck disable=SC2046
"$cc" -std=c99 -Wall -Wextra -Werror -DLEPTRINO_STATIC "$consumer/consumer.c" -o "$tmp/consumer_static" \
  $(pkg-config --cflags leptrino) "$libdir/libleptrino.a" $(pkg-config --static --libs-only-other leptrino)
"$tmp/consumer_static" "$version"

# 3. find_package(leptrino CONFIG) -> leptrino::leptrino.
"$cmake" -S "$consumer" -B "$tmp/cmake-build" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_C_COMPILER="$cc" >/dev/null
"$cmake" --build "$tmp/cmake-build" >/dev/null
"$tmp/cmake-build/consumer" "$version"
echo "install consumer: pkg-config (shared, static) and find_package OK"
