"""The hand-written declarations of both backends against the C headers.

Parses include/leptrino/*.h (see cheaders.py) and compares every prototype,
struct layout and constant the bindings declare. Any drift fails here.
"""

from __future__ import annotations

import ctypes
from pathlib import Path
from typing import Any, Dict, List, Tuple, Union

import pytest

import cheaders
from leptrino import _constants, _ctypes_backend as ct


@pytest.fixture(scope="module")
def headers() -> cheaders.Headers:
    from conftest import ROOT

    if ROOT is None:
        pytest.skip("not run from a leptrino checkout (set LEPTRINO_SOURCE_DIR)")
    h = cheaders.parse(ROOT / "include" / "leptrino")
    # the reader must actually see the headers, or the check is vacuous
    assert len(h.functions) >= 60 and "lep_record_fill" in h.functions
    assert {"lep_sample", "lep_sim_options", "lep_response"} <= set(h.structs)
    return h


# ---- ctypes --------------------------------------------------------------

_BASE: Dict[str, Any] = {
    "void": None,
    "int": ctypes.c_int,
    "unsigned int": ctypes.c_uint,
    "_Bool": ctypes.c_bool,
    "char": ctypes.c_char,
    "float": ctypes.c_float,
    "double": ctypes.c_double,
    "size_t": ctypes.c_size_t,
    "int8_t": ctypes.c_int8,
    "uint8_t": ctypes.c_uint8,
    "int16_t": ctypes.c_int16,
    "uint16_t": ctypes.c_uint16,
    "int32_t": ctypes.c_int32,
    "uint32_t": ctypes.c_uint32,
    "int64_t": ctypes.c_int64,
    "uint64_t": ctypes.c_uint64,
}


def ctypes_accepts(ctype_str: str) -> List[Any]:
    """The ctypes types that exactly represent a normalised C type."""
    if ctype_str.endswith(" *"):
        inner = ctype_str[:-2]
        if inner == "void":
            return [ctypes.c_void_p]
        out = [ctypes.POINTER(t) for t in ctypes_accepts(inner)]
        if inner == "char":
            out.append(ctypes.c_char_p)
        return out
    if ctype_str in _BASE:
        return [_BASE[ctype_str]]
    if ctype_str in ct.STRUCTS:
        return [ct.STRUCTS[ctype_str]]
    return []


def _same_ctypes(a: Any, b: Any) -> bool:
    if a is b:
        return True
    # arrays: compare element type and length
    if isinstance(a, type) and isinstance(b, type) and issubclass(a, ctypes.Array) \
            and issubclass(b, ctypes.Array):
        return a._length_ == b._length_ and _same_ctypes(a._type_, b._type_)
    return False


def _ctypes_field_ok(c_type: Union[str, cheaders.Struct], py_type: Any, where: str,
                     errors: List[str]) -> None:
    if isinstance(c_type, cheaders.Struct):
        base = ctypes.Union if c_type.kind == "union" else ctypes.Structure
        if not (isinstance(py_type, type) and issubclass(py_type, base)):
            errors.append(f"{where}: header has a nested {c_type.kind}, ctypes has {py_type}")
            return
        compare_ctypes_struct(c_type, py_type, where, errors)
        return
    if c_type.endswith("]"):
        elem, n = c_type[:-1].split("[")
        acc = [t * int(n) for t in ctypes_accepts(elem)]
    else:
        acc = ctypes_accepts(c_type)
    if not any(_same_ctypes(py_type, a) for a in acc):
        errors.append(f"{where}: header {c_type!r}, ctypes {py_type!r}")


def compare_ctypes_struct(s: cheaders.Struct, cls: Any, where: str, errors: List[str]) -> None:
    fields = list(getattr(cls, "_fields_", []))
    names = [f[0] for f in fields]
    want = [f[0] for f in s.fields]
    if names != want:
        errors.append(f"{where}: fields {want} in the header, {names} in ctypes")
        return
    for (fname, ftype), (_, ptype) in zip(s.fields, fields):
        _ctypes_field_ok(ftype, ptype, f"{where}.{fname}", errors)


def compare_ctypes_function(h: cheaders.Headers, name: str, restype: Any,
                            argtypes: List[Any]) -> List[str]:
    errors: List[str] = []
    if name not in h.functions:
        return [f"{name}: not a LEP_API function of the headers"]
    ret, params = h.functions[name]
    if not any(_same_ctypes(restype, a) for a in ctypes_accepts(ret)):
        errors.append(f"{name}: returns {ret!r} in the header, ctypes restype {restype!r}")
    if len(params) != len(argtypes):
        errors.append(f"{name}: {len(params)} parameters in the header, {len(argtypes)} in ctypes")
        return errors
    for i, (p, a) in enumerate(zip(params, argtypes)):
        if not any(_same_ctypes(a, x) for x in ctypes_accepts(p)):
            errors.append(f"{name}: parameter {i} is {p!r} in the header, ctypes {a!r}")
    return errors


