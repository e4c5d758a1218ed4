#!/usr/bin/env bash
# Proof that the big-endian run matters: plant a byte-order bug in a copy of
# the core (the message codec's get_le reads the wire's little-endian bytes
# in host order, with memcpy), then require that the core's tests still pass
# on the (little-endian) host but fail on big-endian s390x under qemu-user.
# usage: byte_order_mutant.sh CMAKE CTEST SOURCE_DIR WORK_DIR
set -uo pipefail
cmake=$1 ctest=$2 src=$3 work=$4
rm -rf "$work" && mkdir -p "$work/tree"
# A copy of the source tree (without build trees and git metadata).
tar -C "$src" --exclude=./build --exclude=./.git --exclude='./.venv' -cf - . | tar -C "$work/tree" -xf - || exit 1

python3 - "$work/tree/src/core/message.c" <<'PY' || exit 1
import re, sys
path = sys.argv[1]
text = open(path).read()
pattern = re.compile(r"(static uint32_t get_le\(const uint8_t \*p, unsigned n\)\s*\{)(.*?)(\n\})", re.S)
if not pattern.search(text):
    sys.exit("FAIL: get_le not found in src/core/message.c: update this mutant")
text = pattern.sub(r"\1\n    uint32_t v = 0; /* planted bug: host byte order */\n"
                   r"    memcpy(&v, p, n);\n    return v;\3", text, count=1)
if "#include <string.h>" not in text:
    text = "#include <string.h>\n" + text
open(path, "w").write(text)
PY

build() { # NAME EXTRA-CMAKE-ARGS...: configure + build the unit tests of the mutant
  local name=$1
  shift
  "$cmake" -S "$work/tree" -B "$work/$name" -G Ninja -DCMAKE_BUILD_TYPE=MinSizeRel "$@" \
    >"$work/$name.log" 2>&1 && "$cmake" --build "$work/$name" -j2 >>"$work/$name.log" 2>&1 ||
    { cat "$work/$name.log"; echo "FAIL: the mutant does not build ($name)"; exit 1; }
}
build host -DLEPTRINO_CORE_ONLY=ON -DLEPTRINO_BUILD_SHARED=OFF -DLEPTRINO_UNIT_TESTS_ONLY=ON
build s390x -DCMAKE_TOOLCHAIN_FILE="$work/tree/cmake/toolchains/s390x-linux-gnu.cmake"

fail=0
if "$ctest" --test-dir "$work/host" -R '^test_message$' >/dev/null 2>&1; then
  echo "ok   little-endian host: the mutant passes test_message (a pure byte-order bug)"
else
  echo "FAIL little-endian host: the mutant fails test_message, so it is not a byte-order bug"; fail=1
fi
out=$("$ctest" --test-dir "$work/s390x" -R '^test_message$' -V 2>&1)
if [ $? -ne 0 ]; then
  echo "ok   big-endian s390x: the mutant is caught: $(grep -Eo '[0-9]+ Tests [0-9]+ Failures' <<<"$out" | tail -n 1)"
else
  echo "FAIL big-endian s390x: the planted byte-order bug went unnoticed"; fail=1
fi
exit $fail
