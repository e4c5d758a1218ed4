#!/usr/bin/env bash
# The Rust crates (bindings/rust: leptrino-sys and leptrino): rustfmt, clippy
# and rustdoc with -D warnings, cargo test (unit, integration against the in-process
# virtual sensor, rustdoc examples) with the C sources compiled by the crate,
# the example, the same tests linked to an installed libleptrino found by
# pkg-config (build/dev installed into a prefix under build/), and
# `cargo package` of both crates, each verified by building the packaged
# crate from its own files. Needs crates.io (bindgen, cc, pkg-config) and
# rustup's cargo with clippy and rustfmt (on this machine kind).
set -euo pipefail
cd "$(dirname "$0")/../.."
ci_apt libclang-dev pkg-config gcc cmake ninja-build
if ! command -v cargo >/dev/null && [ -x "$HOME/.cargo/bin/cargo" ]; then
  export PATH="$HOME/.cargo/bin:$PATH"
fi
command -v cargo >/dev/null || { echo "65-rust: cargo not found (rustup's toolchain is needed)"; exit 1; }
cargo --version
root=$PWD
export CARGO_TARGET_DIR="$root/build/rust"
cd bindings/rust

echo "-- rustfmt, clippy"
cargo fmt --all --check
cargo clippy --workspace --all-targets --locked -- -D warnings
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked -q

echo "-- cargo test (bundled C sources)"
LEPTRINO_SYS_BUNDLED=1 timeout 600 cargo test --workspace --locked

echo "-- the example"
LEPTRINO_SYS_BUNDLED=1 cargo run -q --locked --example stream -- --sim --seconds 0.5 | tail -3

echo "-- cargo test linked to an installed libleptrino (pkg-config)"
if [ ! -f "$root/build/dev/CMakeCache.txt" ]; then
  (cd "$root" && cmake --preset dev >/dev/null && cmake --build --preset dev >/dev/null)
fi
prefix="$root/build/rust-prefix"
rm -rf "$prefix"
cmake --install "$root/build/dev" --prefix "$prefix" >/dev/null
libdir=$(dirname "$(find "$prefix" -name leptrino.pc | head -n 1)")/..
PKG_CONFIG_PATH="$libdir/pkgconfig" LEPTRINO_SYS_PKG_CONFIG=1 LD_LIBRARY_PATH="$libdir" \
  timeout 600 cargo test --workspace --locked
# the tests above ran against the shared library, not a static copy
test_bin=$(ls -t "$CARGO_TARGET_DIR"/debug/deps/sensor-* | grep -v '\.d$' | head -n 1)
deps=$(LD_LIBRARY_PATH="$libdir" ldd "$test_bin")
grep -q "libleptrino.so" <<<"$deps" || { echo "65-rust: the pkg-config build did not link libleptrino.so"; exit 1; }

echo "-- cargo package (both crates, each built from the packaged files)"
# cargo verifies leptrino against the packaged leptrino-sys through a local
# registry, and reuses what it built or unpacked before for the same version
# (registry crates are not fingerprinted by content): a stale leptrino-sys
# 0.1.0 of an earlier run. So: a target dir of its own, emptied, and no
# earlier unpacked copy in $CARGO_HOME.
export CARGO_TARGET_DIR="$root/build/rust-package"
rm -rf "$CARGO_TARGET_DIR" "${CARGO_HOME:-$HOME/.cargo}"/registry/src/-*/leptrino-sys-*
LEPTRINO_SYS_BUNDLED=1 cargo package --workspace --locked
for c in "$CARGO_TARGET_DIR"/package/leptrino-sys-*.crate; do
  listing=$(tar tzvf "$c")
  if grep -q '^l' <<<"$listing"; then echo "65-rust: $c holds a symlink"; exit 1; fi
  grep -q 'csrc/src/host/session/session.c$' <<<"$listing" || { echo "65-rust: $c lacks the C sources"; exit 1; }
done

echo "-- the README's Rust example is the crate README's (which runs as a doctest above)"
cd "$root"
python3 - <<'PY'
import re, sys
def block(path):
    m = re.search(r"```rust\n(.*?)```", open(path, encoding="utf-8").read(), re.S)
    return m.group(1) if m else None
a, b = block("README.md"), block("bindings/rust/leptrino/README.md")
if a is None or a != b:
    sys.exit("65-rust: README.md's rust block differs from bindings/rust/leptrino/README.md's")
PY
