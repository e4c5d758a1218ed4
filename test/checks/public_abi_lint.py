#!/usr/bin/env python3
"""The public headers hold only what any language's FFI can call.

ctypes, cffi, koffi (Node), LabVIEW's Call Library Function Node, P/Invoke,
Rust's bindgen... all handle opaque handles, integers, doubles, flat arrays
and NUL-terminated strings; each trips on something else. This lint reads
every public header (include/leptrino/*.h) the way tools/gen_python_decls.py
does (`cc -E` with its stand-in libc headers, then pycparser; its parse() and
build_model() are imported, not copied) and scans their raw text for macros,
then names each finding by header, line and symbol:

  bool        _Bool/bool in an exported function's signature, a callback
              type's signature or any public struct's member (its size and
              its calling convention are not the same across FFIs)
  unsigned    plain `unsigned`/`unsigned int` in a signature (koffi has no
              such type name): use a fixed-width type, int or size_t
  by-value    a struct or union passed or returned by value (LabVIEW cannot)
  variadic    a `...` prototype
  nested      a struct or union member of a public struct (nested records)
  pointer     a pointer member of a public struct (a lifetime the FFI cannot see)
  char-array  a char array of more than 64 bytes in a struct (LabVIEW-hostile:
              a cluster of that many bytes); take a buffer and its size instead
  unsized     a public struct that is not flat (scalars and fixed arrays of
              scalars only) and does not start with a member named `size`
  macro       an object-like macro with a value: FFIs never see macros; make it
              an enumerator or a function (include guards and MACRO_ALLOW
              excepted)
  context     a caller-allocated context (CONTEXTS) without its
              `size_t lep_<name>_sizeof(void)`

The caller-allocated contexts (CONTEXTS) nest other structs and hold
pointers by design (C and firmware allocate them statically); an FFI treats
them as lep_<name>_sizeof() bytes and never looks inside, so only `bool` is
checked in them.

Usage:
  public_abi_lint.py [--include DIR]     exit 1 on any finding (DIR holds leptrino/*.h)
  public_abi_lint.py --include DIR --expect-rules bool,macro,...
                                         exit 0 iff exactly these rules fire
                                         (the self-test of the lint)
Exit 2: the headers could not be read (preprocessor or parser error); 77:
pycparser is missing (ctest counts the test as skipped).
The allow-lists' stale entries are warned about on the tree's own headers only.
"""

from __future__ import annotations

import argparse
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, Iterator, List, Optional, Sequence, Set, Tuple

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))

try:
    from pycparser import c_ast

    import gen_python_decls as gdecl
except ImportError as exc:  # pycparser comes with cffi; Debian: python3-pycparser
    print(f"public_abi_lint: skipped: {exc}: install pycparser (pip install pycparser, or "
          "apt-get install python3-pycparser)", file=sys.stderr)
    sys.exit(77)  # ctest's SKIP_RETURN_CODE

#: Caller-allocated contexts of the portable core -> why they may nest.
#: Each must have `size_t lep_<name without lep_>_sizeof(void)`.
CONTEXTS: Dict[str, str] = {
    "lep_client": "the core's client: C and firmware allocate it statically; "
                  "it holds its decoder and receive state by value",
    "lep_frame_decoder": "the push decoder: allocated statically, holds its counters by value",
    "lep_device": "the sensor side: allocated statically, holds its decoder by value",
}

#: The portable core's C value structs (frame.h, message.h, client.h): they
#: pass through the core's C API on a microcontroller and hold a pointer, a
#: union or a nested value by design. No host task needs them from another
#: language (the session, sim, output and payload headers are flat; see
#: docs/ffi.md); only `bool` is checked in them, as in CONTEXTS.
CORE_VALUES: Dict[str, str] = {
    "lep_io": "the C I/O table (write/read/clock callbacks) firmware gives the client; "
              "FFI callers use a session, which owns its port",
    "lep_frame_event": "the sans-I/O frame decoder's result, pointing into the decoder's "
                       "buffer, for C and firmware",
    "lep_response": "the message codec's decoded message (a union by command), for C and "
                    "firmware",
}

#: Object-like macros with a value that stay, (header, name) -> why.
MACRO_ALLOW: Dict[Tuple[str, str], str] = {
    ("export.h", "LEP_API"): "the visibility/dllexport attribute of every prototype, not a value",
    ("config.h", "LEP_HAVE_DEVICE"): "firmware build switch for #if, from LEP_CONFIG_NO_DEVICE",
    ("config.h", "LEP_HAVE_ERROR_STRINGS"): "firmware build switch for #if, from "
                                            "LEP_CONFIG_NO_ERROR_STRINGS",
    ("version.h", "LEP_VERSION_MAJOR"): "compile-time version for #if; FFIs call lep_version()",
    ("version.h", "LEP_VERSION_MINOR"): "compile-time version for #if; FFIs call lep_version()",
    ("version.h", "LEP_VERSION_PATCH"): "compile-time version for #if; FFIs call lep_version()",
    ("version.h", "LEP_VERSION_STRING"): "compile-time version; FFIs call lep_version()",
    ("version.h", "LEP_VERSION_NUMBER"): "compile-time version for #if; FFIs call lep_version()",
}