def check_ctypes(h: cheaders.Headers, functions: Dict[str, Tuple[Any, List[Any]]],
                 structs: Dict[str, Any]) -> List[str]:
    errors: List[str] = []
    for name, (restype, argtypes) in functions.items():
        errors += compare_ctypes_function(h, name, restype, argtypes)
    for name, cls in structs.items():
        if name in ct.OPAQUE:
            if name not in h.structs and name not in h.opaque:
                errors.append(f"{name}: no such type in the headers")
            continue
        if name not in h.structs:
            errors.append(f"{name}: no such struct in the headers")
            continue
        compare_ctypes_struct(h.structs[name], cls, name, errors)
    return errors


def test_ctypes_declarations_match_headers(headers: cheaders.Headers) -> None:
    assert check_ctypes(headers, ct.FUNCTIONS, ct.STRUCTS) == []


def test_ctypes_library_uses_the_declarations() -> None:
    """The loaded functions carry exactly the checked argtypes/restype."""
    import leptrino

    lib = leptrino.get_backend("ctypes").lib
    for name, (restype, argtypes) in ct.FUNCTIONS.items():
        fn = getattr(lib, name)
        assert fn.restype is restype and list(fn.argtypes) == argtypes, name


def test_ctypes_check_catches_drift(headers: cheaders.Headers) -> None:
    funcs = dict(ct.FUNCTIONS)
    funcs["lep_bcc"] = (ctypes.c_uint8, [ctypes.POINTER(ctypes.c_uint8), ctypes.c_uint32])
    funcs["lep_sim_stall"] = (None, [ctypes.POINTER(ct.lep_sim)])
    funcs["lep_no_such_function"] = (ctypes.c_int, [])

    class lep_rated(ctypes.Structure):  # wrong element type
        _fields_ = [("axis", ctypes.c_double * 6)]

    class lep_sample(ctypes.Structure):  # fields out of order
        _fields_ = [("raw", ctypes.c_int16 * 6), ("status", ctypes.c_uint8),
                    ("reserved", ctypes.c_uint16)]

    structs = dict(ct.STRUCTS, lep_rated=lep_rated, lep_sample=lep_sample)
    errors = check_ctypes(headers, funcs, structs)
    text = "\n".join(errors)
    for name in ("lep_bcc", "lep_sim_stall", "lep_no_such_function", "lep_rated.axis",
                 "lep_sample"):
        assert name in text, text


# ---- cffi ----------------------------------------------------------------

def _cffi_type_ok(c_type: Union[str, cheaders.Struct], ctype: Any, where: str,
                  errors: List[str]) -> None:
    if isinstance(c_type, cheaders.Struct):
        if ctype.kind != c_type.kind:
            errors.append(f"{where}: header has a nested {c_type.kind}, cffi {ctype.cname}")
            return
        compare_cffi_struct(c_type, ctype, where, errors)
        return
    got = ctype.cname.replace("struct ", "").replace("union ", "")
    if got != c_type:
        errors.append(f"{where}: header {c_type!r}, cffi {ctype.cname!r}")


def compare_cffi_struct(s: cheaders.Struct, ctype: Any, where: str, errors: List[str]) -> None:
    fields = ctype.fields or []
    names = [f[0] for f in fields]
    want = [f[0] for f in s.fields]
    if names != want:
        errors.append(f"{where}: fields {want} in the header, {names} in cffi")
        return
    for (fname, ftype), (_, cf) in zip(s.fields, fields):
        _cffi_type_ok(ftype, cf.type, f"{where}.{fname}", errors)


def check_cffi(h: cheaders.Headers, cdef: str) -> List[str]:
    import cffi

    ffi = cffi.FFI()
    ffi.cdef(cdef)
    errors: List[str] = []
    decl = ffi._parser._declarations  # what the cdef declares: "kind name" -> (type, q)
    for key, (tp, _q) in decl.items():
        kind, _, name = key.partition(" ")
        if kind != "function":
            continue
        if name not in h.functions:
            errors.append(f"{name}: not a LEP_API function of the headers")
            continue
        ret, params = h.functions[name]
        ftype = ffi.typeof(tp.get_c_name("(*)", "")).item  # the function type
        if ftype.result.cname != ret:
            errors.append(f"{name}: returns {ret!r} in the header, cffi {ftype.result.cname!r}")
        got = [a.cname for a in ftype.args]
        if got != params:
            errors.append(f"{name}: parameters {params} in the header, cffi {got}")
    for key in decl:
        kind, _, name = key.partition(" ")
        if kind != "typedef":
            continue
        ctype = ffi.typeof(name)
        if ctype.kind != "struct":
            continue
        if ctype.fields is None:  # opaque
            if name not in h.structs and name not in h.opaque:
                errors.append(f"{name}: no such type in the headers")
            continue
        if name not in h.structs:
            errors.append(f"{name}: no such struct in the headers")
            continue
        compare_cffi_struct(h.structs[name], ctype, name, errors)
    return errors


