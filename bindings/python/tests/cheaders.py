"""A small reader of leptrino's public C headers, for the declaration check.

Written apart from tools/gen_python_decls.py (which uses the C preprocessor
and pycparser), with regular expressions on the header text, so that the
check of the generated declarations is independent of the generator.

Extracts LEP_API prototypes, typedef'd structs (with nested unions),
function pointer types, enum constants and #defines. Types are normalised to
cffi's spelling: no const, "_Bool" for bool, "unsigned int" for unsigned, one
" *" per pointer level, "T[N]" for arrays with N evaluated from the
#defines, "R(*)(A, B)" for function pointers; array parameters become
pointers.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Tuple, Union

Field = Tuple[str, Union[str, "Struct"]]


@dataclass
class Struct:
    name: str
    fields: List[Field] = field(default_factory=list)  # (name, type or nested Struct)
    kind: str = "struct"


@dataclass
class Headers:
    functions: Dict[str, Tuple[str, List[str]]] = field(default_factory=dict)
    structs: Dict[str, Struct] = field(default_factory=dict)
    opaque: List[str] = field(default_factory=list)
    #: constants whose value this reader evaluates (int, float or str)
    constants: Dict[str, Union[int, float, str]] = field(default_factory=dict)
    #: every public constant name: LEP_* object-like macros (not config.h's or
    #: export.h's switches, not private names ending in "_") and enumerators
    constant_names: List[str] = field(default_factory=list)
    #: enum name -> its enumerators, in order
    enums: Dict[str, List[str]] = field(default_factory=dict)
    #: function pointer typedefs: name -> "R(*)(A, B)"
    funcptrs: Dict[str, str] = field(default_factory=dict)


def _strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def _eval_int(expr: str, env: Dict[str, Union[int, float, str]]) -> Optional[int]:
    v = _eval(expr, env)
    return v if isinstance(v, int) else None


def _eval(expr: str, env: Dict[str, Union[int, float, str]]) -> Union[int, float, str, None]:
    expr = expr.strip()
    if re.fullmatch(r'"[^"\\]*"', expr):
        return expr[1:-1]
    if re.fullmatch(r"\d+\.\d*([eE][-+]?\d+)?", expr):
        return float(expr)
    expr = re.sub(r"\b(0[xX][0-9a-fA-F]+|\d+)[uUlL]*\b", r"\1", expr)
    expr = re.sub(r"\b(LEP_\w+)\b", lambda m: str(env[m.group(1)]) if m.group(1) in env
                  else m.group(1), expr)
    if not re.fullmatch(r"[0-9a-fA-FxX+\-*/() <>|&]+", expr):
        return None
    try:
        value = eval(expr, {"__builtins__": {}}, {})  # digits and operators only
    except Exception:
        return None
    return int(value) if isinstance(value, int) else None


_FUNCPTRS: Dict[str, str] = {}  # filled by parse(): typedef name -> spelling


def normalise(decl_type: str) -> str:
    """'const uint8_t *' -> 'uint8_t *'; 'bool' -> '_Bool'; a function pointer
    typedef name -> its spelling."""
    t = decl_type.replace("*", " * ")
    words = [w for w in t.split() if w not in ("const", "volatile", "struct", "enum")]
    stars = words.count("*")
    base = " ".join(w for w in words if w != "*")
    base = {"bool": "_Bool", "unsigned": "unsigned int", "signed": "int"}.get(base, base)
    if base in _FUNCPTRS and stars == 0:
        return _FUNCPTRS[base]
    return base + " *" * stars


def _params(raw: str, env: Dict[str, Union[int, float, str]]) -> List[str]:
    params: List[str] = []
    raw = " ".join(raw.split())
    if raw in ("", "void"):
        return params
    for p in raw.split(","):
        p = p.strip()
        arr = re.fullmatch(r"(.+?)\s*\b\w+\s*\[.*\]", p)
        if arr:  # an array parameter is a pointer
            params.append(normalise(arr.group(1) + " *"))
            continue
        t, _ = _split_decl(p, env)
        params.append(t)
    return params


def _fnptr(ret: str, raw: str, env: Dict[str, Union[int, float, str]]) -> str:
    return f"{normalise(ret)}(*)({', '.join(_params(raw, env))})"


def _split_decl(decl: str, env: Dict[str, Union[int, float, str]]) -> Tuple[str, str]:
    """'const uint8_t *msg' -> ('uint8_t *', 'msg'); 'double si[LEP_AXES]' (param)
    is handled by the caller; a field 'char model[LEP_MODEL_LEN + 1]' ->
    ('char[17]', 'model')."""
    decl = " ".join(decl.split())
    fn = re.fullmatch(r"(.+?)\(\s*\*\s*(\w+)\s*\)\s*\((.*)\)", decl)
    if fn:  # function pointer member
        return _fnptr(fn.group(1), fn.group(3), env), fn.group(2)
    arr = re.fullmatch(r"(.+?)\s*\b(\w+)\s*\[(.*)\]", decl)
    if arr:
        n = _eval_int(arr.group(3), env)
        return f"{normalise(arr.group(1))}[{n}]", arr.group(2)
    m = re.fullmatch(r"(.*?[\s*])(\w+)", decl)
    if not m:
        raise ValueError(f"cannot parse declaration {decl!r}")
    return normalise(m.group(1)), m.group(2)


def _parse_body(body: str, env: Dict[str, Union[int, float, str]],
                counter: List[int]) -> List[Field]:
    fields: List[Field] = []
    i = 0
    while i < len(body):
        m = re.compile(r"\s*(union|struct)\s*(\w*)\s*\{").match(body, i)
        if m:
            depth, j = 1, m.end()
            while depth:
                depth += {"{": 1, "}": -1}.get(body[j], 0)
                j += 1
            inner = body[m.end():j - 1]
            end = body.index(";", j)
            name = body[j:end].strip()
            counter[0] += 1
            nested = Struct(m.group(2) or f"${counter[0]}", _parse_body(inner, env, counter),
                            m.group(1))
            fields.append((name, nested))
            i = end + 1
            continue
        end = body.find(";", i)
        if end < 0:
            break
        decl = body[i:end].strip()
        i = end + 1
        if decl:
            first, *more = [d.strip() for d in decl.split(",")] if "(" not in decl else [decl]
            t, name = _split_decl(first, env)
            fields.append((name, t))
            base = first[:first.rindex(name)].rstrip("* ")  # "double min, max"
            for d in more:
                t, name = _split_decl(f"{base} {d}", env)
                fields.append((name, t))
    return fields


#: Headers whose macros are build switches, not values.
SWITCH_HEADERS = ("config.h", "export.h")


def parse(include_dir: Path) -> Headers:
    h = Headers()
    texts = []
    for path in sorted(include_dir.glob("*.h")):
        text = _strip_comments(path.read_text(encoding="utf-8"))
        texts.append(text)
        if path.name in SWITCH_HEADERS:
            continue
        for m in re.finditer(r"^[ \t]*#[ \t]*define[ \t]+(LEP_\w+)([ \t]+[^\n]+)?$", text,
                             re.M):
            name = m.group(1)
            if name.endswith("_") or name in h.constant_names:
                continue  # private by the headers' convention
            h.constant_names.append(name)
            value = _eval(m.group(2) or "", h.constants)
            if value is not None:
                h.constants[name] = value
    text = "\n".join(texts)
    for m in re.finditer(r"\benum\s+(\w+)\s*\{([^}]*)\}", text):
        nxt = 0
        items = h.enums.setdefault(m.group(1), [])
        for item in m.group(2).split(","):
            item = item.strip()
            if not item:
                continue
            name, _, expr = item.partition("=")
            name = name.strip()
            value = _eval_int(expr, h.constants) if expr.strip() else nxt
            if value is None:
                raise ValueError(f"cannot evaluate enum value {item!r}")
            h.constants[name] = value
            h.constant_names.append(name)
            items.append(name)
            nxt = value + 1

    body_text = re.sub(r"^[ \t]*#[^\n]*$", " ", text, flags=re.M)
    _FUNCPTRS.clear()
    for m in re.finditer(r"\btypedef\s+([^;{}()]+?)\(\s*\*\s*(\w+)\s*\)\s*\(([^()]*)\)\s*;",
                         body_text):
        h.funcptrs[m.group(2)] = _fnptr(m.group(1), m.group(3), h.constants)
        _FUNCPTRS[m.group(2)] = h.funcptrs[m.group(2)]

    for m in re.finditer(r"\bLEP_API\s+([^;{}()]*?)\b(\w+)\s*\(([^()]*)\)\s*;", body_text):
        h.functions[m.group(2)] = (normalise(m.group(1)), _params(m.group(3), h.constants))

    for m in re.finditer(r"\btypedef\s+struct\s+(\w+)\s+(\w+)\s*;", body_text):
        h.opaque.append(m.group(2))
    counter = [0]
    for m in re.finditer(r"\btypedef\s+struct\s+(\w+)\s*\{", body_text):
        depth, j = 1, m.end()
        while depth:
            depth += {"{": 1, "}": -1}.get(body_text[j], 0)
            j += 1
        name = re.match(r"\s*(\w+)\s*;", body_text[j:])
        if not name:
            raise ValueError(f"typedef struct {m.group(1)}: no typedef name")
        h.structs[name.group(1)] = Struct(
            name.group(1), _parse_body(body_text[m.end():j - 1], h.constants, counter))
    return h
