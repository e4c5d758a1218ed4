#!/usr/bin/env bash
# The portable core (frame, message, client, device) must build freestanding:
# only <stdint.h> <stddef.h> <stdbool.h> <string.h> and the project's headers,
# no allocation, no stdio, no OS calls, no mutable global state.
# usage: core_purity.sh SOURCE_DIR CC GENERATED_INCLUDE_DIR
set -u
src=$1 cc=$2 gen=$3
fail=0
allowed_std='stdint.h|stddef.h|stdbool.h|string.h'
core_headers="leptrino.h config.h export.h error.h frame.h message.h client.h device.h"
files=("$src"/src/core/*.c)
for h in $core_headers; do files+=("$src/include/leptrino/$h"); done

for f in "${files[@]}"; do
  while IFS= read -r line; do
    inc=$(sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*([<"])([^>"]+)[>"].*/\1\2/' <<<"$line")
    case "$inc" in
      '"'*) name=${inc#\"}
            case "$name" in
              leptrino/leptrino.h|leptrino/export.h|leptrino/error.h|leptrino/frame.h|\
              leptrino/message.h|leptrino/client.h|leptrino/device.h|leptrino/version.h|leptrino/config.h|\
              config.h|export.h|error.h|frame.h|message.h|client.h|device.h|version.h|leptrino/version.h) ;;
              *) echo "FAIL $f: project include outside the core: $name"; fail=1 ;;
            esac ;;
      '<'*) name=${inc#<}
            if ! grep -Eqx "$allowed_std" <<<"$name"; then
              echo "FAIL $f: includes <$name>"; fail=1
            fi ;;
    esac
  done < <(grep -E '^[[:space:]]*#[[:space:]]*include' "$f")
done

# Build each core file freestanding and look at what it needs and defines.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for f in "$src"/src/core/*.c; do
  obj="$tmp/$(basename "$f" .c).o"
  if ! "$cc" -std=c99 -ffreestanding -fno-builtin -O2 -Wall -Wextra -Werror \
      -I"$src/include" -I"$gen" -c "$f" -o "$obj"; then
    echo "FAIL $f does not build freestanding"; fail=1; continue
  fi
  writable=$(nm "$obj" | awk '$2 ~ /^[bBdDcC]$/ {print $3}' || true)
  if [ -n "$writable" ]; then
    echo "FAIL $f has mutable global or static data: $(echo $writable)"; fail=1
  fi
done

# What the core needs from outside itself: only these few string.h functions.
defined=$(nm --defined-only "$tmp"/*.o | awk 'NF == 3 {print $3}' | sort -u)
needed=$(nm -u "$tmp"/*.o | awk 'NF >= 2 {print $NF}' | sort -u)
outside=$(comm -23 <(echo "$needed") <(echo "$defined") | grep -Ev '^(memcpy|memset|memmove|memcmp|strlen)$' || true)
if [ -n "$outside" ]; then
  echo "FAIL the core calls outside the allowed set: $(echo $outside)"; fail=1
fi

if [ $fail -eq 0 ]; then
  echo "core purity: ${#files[@]} files checked, OK"
fi
exit $fail
