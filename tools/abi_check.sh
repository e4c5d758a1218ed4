#!/usr/bin/env bash
# The ABI of a shared library compared with a committed baseline (libabigail),
# and the one place of the rule that decides. Used by tools/abi_baseline.sh
# (dump), .ci/checks/15-abi.sh (build + compare) and test/checks/abi_selftest.sh
# (dump + compare on a throwaway library).
#
#   tools/abi_check.sh build BUILD_DIR
#       configure + build libleptrino.so alone with debug info (RelWithDebInfo,
#       no tests) in BUILD_DIR; prints the path of the library
#   tools/abi_check.sh dump LIB HEADERS_DIR OUT.abi
#       write LIB's ABI as seen through the public headers in HEADERS_DIR
#   tools/abi_check.sh compare BASELINE.abi LIB HEADERS_DIR
#       compare LIB with the baseline and decide:
#         identical                              -> pass
#         compatible (functions or variables added, a struct whose first
#         member is `size` grown at its end)     -> pass, warning: baseline not updated
#         incompatible (anything removed or changed), same SONAME
#                                                -> FAIL (exit 1), naming what changed
#         incompatible, SONAME moved             -> pass, warning: baseline not updated
#       exit 2: the tools failed (no debug info, unreadable file, ...)
#
# Only types whose definition is in HEADERS_DIR count (abidw/abidiff
# --headers-dir + --drop-private-types): the private state behind an opaque
# handle may change freely. The baseline keeps short locations (file name and
# line, no directory): abidiff's header filter matches types by the file name
# of their location, and a baseline without locations would make every type
# of the baseline look private and hide its changes.
#
# abidiff's exit status is a bit set: 1 error, 2 usage error, 4 ABI change,
# 8 incompatible change. Bit 8 is only set for removed symbols; a changed
# parameter list or a grown struct sets 4 alone ("a human must review"), so
# the decision reads the change summary: removed or changed functions and
# variables are incompatible, added ones are not. Growth at the end of a
# struct starting with `size` is compatible by the API's contract (callers
# set size = sizeof what they were built with): a suppression generated from
# the baseline (every struct whose first member is named size) lets abidiff
# accept exactly that change and still report any other change to it.
set -euo pipefail

ABIDW_FLAGS=(--drop-private-types --no-corpus-path --no-comp-dir-path --short-locs
  --type-id-style hash --drop-undefined-syms)

die() { echo "abi-check: $*" >&2; exit 2; }

soname_of_lib() { # the DT_SONAME of an ELF file ("" when none)
  LC_ALL=C readelf -d "$1" | sed -n 's/.*(SONAME).*\[\(.*\)\].*/\1/p'
}

soname_of_abi() { # the soname attribute of an abidw file ("" when none)
  sed -n "s/^<abi-corpus [^>]*soname='\([^']*\)'.*/\1/p" "$1" | head -n 1
}

cmd_build() {
  local dir=$1 root
  root=$(cd "$(dirname "$0")/.." && pwd)
  cmake -S "$root" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DLEPTRINO_BUILD_TESTS=OFF -DLEPTRINO_BUILD_SHARED=ON -DLEPTRINO_MAN=OFF >/dev/null
  cmake --build "$dir" --target leptrino >/dev/null
  local lib="$dir/src/libleptrino.so"
  [ -f "$lib" ] || die "the build made no $lib"
  printf '%s\n' "$lib"
}

cmd_dump() {
  local lib=$1 headers=$2 out=$3
  [ -f "$lib" ] || die "no library $lib"
  [ -d "$headers" ] || die "no headers directory $headers"
  abidw --headers-dir "$headers" "${ABIDW_FLAGS[@]}" --out-file "$out" "$lib" \
    || die "abidw failed on $lib"
  [ -n "$(soname_of_abi "$out")" ] || die "$lib has no SONAME: the rule needs one"
}

# A libabigail suppression file: each struct of the baseline whose first
# member is named size may gain members at its end.
size_first_suppressions() {
  python3 - "$1" <<'EOF'
import sys
import xml.etree.ElementTree as ET

names = set()
for cls in ET.parse(sys.argv[1]).getroot().iter("class-decl"):
    first = cls.find("data-member")
    var = first.find("var-decl") if first is not None else None
    if cls.get("name") and var is not None and var.get("name") == "size":
        names.add(cls.get("name"))
for name in sorted(names):
    print(f"[suppress_type]\n  label = {name} starts with its size: it may grow at its end\n"
          f"  type_kind = struct\n  name = {name}\n  has_data_member_inserted_at = end\n"
          "  has_size_change = yes\n")
EOF
}

# count WHAT REPORT: the number before WHAT on abidiff's summary lines
# ("Functions changes summary: 0 Removed, 1 Changed (2 filtered out), 3 Added functions").
count() {
  local line=$1 what=$2
  printf '%s\n' "$line" | sed -n "s/.*[^0-9]\([0-9][0-9]*\) $what.*/\1/p" | head -n 1
}

