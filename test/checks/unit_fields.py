#!/usr/bin/env python3
"""The session's units own their state: who writes what, read from the code.

A folder (src/host/session) holds units and the lifecycle that composes them.
Each unit header's top comment names the struct it owns ("Owns:   NAME ...")
and the files that implement it ("Files:  a.c, b.c"; without one, the .c of
the header's name). The lifecycle header (session_priv.h, --lifecycle) names
its files the same way ("Files:" ... ) and defines the struct that composes
the units. The rules:

  1. Every .c of the folder belongs to exactly one unit or to the lifecycle.
  2. A unit's file never sees the composed struct: it does not include the
     lifecycle header, nor name `lep_session *` / `struct lep_session`.
  3. A unit's file includes of the folder's headers only its own unit's, and
     headers that own no struct (helpers: --helper); the units it is given
     come through its own header's includes.
  4. A unit's file reaches no field of another unit's struct: a pointer of
     another unit's type (a parameter or a local) is only passed on, never
     followed with `->` or `.`.
  5. A lifecycle file writes no unit's field: no `s->UNIT.field` assigned,
     incremented or taken the address of (a unit is passed whole, `&s->UNIT`,
     to its own functions).

Usage: unit_fields.py --dir DIR --lifecycle H [--helper H ...] [--expect-errors N]
Exit status: 0 all rules hold, 1 otherwise (--expect-errors N: 0 when exactly
N findings), 2 bad usage.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
from typing import Dict, List, Optional, Sequence, Set, Tuple

LABEL = re.compile(r"^\s*/?\*\s*([A-Z][a-z]+):\s*(.*)$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
COMPOSED = re.compile(r"\bstruct\s+lep_session\b(?!_)|\blep_session\s*\*")
# a declaration of a pointer to a struct type: `const T *name` (parameters, locals)
POINTER = re.compile(
    r"\b(?:const\s+)?([a-z_][a-z0-9_]*)\s*\*\s*(?:const\s+)?([A-Za-z_]\w*)\s*[,;)=\[]")
# after a field path: assigned or stepped; before it: stepped or its address taken
ASSIGNED = re.compile(r"[\w.\[\]]*\s*(=(?!=)|\+=|-=|\*=|/=|\|=|&=|\+\+|--)")
STEPPED_OR_TAKEN = re.compile(r"(\+\+|--|&)\s*\w+$")
MEMBER = re.compile(r"^\s*([a-z_][a-z0-9_]*)\s+(\w+)\s*;", re.M)


def strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def top_comment(text: str) -> List[str]:
    m = re.match(r"\s*/\*(.*?)\*/", text, re.S)
    return m.group(1).splitlines() if m else []


def labels(text: str) -> Dict[str, str]:
    """Label -> its text (continued on following lines until the next label)."""
    out: Dict[str, str] = {}
    current: Optional[str] = None
    for line in top_comment(text):
        m = LABEL.match(line)
        if m:
            current = m.group(1)
            out[current] = m.group(2)
        elif current is not None and line.strip(" *"):
            out[current] += " " + line.strip(" *")
        else:
            current = None
    return out


class Unit:
    def __init__(self, header: str, struct: str, files: List[str]) -> None:
        self.header = header
        self.struct = struct
        self.files = files


def read_units(d: str, lifecycle: str,
               helpers: Set[str]) -> Tuple[List[Unit], List[str], List[str]]:
    units: List[Unit] = []
    errors: List[str] = []
    life_files: List[str] = []
    for name in sorted(os.listdir(d)):
        if not name.endswith(".h") or name in helpers:
            continue
        with open(os.path.join(d, name), encoding="utf-8") as f:
            lab = labels(f.read())
        files = re.findall(r"\b(\w+\.c)\b", lab.get("Files", ""))
        if name == lifecycle:
            if not files:
                errors.append(f"{name}: the lifecycle header names no file (a 'Files:' line)")
            life_files = files
            continue
        owns = lab.get("Owns", "").split()
        if not owns:
            errors.append(f"{name}: a unit header without an 'Owns:' line (or pass it as --helper)")
            continue
        units.append(Unit(name, owns[0].rstrip(",;:."), files or [name[:-2] + ".c"]))
    for h in sorted(helpers):  # a helper's own .c is held to the units' rules 2 and 3
        if os.path.isfile(os.path.join(d, h[:-2] + ".c")):
            units.append(Unit(h, "", [h[:-2] + ".c"]))
    return units, life_files, errors


def check(d: str, lifecycle: str, helpers: Set[str]) -> List[str]:
    units, life_files, errors = read_units(d, lifecycle, helpers)
    owner: Dict[str, Unit] = {}
    for u in units:
        for cfile in u.files:
            if cfile in owner or cfile in life_files:
                errors.append(f"{cfile}: named by two units ({u.header} and another)")
            owner[cfile] = u
    structs = {u.struct: u for u in units if u.struct}
    with open(os.path.join(d, lifecycle), encoding="utf-8") as fh:
        composed = strip_comments(fh.read())
    m = re.search(r"struct\s+lep_session\s*\{(.*?)\n\};", composed, re.S)
    unit_members = {name: t for t, name in MEMBER.findall(m.group(1))} if m else {}
    unit_members = {n: t for n, t in unit_members.items() if t in structs}
    local_headers = {n for n in os.listdir(d) if n.endswith(".h")}

    for name in sorted(os.listdir(d)):
        if not name.endswith(".c"):
            continue
        path = os.path.join(d, name)
        with open(path, encoding="utf-8") as fh:
            raw = fh.read()
        code = strip_comments(raw)
        lines = code.splitlines()
        if name in life_files:
            for n, line in enumerate(lines, 1):
                for member in unit_members:
                    pat = rf"(?:->|\.)\s*{member}\s*\.\s*\w+"
                    for w in re.finditer(pat, line):
                        if ASSIGNED.match(line[w.end():]) or \
                                STEPPED_OR_TAKEN.search(line[:w.start()]):
                            header = structs[unit_members[member]].header
                            errors.append(f"{path}:{n}: the lifecycle writes a field of the "
                                          f"unit {member} ({header}): {line.strip()}")
            continue
        found = owner.get(name)
        if found is None:
            errors.append(f"{path}: belongs to no unit and not to the lifecycle "
                          f"(name it in a unit header's 'Files:' or in {lifecycle})")
            continue
        u = found
        for n, line in enumerate(lines, 1):
            if COMPOSED.search(line):
                errors.append(f"{path}:{n}: the unit {u.struct or u.header} sees the "
                              f"composed session: {line.strip()}")
        for inc in INCLUDE.findall(raw):
            if inc not in local_headers:
                continue
            if inc == lifecycle:
                errors.append(f"{path}: the unit {u.struct} includes {lifecycle}")
            elif inc != u.header and inc not in helpers:
                errors.append(f"{path}: the unit {u.struct} includes {inc} (only {u.header} "
                              f"and helpers; what it is given comes through {u.header})")
        foreign: Dict[str, str] = {}
        for t, var in POINTER.findall(code):
            if t in structs and t != u.struct:
                foreign[var] = t
        for n, line in enumerate(lines, 1):
            for var, t in foreign.items():
                if re.search(rf"\b{var}\s*->", line):
                    errors.append(f"{path}:{n}: the unit {u.struct} reaches into {t} "
                                  f"({structs[t].header}) through {var}: {line.strip()}")
    return errors


def main(argv: Sequence[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dir", required=True)
    ap.add_argument("--lifecycle", required=True, help="the header composing the units")
    ap.add_argument("--helper", action="append", default=[], help="a header owning no struct")
    ap.add_argument("--expect-errors", type=int, default=None)
    a = ap.parse_args(argv)
    if not os.path.isfile(os.path.join(a.dir, a.lifecycle)):
        ap.error(f"{a.lifecycle}: not in {a.dir}")
    errors = check(a.dir, a.lifecycle, set(a.helper))
    for e in errors:
        print(e)
    units, life, _ = read_units(a.dir, a.lifecycle, set(a.helper))
    print(f"unit_fields: {sum(1 for u in units if u.struct)} units, {len(life)} lifecycle files, "
          f"{len(errors)} finding(s)")
    if a.expect_errors is not None:
        return 0 if len(errors) == a.expect_errors else 1
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