#: Include guards: defined, usually without a value; never a constant.
GUARD = re.compile(r"LEPTRINO_\w+_H")

#: The longest char array a struct may hold (LabVIEW clusters of bytes).
CHAR_ARRAY_MAX = 64

RULES = ("bool", "unsigned", "by-value", "variadic", "nested", "pointer", "char-array",
         "unsized", "macro", "context")


@dataclass(frozen=True)
class Finding:
    header: str
    line: int
    rule: str
    symbol: str
    message: str


class Lint:
    def __init__(self, include: Path) -> None:
        self.include = include.resolve()
        self.own_tree = self.include == (ROOT / "include").resolve()
        self.findings: List[Finding] = []
        self.warnings: List[str] = []
        self.parsed = gdecl.parse(self.include)
        self.model = gdecl.build_model(self.parsed)
        self.ev = gdecl.Evaluator()
        self.ev.env.update({n: v for n, v, _ in self.parsed.constants})

    # -- helpers -------------------------------------------------------------

    def add(self, coord: object, rule: str, symbol: str, message: str) -> None:
        header = gdecl._header_of(coord) or str(getattr(coord, "file", "?"))
        self.findings.append(Finding(header, int(getattr(coord, "line", 0) or 0), rule,
                                     symbol, message))

    def resolve(self, names: Sequence[str]) -> Tuple[str, ...]:
        """The base type names of a typedef chain (uint8_t stays uint8_t)."""
        seen = 0
        key = tuple(names)
        while len(key) == 1 and key[0] in self.model.scalars and seen < 32:
            key = tuple(self.model.scalars[key[0]])
            seen += 1
        return key

    def leaves(self, t: c_ast.Node) -> Iterator[c_ast.Node]:
        """Every base type a declarator reaches, through pointers, arrays
        and function types (their return and parameters)."""
        if isinstance(t, (c_ast.PtrDecl, c_ast.ArrayDecl)):
            yield from self.leaves(t.type)
        elif isinstance(t, c_ast.TypeDecl):
            yield t.type
        elif isinstance(t, c_ast.FuncDecl):
            yield from self.leaves(t.type)
            for a in (t.args.params if t.args else []):
                if isinstance(a, c_ast.EllipsisParam):
                    continue
                yield from self.leaves(a.type)
        elif isinstance(t, c_ast.Typename):
            yield from self.leaves(t.type)

    def has_bool(self, t: c_ast.Node) -> bool:
        for leaf in self.leaves(t):
            if isinstance(leaf, c_ast.IdentifierType):
                names = self.resolve(leaf.names)
                if "_Bool" in names or names == ("bool",):
                    return True
                if len(leaf.names) == 1 and leaf.names[0] in self.model.funcptrs \
                        and self.has_bool(self.model.funcptrs[leaf.names[0]]):
                    return True
        return False

    def has_plain_unsigned(self, t: c_ast.Node) -> bool:
        for leaf in self.leaves(t):
            if isinstance(leaf, c_ast.IdentifierType) and \
                    self.resolve(leaf.names) in (("unsigned",), ("unsigned", "int")):
                return True
        return False

    def record_by_value(self, t: c_ast.Node) -> Optional[str]:
        """The struct/union a parameter or return type is by value, else None."""
        if not isinstance(t, c_ast.TypeDecl):
            return None
        base = t.type
        if isinstance(base, (c_ast.Struct, c_ast.Union)):
            return f"{'union' if isinstance(base, c_ast.Union) else 'struct'} {base.name or '?'}"
        if isinstance(base, c_ast.IdentifierType) and len(base.names) == 1 \
                and base.names[0] in self.model.structs:
            return base.names[0]
        return None

    def is_char(self, t: c_ast.Node) -> bool:
        return isinstance(t, c_ast.TypeDecl) and isinstance(t.type, c_ast.IdentifierType) \
            and self.resolve(t.type.names) in (("char",), ("signed", "char"), ("unsigned", "char"))

    def member_kind(self, t: c_ast.Node) -> str:
        """scalar, nested or pointer: what a struct member is, arrays looked through."""
        while isinstance(t, c_ast.ArrayDecl):
            t = t.type
        if isinstance(t, c_ast.PtrDecl):
            return "pointer"
        if isinstance(t, c_ast.TypeDecl):
            base = t.type
            if isinstance(base, (c_ast.Struct, c_ast.Union)):
                return "nested"
            if isinstance(base, c_ast.IdentifierType) and len(base.names) == 1:
                name = base.names[0]
                if name in self.model.structs:
                    return "nested"
                if name in self.model.funcptrs:
                    return "pointer"
        return "scalar"

    # -- the rules -----------------------------------------------------------

    def check_signature(self, coord: object, symbol: str, f: c_ast.FuncDecl, what: str) -> None:
        if self.has_bool(f.type):
            self.add(coord, "bool", symbol, f"{what} returns bool: return int (0/1) or an error code")
        if self.has_plain_unsigned(f.type):
            self.add(coord, "unsigned", symbol, f"{what} returns plain unsigned: use uint32_t, "
                     "int or size_t")
        rec = self.record_by_value(f.type)
        if rec:
            self.add(coord, "by-value", symbol, f"{what} returns {rec} by value: fill a "
                     "caller's struct through a pointer")
        for i, a in enumerate(f.args.params if f.args else []):
            if isinstance(a, c_ast.EllipsisParam):
                self.add(coord, "variadic", symbol, f"{what} is variadic (...)")
                continue
            if isinstance(a.type, c_ast.TypeDecl) and isinstance(a.type.type, c_ast.IdentifierType) \
                    and a.type.type.names == ["void"] and not a.name:
                continue
            pname = a.name or f"#{i + 1}"
            pcoord = a.coord or coord
            if self.has_bool(a.type):
                self.add(pcoord, "bool", symbol, f"{what}: parameter {pname} is or points to "
                         "bool: use int (0/1) or uint8_t")
            if self.has_plain_unsigned(a.type):
                self.add(pcoord, "unsigned", symbol, f"{what}: parameter {pname} is or points to "
                         "plain unsigned: use uint32_t, int or size_t")
            rec = self.record_by_value(a.type)
            if rec:
                self.add(pcoord, "by-value", symbol, f"{what}: parameter {pname} is {rec} by "
                         "value: pass a pointer")

    def check_functions(self) -> None:
        for node in self.parsed.decls:
            if isinstance(node, c_ast.Decl) and isinstance(node.type, c_ast.FuncDecl) \
                    and node.name in self.model.functions:
                self.check_signature(node.coord, node.name, node.type, node.name + "()")
            elif isinstance(node, c_ast.Typedef) and node.name in self.model.funcptrs:
                self.check_signature(node.coord, node.name, self.model.funcptrs[node.name],
                                     f"callback type {node.name}")

    def check_structs(self) -> None:
        for name, su in self.model.structs.items():
            kind = self.model.struct_kind[name]
            ctx = name in CONTEXTS or name in CORE_VALUES
            not_flat: List[str] = []
            if kind == "union" and not ctx:
                not_flat.append("(a union)")
            for d in su.decls or []:
                member = f"{name}.{d.name}"
                if self.has_bool(d.type):
                    self.add(d.coord, "bool", member, f"member {d.name} of {name} is bool: "
                             "use uint8_t (0/1)")
                if ctx:
                    continue
                mk = self.member_kind(d.type)
                if mk == "nested":
                    not_flat.append(d.name)
                    self.add(d.coord, "nested", member, f"member {d.name} of {name} is a "
                             "struct/union: flatten it (its members, prefixed) or make it a "
                             "struct of its own filled by a function")
                elif mk == "pointer":
                    not_flat.append(d.name)
                    self.add(d.coord, "pointer", member, f"member {d.name} of {name} is a "
                             "pointer: pass it as a function argument (a string, a buffer and "
                             "its size, a handle)")
                if isinstance(d.type, c_ast.ArrayDecl) and self.is_char(d.type.type) \
                        and d.type.dim is not None:
                    n = self.ev(d.type.dim)
                    if isinstance(n, int) and n > CHAR_ARRAY_MAX:
                        self.add(d.coord, "char-array", member, f"member {d.name} of {name} is "
                                 f"char[{n}] (more than {CHAR_ARRAY_MAX}): LabVIEW-hostile; "
                                 "get the text with a function filling a caller's buffer")
            if not_flat and not ctx:
                first = su.decls[0].name if su.decls else None
                if first != "size":
                    self.add(su.coord, "unsized", name, f"{kind} {name} is not flat "
                             f"({', '.join(not_flat)}) and does not start with a `size` member")

    def check_contexts(self) -> None:
        protos = {n.name: n for n in self.parsed.decls
                  if isinstance(n, c_ast.Decl) and isinstance(n.type, c_ast.FuncDecl)}
        for name in CONTEXTS:
            if name not in self.model.structs:
                if self.own_tree:
                        self.warnings.append(f"CONTEXTS names {name}, which the headers do not "
                                         "define with members: remove the entry if it became "
                                         "opaque")
                continue
            su = self.model.structs[name]
            fn = f"lep_{name[len('lep_'):]}_sizeof" if name.startswith("lep_") else f"{name}_sizeof"
            f = self.model.functions.get(fn)
            good = False
            if f is not None:
                ret = f.type
                args = f.args.params if f.args else []
                void = len(args) == 1 and isinstance(args[0], c_ast.Typename) \
                    and isinstance(args[0].type, c_ast.TypeDecl) \
                    and isinstance(args[0].type.type, c_ast.IdentifierType) \
                    and args[0].type.type.names == ["void"]
                good = isinstance(ret, c_ast.TypeDecl) and isinstance(ret.type, c_ast.IdentifierType) \
                    and ret.type.names == ["size_t"] and void
            if not good:
                where = protos[fn].coord if fn in protos else su.coord
                self.add(where, "context", name, f"caller-allocated context {name} needs "
                         f"`LEP_API size_t {fn}(void);`"
                         + (" (the one declared has another signature)" if fn in protos else ""))

    def check_macros(self) -> None:
        used: Set[Tuple[str, str]] = set()
        for path in sorted((self.include / "leptrino").glob("*.h")):
            text = path.read_text(encoding="utf-8")
            # comments out (keeping the line count), continuations joined
            text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n") + " ",
                          text, flags=re.S)
            text = re.sub(r"//[^\n]*", "", text)
            lines = text.split("\n")
            i = 0
            while i < len(lines):
                start = i
                line = lines[i]
                while line.endswith("\\") and i + 1 < len(lines):
                    i += 1
                    line = line[:-1] + " " + lines[i]
                i += 1
                m = re.match(r"\s*#\s*define\s+(\w+)(\()?(.*)$", line)
                if not m or m.group(2):
                    continue  # not a define, or function-like
                name, value = m.group(1), m.group(3).strip()
                if not value or GUARD.fullmatch(name):
                    continue
                if (path.name, name) in MACRO_ALLOW:
                    used.add((path.name, name))
                    continue
                self.findings.append(Finding(path.name, start + 1, "macro", name,
                                             f"object-like macro {name} = {value}: FFIs do "
                                             "not see macros; make it an enumerator or a "
                                             "function"))
        if self.own_tree:
            for key in sorted(set(MACRO_ALLOW) - used):
                self.warnings.append(f"MACRO_ALLOW names {key[1]} in {key[0]}, which is not "
                                     "defined there any more: remove the entry")

    def run(self) -> List[Finding]:
        self.check_functions()
        self.check_structs()
        self.check_contexts()
        self.check_macros()
        self.findings = sorted(set(self.findings), key=lambda f: (f.header, f.line, f.rule,
                                                                   f.symbol))
        return self.findings