cmd_compare() {
  local base=$1 lib=$2 headers=$3
  [ -f "$base" ] || die "no baseline $base (make one: tools/abi_baseline.sh)"
  [ -f "$lib" ] || die "no library $lib"
  [ -d "$headers" ] || die "no headers directory $headers"
  local old_so new_so tmp rc=0
  old_so=$(soname_of_abi "$base")
  new_so=$(soname_of_lib "$lib")
  [ -n "$old_so" ] || die "$base records no SONAME"
  [ -n "$new_so" ] || die "$lib has no SONAME"
  tmp=$(mktemp -d)
  # shellcheck disable=SC2064
  trap "rm -rf '$tmp'" EXIT
  size_first_suppressions "$base" >"$tmp/size-first.abignore"
  abidiff --headers-dir2 "$headers" --drop-private-types --fail-no-debug-info \
    --no-show-locs --suppressions "$tmp/size-first.abignore" \
    "$base" "$lib" >"$tmp/report" 2>&1 || rc=$?
  if [ $((rc & 3)) -ne 0 ]; then
    cat "$tmp/report" >&2
    die "abidiff failed (exit $rc) comparing $base with $lib"
  fi
  # Without the size-first suppression: what grew (to say the baseline is stale).
  local raw_rc=0
  if [ -s "$tmp/size-first.abignore" ]; then
    abidiff --headers-dir2 "$headers" --drop-private-types --no-show-locs \
      "$base" "$lib" >"$tmp/raw" 2>&1 || raw_rc=$?
  else
    raw_rc=$rc
    cp "$tmp/report" "$tmp/raw"
  fi

  local fn var fsym vsym
  fn=$(grep -m1 '^Functions changes summary:' "$tmp/report" || true)
  var=$(grep -m1 '^Variables changes summary:' "$tmp/report" || true)
  fsym=$(grep -m1 '^Function symbols changes summary:' "$tmp/report" || true)
  vsym=$(grep -m1 '^Variable symbols changes summary:' "$tmp/report" || true)
  local removed=0 changed=0 added=0 n
  for n in "$(count "$fn" Removed)" "$(count "$var" Removed)" \
    "$(count "$fsym" Removed)" "$(count "$vsym" Removed)"; do
    removed=$((removed + ${n:-0}))
  done
  for n in "$(count "$fn" Changed)" "$(count "$var" Changed)"; do
    changed=$((changed + ${n:-0}))
  done
  for n in "$(count "$fn" Added)" "$(count "$var" Added)" \
    "$(count "$fsym" Added)" "$(count "$vsym" Added)"; do
    added=$((added + ${n:-0}))
  done

  local incompatible=0
  if [ $((rc & 8)) -ne 0 ] || [ "$removed" -gt 0 ] || [ "$changed" -gt 0 ]; then
    incompatible=1
  fi
  # A change abidiff reports that the summary does not count (a changed
  # variable type, an ELF property): incompatible unless it is the SONAME.
  if [ $((rc & 4)) -ne 0 ] && [ "$incompatible" -eq 0 ] && [ "$added" -eq 0 ] \
    && [ "$old_so" = "$new_so" ]; then
    incompatible=1
  fi

  echo "abi-check: baseline $base (SONAME $old_so), library $lib (SONAME $new_so)"
  if [ "$rc" -eq 0 ] && [ "$raw_rc" -eq 0 ] && [ "$old_so" = "$new_so" ]; then
    echo "abi-check: ABI identical to the baseline"
    return 0
  fi
  sed 's/^/  | /' "$tmp/report"
  local stale="abi-check: WARNING: baseline not updated: run tools/abi_baseline.sh and commit $base with the change"
  if [ "$incompatible" -eq 1 ]; then
    if [ "$old_so" = "$new_so" ]; then
      {
        echo "abi-check: FAIL: incompatible ABI change with the same SONAME $new_so"
        echo "abi-check: removed: $removed, changed: $changed (functions, variables and symbols); what changed:"
        grep -E "^ *\[[CD]\] |type '[^']*' changed|was (added|removed)|changed from|member (insertion|deletion|change)|^ +'[^']*', at offset" \
          "$tmp/report" | sed 's/^/  /' || true
        echo "abi-check: to make the change on purpose: bump the version in CMakeLists.txt"
        echo "  project(leptrino VERSION ...) (and include/leptrino/version.h): the SONAME"
        echo "  libleptrino.so.<major>.<minor> moves with the minor while 0.x; then run"
        echo "  tools/abi_baseline.sh and commit abi/libleptrino.abi with the change."
        echo "  Or keep the ABI: add, do not change (a new function; a new member at the end"
        echo "  of a struct that starts with its size)."
      } >&2
      return 1
    fi
    echo "abi-check: incompatible changes (removed: $removed, changed: $changed) accepted: the SONAME moved $old_so -> $new_so"
    echo "$stale"
    return 0
  fi
  if [ "$added" -gt 0 ]; then
    echo "abi-check: compatible: $added added:"
    grep -E "^ *\[A\] " "$tmp/report" | sed 's/^ */    /' || true
  fi
  local raw_changed
  raw_changed=$(count "$(grep -m1 '^Functions changes summary:' "$tmp/raw" || true)" Changed)
  if [ "${raw_changed:-0}" -gt "$(count "$fn" Changed)" ]; then
    echo "abi-check: compatible: structs that start with their size grew at their end:"
    grep -E "^ *\[C\] |type '[^']*' changed|type size changed|data member insertion|^ +'[^']*', at offset" \
      "$tmp/raw" | sed 's/^/  /' || true
  fi
  if [ "$old_so" != "$new_so" ]; then
    echo "abi-check: the SONAME moved $old_so -> $new_so"
  fi
  echo "$stale"
  return 0
}

case "${1:-}" in
  build) [ $# -eq 2 ] || die "usage: $0 build BUILD_DIR"; cmd_build "$2" ;;
  dump) [ $# -eq 4 ] || die "usage: $0 dump LIB HEADERS_DIR OUT.abi"; cmd_dump "$2" "$3" "$4" ;;
  compare) [ $# -eq 4 ] || die "usage: $0 compare BASELINE.abi LIB HEADERS_DIR"
    cmd_compare "$2" "$3" "$4" ;;
  *) die "usage: $0 build BUILD_DIR | dump LIB HEADERS_DIR OUT.abi | compare BASELINE.abi LIB HEADERS_DIR" ;;
esac
