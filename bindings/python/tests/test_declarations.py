"""The generated declarations of both backends against the C headers.

tools/gen_python_decls.py writes leptrino/_constants.py, _cdef.py,
_ctypes_decls.py and _stats.py from include/leptrino/*.h. Here:
  - the committed files are what the generator makes of today's headers;
  - an independent reader of the headers (cheaders.py: regular expressions,
    not the generator's preprocessor and pycparser) agrees with them both
    ways: every LEP_API function, struct, member, function pointer type,
    constant, error code and counter of the headers is in Python, with the
    same type and value, and Python declares nothing the headers do not;
  - the loaded library exports exactly the declared functions.
"""

from __future__ import annotations

import ctypes
import dataclasses
import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any, Dict, List, Tuple, Union

import pytest

import cheaders
from leptrino import _constants, _ctypes_backend as ct, _ctypes_decls as ct_decls, _stats


@pytest.fixture(scope="module")
def headers() -> cheaders.Headers:
    from conftest import ROOT

    if ROOT is None:
        pytest.skip("not run from a leptrino checkout (set LEPTRINO_SOURCE_DIR)")
    h = cheaders.parse(ROOT / "include" / "leptrino")
    # the reader must actually see the headers, or the check is vacuous
    assert len(h.functions) >= 60 and "lep_record_fill" in h.functions
    assert {"lep_sample", "lep_client_stats", "lep_response"} <= set(h.structs)
    # the host API mirrors no layout: options, batches, events, health and
    # metadata are handles and flat arrays
    assert not {"lep_session_options", "lep_sim_options", "lep_session_batch",
                "lep_session_event", "lep_session_health", "lep_session_metadata",
                "lep_sim_stats"} & set(h.structs)
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


_SPELL: Dict[Any, str] = {}
for _name, _t in _BASE.items():  # the first name wins: c_int32 is c_int, spelled "int"
    if _t is not None:
        _SPELL.setdefault(_t, _name)


def canonical_spelling(spelling: str) -> str:
    """A function pointer's spelling with every scalar named as ctypes_spelling
    names it (ctypes cannot tell uint32_t from unsigned int)."""
    def one(part: str) -> str:
        part = part.strip()
        base, stars = part.rstrip(" *"), part.count("*")
        t = _BASE.get(base)
        return (_SPELL[t] if t is not None else base) + " *" * stars

    m = re.fullmatch(r"(.*?)\(\*\)\((.*)\)", spelling)
    assert m, spelling
    args = [one(a) for a in m.group(2).split(",")] if m.group(2) else []
    return f"{one(m.group(1))}(*)({', '.join(args)})"


def ctypes_spelling(t: Any) -> str:
    """A ctypes type in cheaders' (cffi's) spelling, for function pointers."""
    if t is None:
        return "void"
    if t is ctypes.c_void_p:
        return "void *"
    if t is ctypes.c_char_p:
        return "char *"
    if isinstance(t, type) and issubclass(t, ctypes._Pointer):  # type: ignore[attr-defined]
        return ctypes_spelling(t._type_) + " *"
    if isinstance(t, type) and issubclass(t, ctypes._CFuncPtr):  # type: ignore[attr-defined]
        args = ", ".join(ctypes_spelling(a) for a in t._argtypes_)
        return f"{ctypes_spelling(t._restype_)}(*)({args})"
    if t in _SPELL:
        return _SPELL[t]
    return str(getattr(t, "__name__", t))