def test_cffi_declarations_match_headers(headers: cheaders.Headers) -> None:
    pytest.importorskip("cffi")
    from leptrino._cdef import CDEF

    assert check_cffi(headers, CDEF) == []


def test_cffi_library_uses_the_declarations(headers: cheaders.Headers) -> None:
    """Every function of the loaded cffi library has the header's signature."""
    pytest.importorskip("cffi")
    import leptrino

    be = leptrino.get_backend("cffi")
    names = be.function_names()
    assert set(names) >= set(ct.FUNCTIONS)  # both backends declare the same set
    for name in names:
        ft = be.ffi.typeof(getattr(be.lib, name))
        ret, params = headers.functions[name]
        assert (ft.result.cname, [a.cname for a in ft.args]) == (ret, params), name


def test_cffi_check_catches_drift(headers: cheaders.Headers) -> None:
    pytest.importorskip("cffi")
    from leptrino._cdef import CDEF

    bad = (CDEF.replace("uint8_t lep_bcc(const uint8_t *msg, size_t len);",
                        "uint8_t lep_bcc(const uint8_t *msg, uint32_t len);")
           .replace("void lep_sim_stall(lep_sim *s, int ms);", "void lep_sim_stall(lep_sim *s);")
           .replace("float axis[6];", "double axis[6];")
           .replace("uint16_t reserved;\n    uint8_t status;",
                    "uint8_t status;\n    uint16_t reserved;"))
    assert bad.count("lep_") == CDEF.count("lep_")
    text = "\n".join(check_cffi(headers, bad))
    for name in ("lep_bcc", "lep_sim_stall", "lep_rated.axis", "lep_sample"):
        assert name in text, text


def test_both_backends_declare_the_same_functions() -> None:
    pytest.importorskip("cffi")
    import cffi

    from leptrino._cdef import CDEF

    ffi = cffi.FFI()
    ffi.cdef(CDEF)
    cffi_funcs = {k.partition(" ")[2] for k in ffi._parser._declarations
                  if k.startswith("function ")}
    assert cffi_funcs == set(ct.FUNCTIONS)


# ---- constants and sizes ---------------------------------------------------

def test_constants_match_headers(headers: cheaders.Headers) -> None:
    mine = {k: v for k, v in vars(_constants).items() if k.startswith("LEP_")}
    assert len(mine) > 50
    wrong = {k: (v, headers.constants.get(k)) for k, v in mine.items()
             if headers.constants.get(k) != v}
    assert wrong == {}


def test_client_size_covers_the_header_layout(backend: str) -> None:
    """lep_client is allocated as lep_client_sizeof() bytes: sane and 8-aligned use."""
    import leptrino

    be = leptrino.get_backend(backend)
    size = int(be.lib.lep_client_sizeof())
    assert 200 <= size <= 4096


def test_session_and_output_are_fully_declared(headers: cheaders.Headers) -> None:
    """Every function and structure of session.h and output.h (what Sensor and
    Recording.save use) is declared by both backends, and so checked above."""
    import re

    from conftest import ROOT

    assert ROOT is not None
    for header in ("session.h", "output.h", "payload.h"):
        text = (ROOT / "include" / "leptrino" / header).read_text(encoding="utf-8")
        funcs = set(re.findall(r"\bLEP_API\b[^;(]*?\b(lep_\w+)\s*\(", text))
        structs = set(re.findall(r"\btypedef\s+struct\s+\w+\s*\{.*?\}\s*(\w+)\s*;", text, re.S))
        assert funcs and funcs <= set(ct.FUNCTIONS), (header, funcs - set(ct.FUNCTIONS))
        assert structs <= set(ct.STRUCTS), (header, structs - set(ct.STRUCTS))
        try:
            from leptrino._cdef import CDEF
        except ImportError:  # pragma: no cover
            continue
        for name in funcs:
            assert re.search(rf"\b{name}\s*\(", CDEF), name
        for name in structs:
            assert re.search(rf"\}}\s*{name}\s*;", CDEF), name
