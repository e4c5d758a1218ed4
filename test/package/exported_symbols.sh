#!/usr/bin/env bash
# Only lep_ symbols may be exported, and the SONAME must carry the ABI version
# that src/CMakeLists.txt gives the library (its SOVERSION).
# usage: exported_symbols.sh LIB NM READELF SOVERSION
set -u
lib=$1 nm=$2 readelf=$3 soversion=$4
fail=0
syms=$("$nm" -D --defined-only "$lib" | awk '{print $3}')
count=$(wc -w <<<"$syms")
bad=$(grep -v '^lep_' <<<"$syms" || true)
if [ -n "$bad" ]; then
  echo "FAIL exported symbols without the lep_ prefix:"; echo "$bad"; fail=1
fi
if [ "$count" -lt 40 ]; then
  echo "FAIL only $count exported symbols: is the public API missing?"; fail=1
fi
soname=$("$readelf" -d "$lib" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
if [ -z "$soversion" ] || [ "$soname" != "libleptrino.so.$soversion" ]; then
  echo "FAIL SONAME is '$soname', want libleptrino.so.$soversion (SOVERSION '$soversion')"; fail=1
fi
[ $fail -eq 0 ] && echo "exported symbols: $count, all lep_; SONAME $soname"
exit $fail