def main(argv: Optional[Sequence[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--include", type=Path, default=ROOT / "include",
                    help="directory holding leptrino/*.h (default: the tree's include/)")
    ap.add_argument("--expect-rules", metavar="R1,R2,...",
                    help="exit 0 iff exactly these rules fire (self-test)")
    args = ap.parse_args(argv)
    try:
        lint = Lint(args.include)
        findings = lint.run()
    except gdecl.GenError as exc:
        print(f"public_abi_lint: cannot read the headers: {exc}", file=sys.stderr)
        return 2
    shown = args.include.resolve() / "leptrino"
    try:
        shown = shown.relative_to(ROOT)
    except ValueError:
        pass
    for f in findings:
        print(f"{shown}/{f.header}:{f.line}: [{f.rule}] {f.symbol}: {f.message}")
    for w in lint.warnings:
        print(f"public_abi_lint: warning: {w}")
    counts: Dict[str, int] = {}
    for f in findings:
        counts[f.rule] = counts.get(f.rule, 0) + 1
    summary = ", ".join(f"{r} {counts[r]}" for r in RULES if r in counts)
    print(f"public_abi_lint: {len(lint.parsed.headers)} headers, "
          f"{len(lint.model.functions)} functions, {len(lint.model.structs)} structs: "
          + (f"{len(findings)} findings ({summary})" if findings else "FFI-clean"))
    if args.expect_rules is not None:
        want = {r for r in args.expect_rules.split(",") if r}
        unknown = want - set(RULES)
        if unknown:
            print(f"public_abi_lint: unknown rules {sorted(unknown)}", file=sys.stderr)
            return 2
        got = set(counts)
        if got != want:
            print(f"public_abi_lint: expected rules {sorted(want)}, got {sorted(got)} "
                  f"(missing {sorted(want - got)}, unexpected {sorted(got - want)})",
                  file=sys.stderr)
            return 1
        print(f"public_abi_lint: each expected rule fired: {', '.join(sorted(want))}")
        return 0
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