def ctypes_accepts(ctype_str: str) -> List[Any]:
    """The ctypes types that exactly represent a normalised C type."""
    if "(*)(" in ctype_str:  # a function pointer: compared by spelling
        return [ctype_str]
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
    if isinstance(b, str):  # a function pointer's spelling
        return ctypes_spelling(a) == canonical_spelling(b)
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
    # the other way: nothing of the headers is missing
    errors += [f"{n}: a function of the headers that ctypes does not declare"
               for n in h.functions if n not in functions]
    errors += [f"{n}: a type of the headers that ctypes does not declare"
               for n in list(h.structs) + h.opaque if n not in structs]
    for n, spelling in h.funcptrs.items():
        if not hasattr(ct_decls, n) or \
                ctypes_spelling(getattr(ct_decls, n)) != canonical_spelling(spelling):
            errors.append(f"{n}: function pointer type {spelling!r} in the headers, ctypes "
                          f"{ctypes_spelling(getattr(ct_decls, n, None))!r}")
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
    funcs["lep_sim_stall"] = (None, [ctypes.POINTER(ct_decls.lep_sim)])
    funcs["lep_no_such_function"] = (ctypes.c_int, [])
    del funcs["lep_exit_code"]  # the other way: a header function left out

    class lep_rated(ctypes.Structure):  # wrong element type
        _fields_ = [("axis", ctypes.c_double * 6)]

    class lep_sample(ctypes.Structure):  # fields out of order
        _fields_ = [("raw", ctypes.c_int16 * 6), ("status", ctypes.c_uint8),
                    ("reserved", ctypes.c_uint16)]

    structs = dict(ct.STRUCTS, lep_rated=lep_rated, lep_sample=lep_sample)
    errors = check_ctypes(headers, funcs, structs)
    text = "\n".join(errors)
    for name in ("lep_bcc", "lep_sim_stall", "lep_no_such_function", "lep_rated.axis",
                 "lep_sample", "lep_exit_code"):
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
    # the other way: nothing of the headers is missing
    errors += [f"{n}: a function of the headers that the cdef does not declare"
               for n in h.functions if f"function {n}" not in decl]
    errors += [f"{n}: a type of the headers that the cdef does not declare"
               for n in list(h.structs) + h.opaque + list(h.funcptrs)
               if f"typedef {n}" not in decl]
    for n, spelling in h.funcptrs.items():
        if f"typedef {n}" in decl and ffi.typeof(n).cname != spelling:
            errors.append(f"{n}: function pointer type {spelling!r} in the headers, cffi "
                          f"{ffi.typeof(n).cname!r}")
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
           .replace("uint16_t reserved;\n  uint8_t status;",
                    "uint8_t status;\n  uint16_t reserved;")
           .replace("int lep_exit_code(int err);", ""))  # the other way: left out
    assert bad.count("lep_") == CDEF.count("lep_") - 1
    text = "\n".join(check_cffi(headers, bad))
    for name in ("lep_bcc", "lep_sim_stall", "lep_rated.axis", "lep_sample", "lep_exit_code"):
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


# ---- constants, errors, counters ------------------------------------------

def _python_constants() -> Dict[str, Any]:
    return {k: v for k, v in vars(_constants).items() if k.startswith("LEP_")}


def check_constants(h: cheaders.Headers, mine: Dict[str, Any]) -> List[str]:
    """Both ways: the same names; the same value wherever the reader evaluates one."""
    errors = [f"{k}: in the headers, not in _constants" for k in h.constant_names
              if k not in mine]
    errors += [f"{k}: in _constants, not in the headers" for k in mine
               if k not in h.constant_names]
    errors += [f"{k}: {v!r} in the headers, {mine.get(k)!r} in _constants"
               for k, v in h.constants.items() if k in mine and mine[k] != v
               or type(mine.get(k)) is not type(v)]
    return errors


def test_constants_match_headers(headers: cheaders.Headers) -> None:
    mine = _python_constants()
    assert len(mine) > 100 and len(headers.constants) > 100
    assert check_constants(headers, mine) == []


def test_constant_check_catches_drift(headers: cheaders.Headers) -> None:
    mine = _python_constants()
    mine["LEP_E_TIMEOUT"] = -99
    del mine["LEP_SF_GAP"]
    mine["LEP_NO_SUCH"] = 1
    text = "\n".join(check_constants(headers, mine))
    for name in ("LEP_E_TIMEOUT", "LEP_SF_GAP", "LEP_NO_SUCH"):
        assert name in text, text


