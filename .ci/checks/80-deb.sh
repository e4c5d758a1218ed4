#!/usr/bin/env bash
# The Debian package: build it with CPack (preset deb), list it, install it
# with dpkg, use it from the shell and from C (pkg-config, find_package, the
# README's example) with nothing but the installed files, remove it, and check
# that nothing of it is left behind. Runs as root; cleans up even on failure.
# No Python anywhere in this check.
set -euo pipefail
ci_apt cmake ninja-build gcc pkg-config dpkg-dev file help2man man-db binutils udev

root=$(pwd)
pkg=leptrino
version=$(sed -n 's/^project(leptrino VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
arch=$(dpkg --print-architecture)
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH)
work=$(mktemp -d)
installed=0
sim_pid=

cleanup() {
  local rc=$?
  if [ -n "$sim_pid" ]; then kill "$sim_pid" 2>/dev/null || true; wait "$sim_pid" 2>/dev/null || true; fi
  if [ "$installed" = 1 ]; then
    echo "deb: cleaning up: dpkg -r $pkg"
    dpkg -r "$pkg" >/dev/null 2>&1 || true
  fi
  rm -rf "$work"
  exit "$rc"
}
trap cleanup EXIT
fail() { echo "FAIL deb: $*"; exit 1; }
# Under pipefail, `cmd | grep -q` can fail when grep stops reading at the first
# match and cmd dies of SIGPIPE: the greps below read all their input instead.

# Never touch a leptrino someone installed: no such package, no such files.
[ "$(id -u)" = 0 ] || fail "needs root (dpkg -i / dpkg -r)"

# state PKG: dpkg's state of the package ("" or not-installed when unknown to it).
state() { dpkg-query -W -f='${db:Status-Status}' "$1" 2>/dev/null || true; }
case "$(state "$pkg")" in
  ""|not-installed) ;;
  *) fail "a $pkg package is on this machine already ($(state "$pkg")); not replacing it" ;;
esac

# 1. Build the package from a fresh configure.
t0=$(date +%s)
cmake --workflow --preset deb --fresh >"$work/build.log" 2>&1 || { cat "$work/build.log"; fail "cmake --workflow --preset deb"; }
deb=build/deb/${pkg}_${version}-1_${arch}.deb
[ -f "$deb" ] || fail "no $deb"
echo "deb: built $deb ($(stat -c %s "$deb") bytes) in $(( $(date +%s) - t0 )) s"

# 2. What it holds.
dpkg-deb -c "$deb" | tee "$work/contents.txt"
dpkg-deb --fsys-tarfile "$deb" | tar -t | sed 's|^\./|/|; s|/$||' | grep -v '^$' | sort >"$work/paths.txt"
need=(
  /usr/bin/leptrino /usr/bin/leptrino-sim
  /usr/include/leptrino/leptrino.h /usr/include/leptrino/serial.h /usr/include/leptrino/version.h
  "/usr/lib/$multiarch/libleptrino.so" "/usr/lib/$multiarch/libleptrino.a"
  "/usr/lib/$multiarch/pkgconfig/leptrino.pc"
  "/usr/lib/$multiarch/cmake/leptrino/leptrinoConfig.cmake"
  "/usr/lib/$multiarch/cmake/leptrino/leptrinoConfigVersion.cmake"
  /usr/share/man/man1/leptrino.1.gz /usr/share/man/man1/leptrino-sim.1.gz
  /usr/lib/udev/rules.d/60-leptrino.rules
  /usr/share/doc/leptrino/copyright
)
if [ -f tools/leptrino-soak/CMakeLists.txt ]; then
  need+=(/usr/bin/leptrino-soak)
fi
# Every program of the package has its man page.
programs=$(sed -n 's|^/usr/bin/\(.*\)|\1|p' "$work/paths.txt")
for prog in $programs; do
  need+=("/usr/share/man/man1/$prog.1.gz")
done
for p in "${need[@]}"; do
  grep -qxF "$p" "$work/paths.txt" || fail "the package lacks $p"
