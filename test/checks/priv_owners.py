#!/usr/bin/env python3
"""The private headers' map of who owns what is true: each prototype is
defined by the file whose section it sits in.

A private header (each of the session's unit headers and session_priv.h in
src/host/session, sim_priv.h) is divided into sections by comments that begin
with a file's name at the start of a line ("/* session_guard.c: ..." or
"/* ---- session_chain_load.c ---- */"). Each function
prototype at the start of a line (not static, not a typedef) belongs to the
section above it; the object file compiled from that section's file must
define it (`nm -P`). Prototypes before any section are reported too.

Usage: priv_owners.py [--nm NM] [--expect-errors N] --header H [--header H...] OBJ...
Exit status: 0 every prototype in its owner's section, 1 otherwise,
2 bad usage or nm failing (--expect-errors N: 0 when exactly N are misplaced).
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from typing import Dict, List, Sequence, Set, Tuple

SECTION = re.compile(r"^/\*[\s-]*([A-Za-z0-9_]+\.c)\b")
PROTOTYPE = re.compile(r"^(?!static\b|typedef\b|extern\b|#)[A-Za-z_][\w \t*]*?\b(\w+)\s*\(")


def prototypes(header: str) -> List[Tuple[str, str, int]]:
    """(function, section file or "", line number) of each prototype."""
    out: List[Tuple[str, str, int]] = []
    section = ""
    with open(header, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            m = SECTION.match(line)
            if m:
                section = m.group(1)
                continue
            m = PROTOTYPE.match(line)
            if m:
                out.append((m.group(1), section, n))
    return out


def defined_by(nm: str, objs: Sequence[str]) -> Dict[str, Set[str]]:
    """Source file name (x.c, from x.c.o, x.c.obj or x.o) -> global symbols it defines."""
    out: Dict[str, Set[str]] = {}
    for obj in objs:
        try:
            text = subprocess.run([nm, "-P", obj], check=True, capture_output=True,
                                  text=True).stdout
        except (OSError, subprocess.CalledProcessError) as exc:
            print(f"priv_owners: {nm} -P {obj}: {exc}", file=sys.stderr)
            raise SystemExit(2) from exc
        base = os.path.basename(obj)
        if base.endswith(".obj"):  # CMake's object suffix for Windows targets
            base = base[:-2]
        name = base[:-2] if base.endswith(".c.o") else base[:-2] + ".c"
        syms = out.setdefault(name, set())
        for line in text.splitlines():
            parts = line.split()
            if len(parts) >= 2 and parts[1] in "TDBRSVWG":
                syms.add(parts[0])
    return out


def check(headers: Sequence[str], defs: Dict[str, Set[str]]) -> List[str]:
    errors: List[str] = []
    for h in headers:
        protos = prototypes(h)
        if not protos:
            errors.append(f"{h}: no prototype found (is this a private header?)")
        for fn, section, line in protos:
            if section and fn in defs.get(section, set()):
                continue
            owners = sorted(f for f, s in defs.items() if fn in s)
            where = f"in the {section} section" if section else "before any section"
            errors.append(f"{h}:{line}: {fn} is declared {where} but defined in "
                          f"{', '.join(owners) or 'no object given'}")
    return errors


def main(argv: Sequence[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nm", default="nm")
    ap.add_argument("--header", action="append", required=True)
    ap.add_argument("--expect-errors", type=int, default=None)
    ap.add_argument("objs", nargs="+")
    a = ap.parse_args(argv)
    # CMake's $<TARGET_OBJECTS:...> arrives as one ;-separated argument
    objs = [o for arg in a.objs for o in arg.split(";") if o]
    errors = check(a.header, defined_by(a.nm, objs))
    for e in errors:
        print(e)
    count = sum(len(prototypes(h)) for h in a.header)
    print(f"priv_owners: {count} prototypes in {len(a.header)} headers, {len(errors)} misplaced")
    if a.expect_errors is not None:
        return 0 if len(errors) == a.expect_errors else 1
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
