"""What the C compiler says of the public headers, against what both backends hold.

test_declarations.py compares names and types, as text. Here a small C
program, compiled against include/leptrino/*.h by the system's C compiler,
prints what only the compiler knows for certain: the size and alignment of
every public struct, the offset and size of every member (nested ones too),
and the value of every public constant (LEP_* macros and enumerators, as
listed by cheaders.py, the reader independent of the generator). Each backend
must agree:
  - ctypes: ctypes.sizeof/alignment of its Structure, each field's offset;
  - cffi: ffi.sizeof/alignof/offsetof of the cdef'd type; every enumerator
    of the cdef (lib.LEP_*) with the compiler's value;
  - both: leptrino._constants and leptrino.Error (every LEP_E_* code).
"""

from __future__ import annotations

import ctypes
import os
import shutil
import subprocess
from pathlib import Path
from typing import Any, Dict, Iterator, List, Tuple, Union

import pytest

import cheaders
from leptrino import _constants, _ctypes_decls as ct_decls

Layout = Dict[str, Tuple[int, int]]  # "type" or "type.member.sub" -> (offset or 0, size)


def _members(h: cheaders.Headers, s: cheaders.Struct,
             prefix: str) -> Iterator[Tuple[str, Union[str, cheaders.Struct]]]:
    """Every member path of a struct, and those of the structs and unions in it
    (nested definitions, or public struct types by name)."""
    for name, t in s.fields:
        yield f"{prefix}.{name}", t
        inner = h.structs.get(t) if isinstance(t, str) else t
        if inner is not None:
            yield from _members(h, inner, f"{prefix}.{name}")


def probe_source(h: cheaders.Headers, include_dir: Path) -> str:
    """A C11 program printing layouts and constant values, one per line."""
    lines = ["#include <stddef.h>", "#include <stdio.h>", "#include <stdint.h>"]
    lines += [f"#include <leptrino/{p.name}>" for p in sorted(include_dir.glob("*.h"))]
    lines += [
        "static void show_g(const char *n, double x) { printf(\"C %s g %.17g\\n\", n, x); }",
        "static void show_s(const char *n, const char *x) { printf(\"C %s s %s\\n\", n, x); }",
        "static void show_i(const char *n, long long x) { printf(\"C %s i %lld\\n\", n, x); }",
        "static void show_u(const char *n, unsigned long long x) "
        "{ printf(\"C %s i %llu\\n\", n, x); }",
        "#define SHOW(n, x) _Generic((x), float: show_g, double: show_g, char *: show_s, \\",
        "    const char *: show_s, unsigned int: show_u, unsigned long: show_u, \\",
        "    unsigned long long: show_u, default: show_i)(n, x)",
        "int main(void) {",
    ]
    for name, s in h.structs.items():
        lines.append(f'    printf("S {name} %zu %zu\\n", sizeof({name}), _Alignof({name}));')
        for path, _t in _members(h, s, name):
            member = path.split(".", 1)[1]
            lines.append(f'    printf("M {path} %zu %zu\\n", offsetof({name}, {member}), '
                         f'sizeof((({name} *)0)->{member}));')
    for name in h.constant_names:
        lines.append(f'    SHOW("{name}", {name});')
    lines += ["    return 0;", "}"]
    return "\n".join(lines) + "\n"


def compiler_view(root: Path, tmp: Path) -> Tuple[Layout, Layout, Dict[str, Any]]:
    """(struct size/alignment, member offset/size, constant values) as compiled."""
    cc = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")
    assert cc, "a C compiler (cc) is needed to compare layouts"
    h = cheaders.parse(root / "include" / "leptrino")
    src, exe = tmp / "probe.c", tmp / "probe"
    src.write_text(probe_source(h, root / "include" / "leptrino"), encoding="utf-8")
    subprocess.run([cc, "-std=c11", "-Wall", "-Werror", "-I", str(root / "include"),
                    str(src), "-o", str(exe)], check=True, capture_output=True, text=True)
    out = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout
    structs: Layout = {}
    members: Layout = {}
    consts: Dict[str, Any] = {}
    for line in out.splitlines():
        kind, name, *rest = line.split(" ", 3 if line.startswith("C ") else 4)
        if kind == "S":
            structs[name] = (int(rest[0]), int(rest[1]))
        elif kind == "M":
            members[name] = (int(rest[0]), int(rest[1]))
        else:
            typ, value = rest[0], rest[1] if len(rest) > 1 else ""
            consts[name] = int(value) if typ == "i" else float(value) if typ == "g" else value
    assert len(structs) == len(h.structs) and len(consts) == len(h.constant_names)
    return structs, members, consts


@pytest.fixture(scope="module")
def compiled(tmp_path_factory: pytest.TempPathFactory) -> Tuple[Layout, Layout, Dict[str, Any]]:
    from conftest import ROOT

    if ROOT is None:
        pytest.skip("not run from a leptrino checkout (set LEPTRINO_SOURCE_DIR)")
    assert ROOT is not None
    view = compiler_view(ROOT, tmp_path_factory.mktemp("layout"))
    assert {"lep_client_stats", "lep_frame_stats", "lep_response"} <= set(view[0])
    assert "lep_response.u.sample.raw" in view[1] and "LEP_E_STALLED" in view[2]
    # the host API's sizes and indices are enumerators now: the compiler says them too
    assert {"LEP_EVF_COUNT", "LEP_H_COUNT", "LEP_MD_COUNT", "LEP_SIMST_COUNT"} <= set(view[2])
    return view


