#!/usr/bin/env bash
# The manylinux wheel on another glibc distribution: the wheel built here (the
# build runs auditwheel repair) is pip-installed in a venv inside Debian 13
# (trixie: another glibc than this machine's), debootstrapped into a temporary
# folder and entered with chroot, and used there: dist_check.py's smoke test
# (both backends, the Simulator, a session, a recording saved as CSV) and the
# bundled programs. Cache-free; about 3 minutes (debootstrap and the wheel's
# build run side by side). Needs root (debootstrap, mount, chroot), Debian's
# archive (the mirror of this machine's apt sources) and PyPI.
set -euo pipefail
cd "$(dirname "$0")/../.."
ci_apt debootstrap python3 python3-venv python3-pip cmake ninja-build gcc util-linux

suite=${LEPTRINO_OTHER_SUITE:-trixie}
root_dir=$(pwd)
work=$(mktemp -d /tmp/leptrino-glibc-XXXXXX)
chroot_dir=$work/root
mounts=()
fail() { echo "FAIL wheel-other-glibc: $*"; exit 1; }

boot=
cleanup() {
  local rc=$?
  local i m
  if [ -n "$boot" ] && kill -0 "$boot" 2>/dev/null; then # our debootstrap, still running
    kill "$boot" 2>/dev/null || true
    wait "$boot" 2>/dev/null || true
  fi
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do umount "${mounts[$i]}" 2>/dev/null || true; done
  # what debootstrap mounted under the chroot (when it was stopped midway), deepest first
  for m in $(findmnt -rn -o TARGET | grep "^$work/" | sort -r); do umount "$m" 2>/dev/null || true; done
  if findmnt -rn -o TARGET | grep -q "^$work/"; then
    echo "wheel-other-glibc: $work still has mounts; left in place"
  else
    rm -rf --one-file-system "$work"
  fi
  exit "$rc"
}
trap cleanup EXIT
[ "$(id -u)" = 0 ] || fail "needs root (debootstrap, mount, chroot)"

# The Debian mirror this machine's apt uses.
mirror=$(sed -n 's/^URIs: *\([^ ]*\).*/\1/p' /etc/apt/sources.list.d/*.sources 2>/dev/null \
           | grep -v security | head -n 1 || true)
if [ -z "$mirror" ]; then
  mirror=$(sed -n 's/^deb \(\[[^]]*\] \)\?\([^ ]*\) .*/\2/p' /etc/apt/sources.list 2>/dev/null \
             | grep -v security | head -n 1 || true)
fi
[ -n "$mirror" ] || fail "no Debian mirror in this machine's apt sources"

t0=$(date +%s)
# 1. The other distribution and the wheel, side by side.
debootstrap --variant=minbase --include=python3,python3-venv,ca-certificates \
  "$suite" "$chroot_dir" "$mirror" >"$work/debootstrap.log" 2>&1 &
boot=$!
tools=build/venv-dist-tools
python3 -m venv "$tools"
"$tools/bin/python" -m pip install -q --upgrade pip build
if ! "$tools/bin/python" -m build -w -o "$work/dist" bindings/python >"$work/build.log" 2>&1; then
  tail -n 40 "$work/build.log"
  fail "python -m build -w"
fi
wheel=$(ls "$work"/dist/*.whl)
case "$(basename "$wheel")" in
  leptrino-*-py3-none-manylinux_*.whl) ;;
  *) fail "the wheel is not tagged manylinux: $(basename "$wheel")" ;;
esac
echo "wheel-other-glibc: built $(basename "$wheel") in $(($(date +%s) - t0)) s"
if ! wait "$boot"; then
  boot=
  tail -n 40 "$work/debootstrap.log"
  fail "debootstrap $suite"
fi
boot=
echo "wheel-other-glibc: debootstrap $suite done at $(($(date +%s) - t0)) s"

# 2. Enter it: its own /proc and pty instance (nothing of the host's /dev).
mount -t proc proc "$chroot_dir/proc" && mounts+=("$chroot_dir/proc")
mount -t devpts -o newinstance,ptmxmode=0666,mode=0620 devpts "$chroot_dir/dev/pts" \
  && mounts+=("$chroot_dir/dev/pts")
rm -f "$chroot_dir/dev/ptmx"
ln -s pts/ptmx "$chroot_dir/dev/ptmx"
cp /etc/resolv.conf "$chroot_dir/etc/resolv.conf"
# pip in there trusts what pip here trusts (PyPI may be reached through a proxy
# with a certificate authority of its own): the same pip.conf and CA files.
for f in /etc/pip.conf /etc/ssl/certs/ca-certificates.crt "${PIP_CERT:-}" "${SSL_CERT_FILE:-}"; do
  if [ -n "$f" ] && [ -f "$f" ]; then
    mkdir -p "$chroot_dir$(dirname "$f")"
    cp "$f" "$chroot_dir$f"
  fi
done
cp "$wheel" "$chroot_dir/tmp/"
python3 -c 'import sys; sys.path.insert(0, "test/python"); import dist_check; print(dist_check.SMOKE)' \
  >"$chroot_dir/tmp/smoke.py"
version=$(sed -n 's/^project(leptrino VERSION \([0-9.]*\).*/\1/p' "$root_dir/CMakeLists.txt")
host_glibc=$(python3 -c 'import platform; print(platform.libc_ver()[1])')

# 3. Install and use it there.
chroot "$chroot_dir" /usr/bin/env -i PATH=/usr/bin:/bin HOME=/tmp ${PIP_CERT:+PIP_CERT=$PIP_CERT} \
  ${SSL_CERT_FILE:+SSL_CERT_FILE=$SSL_CERT_FILE} /bin/sh -eu -c '
  cd /tmp
  glibc=$(python3 -c "import platform; print(platform.libc_ver()[1])")
  [ "$glibc" != "$1" ] || { echo "the chroot has the same glibc ($glibc) as the host"; exit 1; }
  echo "wheel-other-glibc: $(. /etc/os-release; echo "$PRETTY_NAME"), glibc $glibc (host: $1)"
  python3 -m venv v
  v/bin/python -m pip install -q "/tmp/$2"
  v/bin/python smoke.py "$3"
  v/bin/leptrino --version
  v/bin/leptrino stream --sim -c 5 | grep -vc "^#" | grep -qx 6
  v/bin/python -m leptrino info --sim >/dev/null
' sh "$host_glibc" "$(basename "$wheel")" "$version" || fail "install or use in $suite"
echo "wheel-other-glibc: $(basename "$wheel") installed and working in $suite, $(($(date +%s) - t0)) s in all"