def test_error_enum_is_every_error_code(headers: cheaders.Headers) -> None:
    """leptrino.Error holds every enumerator of enum lep_error, named without
    LEP_E_ (LEP_OK as OK), with its value; and nothing else."""
    import leptrino

    want = {n[len("LEP_E_"):] if n.startswith("LEP_E_") else n[len("LEP_"):]:
            headers.constants[n] for n in headers.enums["lep_error"]}
    assert len(want) >= 24 and "STALLED" in want
    assert {e.name: int(e.value) for e in leptrino.Error} == want
    assert leptrino.Error is leptrino.errors.Error is _constants.Error
    assert leptrino.Error.TIMEOUT == _constants.LEP_E_TIMEOUT


def _counter_structs(h: cheaders.Headers) -> List[str]:
    return [n for n in h.structs if n.endswith("_stats") or n.endswith("_health")]


#: enums that index a flat array of counters, and the library's name function
_COUNTER_ENUMS = {"lep_health_field": "lep_session_health_field_name",
                  "lep_sim_stat": "lep_sim_stats_field_name"}


def _dataclasses_by_c_name() -> Dict[str, Any]:
    by_doc = {}
    for cls in vars(_stats).values():
        if dataclasses.is_dataclass(cls):
            m = re.search(r"C: (lep_\w+) \(", cls.__doc__ or "")
            assert m, cls
            by_doc[m.group(1)] = cls
    return by_doc


def _flat_names(cls: Any) -> List[str]:
    """A dataclass's fields as flat names (a nested counter dataclass: its own)."""
    out: List[str] = []
    for f in dataclasses.fields(cls):
        sub = getattr(_stats, str(f.type), None)
        out += _flat_names(sub) if dataclasses.is_dataclass(sub) else [f.name]
    return out


def test_every_counter_struct_has_its_dataclass(headers: cheaders.Headers) -> None:
    """Each *_stats / *_health struct of the headers is a dataclass of
    leptrino with exactly its members, in order; each enum of a flat counter
    array (health, the virtual sensor's counters) is one with a field per
    enumerator (its name without the prefix, lower case; a nested counter
    struct as its own dataclass)."""
    import leptrino

    structs = _counter_structs(headers)
    assert {"lep_client_stats", "lep_frame_stats"} <= set(structs)
    by_doc = _dataclasses_by_c_name()
    assert set(by_doc) == set(structs) | set(_COUNTER_ENUMS)
    for name in structs:
        cls = by_doc[name]
        assert getattr(leptrino, cls.__name__) is cls  # exported
        want = [f[0] for f in headers.structs[name].fields]
        assert [f.name for f in dataclasses.fields(cls)] == want, name
    for name in _COUNTER_ENUMS:
        cls = by_doc[name]
        assert getattr(leptrino, cls.__name__) is cls
        items = [e for e in headers.enums[name] if not e.endswith("_COUNT")]
        prefix = items[0][:items[0].index("_", 4) + 1]  # LEP_H_, LEP_SIMST_
        assert _flat_names(cls) == [e[len(prefix):].lower() for e in items], name
    assert [f.name for f in dataclasses.fields(leptrino.ClientStats)][-5:] == [
        "resent_after_timeout", "resent_confirmed", "recoveries", "reserved_nonzero", "stalls"]
    assert [f.name for f in dataclasses.fields(leptrino.Health)][-1] == "client"


def test_counter_names_are_the_librarys(backend: str) -> None:
    """The library names its flat counters (lep_*_field_name) exactly as the
    dataclasses' fields, in the order of the array it fills."""
    import leptrino

    be = leptrino.get_backend(backend)
    lib = be.lib
    for cls, count, name_of in (
            (leptrino.Health, lib.lep_session_health_fields, lib.lep_session_health_field_name),
            (leptrino.SimStats, lib.lep_sim_stats_fields, lib.lep_sim_stats_field_name)):
        names = [be.text(name_of(i)) for i in range(int(count()))]
        assert names == _flat_names(cls), cls
        assert be.text(name_of(len(names))) == ""  # NULL past the end