done
if grep -v -e '^/usr$' -e '^/usr/' "$work/paths.txt" | grep . >/dev/null; then fail "files outside /usr"; fi
if grep -q '^/usr/local' "$work/paths.txt"; then fail "files in /usr/local"; fi

dpkg-deb -I "$deb" >"$work/info.txt"
cat "$work/info.txt"
for script in preinst postinst prerm postrm config; do
  if dpkg-deb --ctrl-tarfile "$deb" | tar -t | grep -x "\./$script" >/dev/null; then fail "maintainer script $script"; fi
done
depends=$(dpkg-deb -f "$deb" Depends)
grep -q 'libc6' <<<"$depends" || fail "Depends has no libc6 (dpkg-shlibdeps?): '$depends'"
[ "$(dpkg-deb -f "$deb" Package)" = "$pkg" ] || fail "Package field"
[ "$(dpkg-deb -f "$deb" Version)" = "${version}-1" ] || fail "Version field"
grep -Eq '^[^<>]+ <[^<>@ ]+@[^<>@ ]+>$' <<<"$(dpkg-deb -f "$deb" Maintainer)" \
  || fail "Maintainer field is not 'Name <address>': '$(dpkg-deb -f "$deb" Maintainer)'"
dpkg-deb --fsys-tarfile "$deb" | tar -xO ./usr/share/doc/leptrino/copyright | grep '^License: MIT' >/dev/null \
  || fail "copyright file without License: MIT"
echo "deb: Depends: $depends"

# None of its files may already exist (dpkg would overwrite someone's file,
# and dpkg -r would then delete it).
while read -r p; do
  if [ -e "$p" ] && [ ! -d "$p" ]; then fail "$p exists already; not overwriting it"; fi
done <"$work/paths.txt"

