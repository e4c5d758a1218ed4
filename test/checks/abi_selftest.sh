#!/usr/bin/env bash
# tools/abi_check.sh decides right, shown on a throwaway library built here in
# several versions from one source with switches: a baseline is dumped from
# the first, then each other version is compared with it and the verdict
# (exit status, and what the report names) checked:
#   identical, or changed only in its private state  -> pass, "identical"
#   a function added                                -> pass, names it, "baseline not updated"
#   a struct that starts with size grown at its end -> pass, "baseline not updated"
#   that struct grown elsewhere than at its end     -> FAIL, names it
#   a parameter added, a struct grown (same SONAME) -> FAIL, names both
#   a function removed (same SONAME)                -> FAIL, names it
#   the same incompatible change, SONAME moved      -> pass, "SONAME moved"
# Needs cc, readelf and abigail-tools (abidw, abidiff).
set -euo pipefail
if ! command -v abidw >/dev/null || ! command -v abidiff >/dev/null; then
  echo "abi selftest: skipped: abidw/abidiff not found (apt-get install abigail-tools)"
  exit 77 # ctest's SKIP_RETURN_CODE
fi
here=$(cd "$(dirname "$0")" && pwd)
check="$here/../../tools/abi_check.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cc=${CC:-cc}

# build NAME SONAME CFLAGS...: libabt.so of that version in $work/NAME, its
# public header in $work/NAME/include.
build() {
  local name=$1 soname=$2
  shift 2
  mkdir -p "$work/$name/include"
  cat >"$work/$name/include/abt.h" <<'EOF'
#include <stddef.h>
typedef struct abt_point {
    int x;
#ifdef GROW_POINT
    double z;
#endif
} abt_point;
typedef struct abt_options {
    size_t size;
#ifdef GROW_OPTIONS_MIDDLE
    double gain;
#endif
    int rate;
#ifdef GROW_OPTIONS
    double gain;
#endif
} abt_options;
typedef struct abt_handle abt_handle;
#ifdef MORE_PARAMS
int abt_scale(int v, double k);
#else
int abt_scale(int v);
#endif
void abt_move(abt_point *p);
int abt_open(const abt_options *o, abt_handle **out);
#ifndef NO_CLOSE
void abt_close(abt_handle *h);
#endif
#ifdef ADD_FUNCTION
int abt_version(void);
#endif
EOF
  cat >"$work/$name/abt.c" <<'EOF'
#include <stdlib.h>
#include "abt.h"
struct abt_handle { /* private: only the header's types count */
    int rate;
#ifdef GROW_PRIVATE
    long spare[8];
#endif
};
#ifdef MORE_PARAMS
int abt_scale(int v, double k) { return (int)(v * k); }
#else
int abt_scale(int v) { return 2 * v; }
#endif
void abt_move(abt_point *p) { p->x++; }
int abt_open(const abt_options *o, abt_handle **out) {
    *out = calloc(1, sizeof **out);
    if (*out == NULL) return -1;
    (*out)->rate = o->rate;
    return 0;
}
#ifndef NO_CLOSE
void abt_close(abt_handle *h) { free(h); }
#endif
#ifdef ADD_FUNCTION
int abt_version(void) { return 2; }
#endif
EOF
  "$cc" -std=c99 -g -Og -shared -fPIC "$@" -I"$work/$name/include" \
    -Wl,-soname,"$soname" -o "$work/$name/libabt.so" "$work/$name/abt.c"
}

fails=0
# expect NAME STATUS PATTERN...: compare version NAME with the baseline; the
# exit status must be STATUS and the output match every pattern (grep -E).
expect() {
  local name=$1 want=$2 got=0 pat
  shift 2
  "$check" compare "$work/base.abi" "$work/$name/libabt.so" "$work/$name/include" \
    >"$work/$name.out" 2>&1 || got=$?
  local ok=1
  [ "$got" -eq "$want" ] || ok=0
  for pat in "$@"; do
    grep -Eq -- "$pat" "$work/$name.out" || { ok=0; echo "  missing: $pat"; }
  done
  if [ "$ok" -eq 1 ]; then
    echo "ok   $name: exit $got"
  else
    echo "FAIL $name: exit $got, expected $want; output:"
    sed 's/^/    /' "$work/$name.out"
    fails=$((fails + 1))
  fi
}

build base libabt.so.0.1
"$check" dump "$work/base/libabt.so" "$work/base/include" "$work/base.abi"

build same libabt.so.0.1
build private libabt.so.0.1 -DGROW_PRIVATE
build added libabt.so.0.1 -DADD_FUNCTION
build grown_sized libabt.so.0.1 -DGROW_OPTIONS
build grown_sized_middle libabt.so.0.1 -DGROW_OPTIONS_MIDDLE
build broken libabt.so.0.1 -DMORE_PARAMS -DGROW_POINT
build removed libabt.so.0.1 -DNO_CLOSE
build broken_bumped libabt.so.0.2 -DMORE_PARAMS -DGROW_POINT

expect same 0 "ABI identical"
expect private 0 "ABI identical"
expect added 0 "abt_version" "baseline not updated: run tools/abi_baseline.sh"
expect grown_sized 0 "abt_options" "grew at their end" "baseline not updated"
expect grown_sized_middle 1 "FAIL: incompatible" "struct abt_options' changed"
expect broken 1 "FAIL: incompatible ABI change with the same SONAME libabt.so.0.1" \
  "abt_scale" "abt_move" "struct abt_point' changed" "bump the version in CMakeLists.txt" "tools/abi_baseline.sh"
expect removed 1 "FAIL: incompatible" "abt_close"
expect broken_bumped 0 "SONAME moved libabt.so.0.1 -> libabt.so.0.2" "baseline not updated"

if [ "$fails" -ne 0 ]; then
  echo "abi selftest: $fails case(s) wrong" >&2
  exit 1
fi
echo "abi selftest: the checker passes compatible changes and fails incompatible ones unless the SONAME moves"