# ---- each backend's view ----------------------------------------------------

def ctypes_layout(members: Layout) -> Tuple[Layout, Layout]:
    structs: Layout = {}
    got: Layout = {}
    for name, struct in ct_decls.STRUCTS.items():
        if name in ct_decls.OPAQUE:
            continue
        structs[name] = (ctypes.sizeof(struct), ctypes.alignment(struct))
    for path in members:
        name, *chain = path.split(".")
        cls: Any = ct_decls.STRUCTS.get(name)
        offset = 0
        for field in chain:
            if cls is None or not hasattr(cls, "_fields_"):
                cls = None
                break
            desc = getattr(cls, field, None)
            ftype = dict(cls._fields_).get(field)
            if desc is None or ftype is None:
                cls = None
                break
            offset += desc.offset
            cls = ftype
        if cls is not None:
            got[path] = (offset, ctypes.sizeof(cls))
    return structs, got


def cffi_layout(members: Layout) -> Tuple[Layout, Layout]:
    import cffi

    import leptrino

    ffi = leptrino.get_backend("cffi").ffi
    structs: Layout = {}
    got: Layout = {}
    for name in {p.split(".")[0] for p in members} | set(ct_decls.STRUCTS):
        try:
            structs[name] = (ffi.sizeof(name), ffi.alignof(name))
        except (cffi.FFIError, ValueError, KeyError, TypeError):
            pass  # opaque, or not declared: reported by the comparison
    for path in members:
        name, *chain = path.split(".")
        try:
            t = ffi.typeof(name)
            for field in chain:
                t = dict(t.fields)[field].type
            got[path] = (ffi.offsetof(name, *chain), ffi.sizeof(t))
        except (cffi.FFIError, ValueError, KeyError, TypeError):
            pass
    return structs, got


def compare(what: str, want: Layout, got: Layout) -> List[str]:
    errors = [f"{what} {k}: C (offset or size, size or alignment) {v}, Python {got.get(k)}"
              for k, v in want.items() if got.get(k) != v]
    errors += [f"{what} {k}: in Python, not in the compiled headers" for k in got
               if k not in want]
    return errors


def test_struct_layouts_match_the_compiler(backend: str,
                                          compiled: Tuple[Layout, Layout, Dict[str, Any]]
                                          ) -> None:
    structs, members, _ = compiled
    got_s, got_m = ctypes_layout(members) if backend == "ctypes" else cffi_layout(members)
    errors = compare("struct", structs, got_s) + compare("member", members, got_m)
    assert errors == []


def test_layout_check_catches_drift(compiled: Tuple[Layout, Layout, Dict[str, Any]]) -> None:
    structs, members, _ = compiled
    got_s, got_m = ctypes_layout(members)
    got_s["lep_sample"] = (got_s["lep_sample"][0] + 2, got_s["lep_sample"][1])
    got_m["lep_client_stats.stalls"] = (0, 4)
    del got_m["lep_response.u.sample.raw"]
    text = "\n".join(compare("struct", structs, got_s) + compare("member", members, got_m))
    for name in ("lep_sample", "lep_client_stats.stalls", "lep_response.u.sample.raw"):
        assert name in text, text


# ---- constants and error codes ------------------------------------------------

def check_constants(want: Dict[str, Any], mine: Dict[str, Any]) -> List[str]:
    errors = [f"{k}: {v!r} compiled, {mine.get(k, 'missing')!r} in Python"
              for k, v in want.items() if mine.get(k) != v or type(mine.get(k)) is not type(v)]
    errors += [f"{k}: in Python, not in the headers" for k in mine if k not in want]
    return errors


def test_constants_match_the_compiler(compiled: Tuple[Layout, Layout, Dict[str, Any]]) -> None:
    mine = {k: v for k, v in vars(_constants).items() if k.startswith("LEP_")}
    assert check_constants(compiled[2], mine) == []


def test_constant_check_catches_drift(compiled: Tuple[Layout, Layout, Dict[str, Any]]) -> None:
    mine = {k: v for k, v in vars(_constants).items() if k.startswith("LEP_")}
    mine["LEP_E_STALLED"] = -1
    del mine["LEP_SF_GAP"]
    text = "\n".join(check_constants(compiled[2], mine))
    assert "LEP_E_STALLED" in text and "LEP_SF_GAP" in text, text


def test_every_error_code_is_an_error_member(backend: str,
                                             compiled: Tuple[Layout, Layout, Dict[str, Any]]
                                             ) -> None:
    """leptrino.Error is exactly the compiled LEP_E_* codes (and LEP_OK), and
    the exception raised for each code on this backend carries it."""
    import leptrino

    codes = {k: v for k, v in compiled[2].items() if k.startswith("LEP_E_") or k == "LEP_OK"}
    assert len(codes) >= 24
    assert {e.name: int(e.value) for e in leptrino.Error} == \
        {k[len("LEP_E_"):] if k.startswith("LEP_E_") else "OK": v for k, v in codes.items()}
    be = leptrino.get_backend(backend)
    for name, value in codes.items():
        if value < 0:  # the exception the bindings raise for it carries that code
            exc = leptrino.errors.error_for(be, value)
            assert exc.code is leptrino.Error(value) and str(exc), name
    if backend == "cffi":  # the cdef's enumerators, as cffi evaluates them
        for name, value in compiled[2].items():
            if hasattr(be.lib, name) and isinstance(value, int):
                assert getattr(be.lib, name) == value, name