# 3. Install, with a list of the file system before.
snapshot() {
  find /usr /etc /var/lib/dpkg/info -xdev -path /usr/local -prune -o -print 2>/dev/null | sort
}
snapshot >"$work/before.txt"
installed=1
# --path-include: a minimal image's dpkg may exclude /usr/share/man.
dpkg -i --path-include='/usr/share/man/man1/leptrino*' "$deb"
dpkg-query -W -f='${Status}\n' "$pkg" | grep -x 'install ok installed' >/dev/null || fail "not installed"
dpkg -V "$pkg" || fail "dpkg -V: installed files differ from the package"
lib=$(readlink -f "/usr/lib/$multiarch/libleptrino.so")
soname=$(readelf -d "$lib" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
[ -n "$soname" ] && [ -L "/usr/lib/$multiarch/$soname" ] || fail "no SONAME link '$soname'"
ldconfig -p | grep -F "$soname" >/dev/null || fail "$soname not in the ld.so cache (ldconfig trigger)"
echo "deb: installed; library $lib, SONAME $soname"

# The udev rule parses: udevadm test reads every rules file and names any
# line it rejects (file:line); no tty here is a sensor, so nothing matches.
rule=/usr/lib/udev/rules.d/60-leptrino.rules
tty=$(ls -d /sys/class/tty/* | head -n 1)
udevadm test --action=add "$tty" >"$work/udev.txt" 2>&1 || true
grep -qF "Reading rules file: $rule" "$work/udev.txt" || { cat "$work/udev.txt"; fail "udevadm did not read $rule"; }
if grep -F "$rule:" "$work/udev.txt"; then fail "udevadm rejects lines of $rule (above)"; fi
echo "deb: udevadm test reads $rule without complaint"

# 4. The shell: the programs, from their installed paths only.
cd "$work"
out=$(leptrino --version)
[ "$out" = "leptrino $version" ] || fail "leptrino --version says '$out'"
[ "$(command -v leptrino)" = /usr/bin/leptrino ] || fail "leptrino is not /usr/bin/leptrino"
leptrino stream --sim --duration 1 >"$work/stream.csv" 2>"$work/stream.err" \
  || { cat "$work/stream.err"; fail "leptrino stream --sim --duration 1"; }
rows=$(grep -cE '^[0-9]+(\.[0-9]+)?,' "$work/stream.csv" || true)
[ "$rows" -ge 100 ] || { head "$work/stream.csv"; cat "$work/stream.err"; fail "only $rows samples in 1 s"; }
echo "deb: leptrino stream --sim --duration 1: $rows samples"

leptrino-sim --link "$work/sensor" --exit-after 60 >"$work/sim.out" 2>&1 &
sim_pid=$!
for _ in $(seq 1 200); do [ -e "$work/sensor" ] && break; sleep 0.05; done
[ -e "$work/sensor" ] || fail "leptrino-sim made no link"
leptrino info "$work/sensor" >"$work/info.out" 2>&1 || { cat "$work/info.out"; fail "leptrino info on leptrino-sim"; }
grep -q 'PFS055YA501U6' "$work/info.out" || { cat "$work/info.out"; fail "leptrino info did not show the model"; }
echo "deb: leptrino info on the installed leptrino-sim: OK"

if [ -x /usr/bin/leptrino-soak ]; then
  leptrino-soak --help >/dev/null || fail "leptrino-soak --help"
fi

for prog in $programs; do
  page=$(man -w "$prog") || fail "man -w $prog"
  [ "$page" = "/usr/share/man/man1/$prog.1.gz" ] || fail "man -w $prog gives $page"
  MANPAGER=cat MANWIDTH=80 man "$prog" 2>/dev/null | grep "^NAME" >/dev/null || fail "man $prog does not render"
done
echo "deb: man pages of" $programs "found by man -w"

# 5. C, against the installed files only (no build tree, no rpath).
consumer=$root/test/package/consumer
# shellcheck disable=SC2046
cc -std=c99 -Wall -Wextra -Werror "$consumer/consumer.c" $(pkg-config --cflags --libs leptrino) -o consumer_pc
./consumer_pc "$version"
# shellcheck disable=SC2046
cc -std=c99 -Wall -Wextra -Werror -DLEPTRINO_STATIC "$consumer/consumer.c" $(pkg-config --cflags leptrino) \
  "$(pkg-config --variable=libdir leptrino)/libleptrino.a" $(pkg-config --static --libs-only-other leptrino) -o consumer_static
./consumer_static "$version"
cmake -S "$consumer" -B cmake-consumer -G Ninja >/dev/null
cmake --build cmake-consumer >/dev/null
./cmake-consumer/consumer "$version"
# (/lib is /usr/lib on a merged-/usr system.)
deps=$(ldd ./cmake-consumer/consumer)
grep -qE "libleptrino\.so[.0-9]* => (/usr)?/lib/$multiarch/libleptrino" <<<"$deps" \
  || { echo "$deps"; fail "the find_package consumer does not load the package's library"; }
# The README's C example, compiled as the README says, run against leptrino-sim.
# shellcheck disable=SC2046
bash "$root/test/package/readme_c_example.sh" "$root/README.md" cc /usr/bin/leptrino-sim $(pkg-config --cflags --libs leptrino)
cd "$root"

kill "$sim_pid" 2>/dev/null || true
wait "$sim_pid" 2>/dev/null || true
sim_pid=

# 6. Remove; nothing of it may be left.
dpkg -r "$pkg"
installed=0
case "$(state "$pkg")" in
  ""|not-installed) ;;
  *) fail "dpkg still has $pkg after dpkg -r: $(state "$pkg")" ;;
esac
snapshot >"$work/after.txt"
if ! diff -u "$work/before.txt" "$work/after.txt"; then fail "the file system differs after dpkg -r (above)"; fi
while read -r p; do
  if [ -e "$p" ] && [ ! -d "$p" ]; then fail "$p left behind"; fi
done <"$work/paths.txt"
if ldconfig -p | grep libleptrino >/dev/null; then fail "libleptrino still in the ld.so cache"; fi
echo "deb: removed; nothing left behind ($(wc -l <"$work/before.txt") paths compared)"
