#!/usr/bin/env bash
# The FFI examples (examples/ffi, docs/ffi.md): Go through cgo, Java through
# JNA, Node through koffi, each run against libleptrino.so (Release, installed
# into a prefix under build/) and the in-process virtual sensor: identity,
# rated values, 1 s of samples and their rate, a tare, a missing port's
# message. Each program exits non-zero when something did not behave. Needs
# the machine's Go, Debian's maven and a JDK, Node with npm (koffi from the npm
# registry, JNA and Maven's plugins from Maven Central).
set -euo pipefail
cd "$(dirname "$0")/../.."
ci_apt gcc cmake ninja-build pkg-config maven default-jdk-headless
if ! command -v go >/dev/null && [ -x /usr/local/go/bin/go ]; then
  export PATH="/usr/local/go/bin:$PATH"
fi
for tool in go mvn javac node npm; do
  command -v "$tool" >/dev/null || { echo "70-ffi: $tool not found"; exit 1; }
done
root=$PWD
t0=$(date +%s)
lap() { echo "-- $1 in $(( $(date +%s) - t0 )) s"; t0=$(date +%s); }

echo "-- no layout mirrored on the main path (no JNA Structure, no koffi struct)"
if grep -nE 'extends Structure|import com\.sun\.jna\.Structure' examples/ffi/java -r ||
   grep -nE 'koffi\.(struct|union|pack)\(' examples/ffi/node/*.js; then
  echo "70-ffi: an example mirrors a C layout"; exit 1
fi

echo "-- libleptrino.so (Release)"
cmake -S . -B build/ffi -G Ninja -DLEPTRINO_BUILD_TESTS=OFF -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/ffi >/dev/null
prefix="$root/build/ffi-prefix"
rm -rf "$prefix"
cmake --install build/ffi --prefix "$prefix" >/dev/null
libdir=$(dirname "$(dirname "$(find "$prefix" -name leptrino.pc | head -n 1)")")
[ -f "$libdir/libleptrino.so" ] || { echo "70-ffi: no libleptrino.so under $prefix"; exit 1; }
export LEPTRINO_LIB="$libdir/libleptrino.so"
lap "library built and installed"

echo "-- Go (cgo)"
(
  cd examples/ffi/go
  export PKG_CONFIG_PATH="$libdir/pkgconfig" CGO_ENABLED=1
  # Go's build cache does not hash an external library or the headers it
  # includes from -I: a binary linked against an older libleptrino (another
  # SONAME) would be reused. A define carrying their hash keys the cache.
  stamp=$(cat "$libdir"/libleptrino.so "$prefix"/include/leptrino/*.h | sha256sum | cut -c1-16)
  export CGO_CPPFLAGS="-DLEPTRINO_FFI_STAMP=$stamp"
  go vet .
  go build -o "$root/build/ffi/leptrino-ffi-go" .
  LD_LIBRARY_PATH="$libdir" "$root/build/ffi/leptrino-ffi-go"
)
lap "Go"

echo "-- Java (JNA)"
# Debian's Maven 3.8 writes colour resets even in batch mode: stripped for the log.
mvn -q -B -f examples/ffi/java/pom.xml compile exec:exec 2>&1 |
  sed 's/\x1b\[[0-9;]*m//g'
lap "Java"

echo "-- Node (koffi)"
(
  cd examples/ffi/node
  npm ci --no-audit --no-fund --loglevel=error
  node example.js
)
lap "Node"