def test_counters_are_copied_from_c(backend: str) -> None:
    """from_c reads every member of a struct, from_fields every name: distinct
    values in, the same values out."""
    import leptrino

    be = leptrino.get_backend(backend)
    structs: List[Tuple[str, Any]] = [("lep_client_stats", leptrino.ClientStats),
                                      ("lep_frame_stats", leptrino.FrameStats)]
    for cname, cls in structs:
        c = be.new(cname)
        want: Dict[str, Any] = {}
        for i, f in enumerate(dataclasses.fields(cls)):
            setattr(c, f.name, 1 + i)
            want[f.name] = 1 + i
        got = cls.from_c(c)
        assert {k: getattr(got, k) for k in want} == want, cname
    flats: List[Any] = [leptrino.Health, leptrino.SimStats, leptrino.ClientStats]
    for cls in flats:
        names = _flat_names(cls)
        values = {n: float(1 + i) for i, n in enumerate(names)}
        made: Any = cls.from_fields(values)
        flat: Dict[str, Any] = {}
        for f in dataclasses.fields(made):
            v: Any = getattr(made, f.name)
            if dataclasses.is_dataclass(v) and not isinstance(v, type):
                flat.update(dataclasses.asdict(v))
            else:
                flat[f.name] = v
        assert flat == {n: (True if isinstance(flat[n], bool) else v)
                        for n, v in values.items()}, cls
    h = leptrino.Health.from_fields({n: 7.0 for n in _flat_names(leptrino.Health)})
    assert h.client.stalls == 7 and isinstance(h.client.stalls, int)
    assert isinstance(h.shortfall, bool) and isinstance(h.elapsed_s, float)


# ---- the generated files and the library ---------------------------------

def _generator(root: Path) -> Any:
    spec = importlib.util.spec_from_file_location("gen_python_decls",
                                                  root / "tools" / "gen_python_decls.py")
    assert spec and spec.loader
    mod = importlib.util.module_from_spec(spec)
    sys.modules["gen_python_decls"] = mod
    spec.loader.exec_module(mod)
    return mod


def test_generated_files_are_current(root: Path) -> None:
    """The committed declarations are what the generator makes of the headers
    (run tools/gen_python_decls.py after changing a header)."""
    import leptrino

    gen = _generator(root)
    package = Path(leptrino.__file__).resolve().parent
    fresh = gen.generate(root / "include")
    assert set(fresh) == {"_constants.py", "_cdef.py", "_ctypes_decls.py", "_stats.py"}
    stale = [name for name, text in fresh.items()
             if (package / name).read_text(encoding="utf-8") != text]
    assert stale == [], f"stale: {stale}; run python3 tools/gen_python_decls.py"


def test_generator_refuses_what_it_cannot_translate(root: Path, tmp_path: Path) -> None:
    """A header construct the generator has no translation for is an error
    naming it, never silently left out."""
    gen = _generator(root)
    inc = tmp_path / "include"
    shutil.copytree(root / "include", inc)
    with open(inc / "leptrino" / "frame.h", "a", encoding="utf-8") as f:
        f.write("\n#define LEP_NOT_A_NUMBER (sizeof(int) * 3)\n")
    with pytest.raises(gen.GenError, match="cannot evaluate"):
        gen.generate(inc)


def test_library_exports_exactly_the_declared_functions() -> None:
    """The loaded library's exported lep_* symbols are the declared functions."""
    import leptrino

    nm = shutil.which("nm")
    assert nm, "nm (binutils) is needed to list the library's symbols"
    path = leptrino.get_backend("ctypes").path
    out = subprocess.run([nm, "-D", "--defined-only", path], capture_output=True, text=True,
                         check=True).stdout
    exported = {line.split()[-1] for line in out.splitlines()
                if line.split() and line.split()[-1].startswith("lep_")}
    assert exported == set(ct.FUNCTIONS)


def test_client_size_covers_the_header_layout(backend: str) -> None:
    """lep_client is allocated as lep_client_sizeof() bytes: sane and 8-aligned use."""
    import leptrino

    be = leptrino.get_backend(backend)
    size = int(be.lib.lep_client_sizeof())
    assert 200 <= size <= 4096
