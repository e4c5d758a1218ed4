"""A small reader of leptrino's public C headers, for the declaration check.

Extracts what the bindings declare by hand: LEP_API prototypes, typedef'd
structs (with nested unions), enum constants and numeric #defines. Types are
normalised to cffi's spelling: no const, "_Bool" for bool, "unsigned int"
for unsigned, one " *" per pointer level, "T[N]" for arrays with N
evaluated from the #defines; array parameters become pointers.
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
    constants: Dict[str, int] = field(default_factory=dict)


def _strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def _eval_int(expr: str, env: Dict[str, int]) -> Optional[int]:
    expr = re.sub(r"\b(0[xX][0-9a-fA-F]+|\d+)[uUlL]*\b", r"\1", expr.strip())
    expr = re.sub(r"\b(LEP_\w+)\b", lambda m: str(env[m.group(1)]) if m.group(1) in env
                  else m.group(1), expr)
    if not re.fullmatch(r"[0-9a-fA-FxX+\-*/() <>|&]+", expr):
        return None
    try:
        value = eval(expr, {"__builtins__": {}}, {})  # digits and operators only
    except Exception:
        return None
    return int(value) if isinstance(value, int) else None


def normalise(decl_type: str) -> str:
    """'const uint8_t *' -> 'uint8_t *'; 'bool' -> '_Bool'."""
    t = decl_type.replace("*", " * ")
    words = [w for w in t.split() if w not in ("const", "volatile", "struct", "enum")]
    stars = words.count("*")
    base = " ".join(w for w in words if w != "*")
    base = {"bool": "_Bool", "unsigned": "unsigned int", "signed": "int"}.get(base, base)
    return base + " *" * stars


def _split_decl(decl: str, env: Dict[str, int]) -> Tuple[str, str]:
    """'const uint8_t *msg' -> ('uint8_t *', 'msg'); 'double si[LEP_AXES]' (param)
    is handled by the caller; a field 'char model[LEP_MODEL_LEN + 1]' ->
    ('char[17]', 'model')."""
    decl = " ".join(decl.split())
    fn = re.fullmatch(r"(.+?)\(\s*\*\s*(\w+)\s*\)\s*\((.*)\)", decl)
    if fn:  # function pointer member
        return "fnptr", fn.group(2)
    arr = re.fullmatch(r"(.+?)\s*\b(\w+)\s*\[(.*)\]", decl)
    if arr:
        n = _eval_int(arr.group(3), env)
        return f"{normalise(arr.group(1))}[{n}]", arr.group(2)
    m = re.fullmatch(r"(.*?[\s*])(\w+)", decl)
    if not m:
        raise ValueError(f"cannot parse declaration {decl!r}")
    return normalise(m.group(1)), m.group(2)


def _parse_body(body: str, env: Dict[str, int], counter: List[int]) -> List[Field]:
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


def parse(include_dir: Path) -> Headers:
    h = Headers()
    texts = []
    for path in sorted(include_dir.glob("*.h")):
        texts.append(_strip_comments(path.read_text(encoding="utf-8")))
    text = "\n".join(texts)

    for m in re.finditer(r"^[ \t]*#[ \t]*define[ \t]+(LEP_\w+)[ \t]+([^\n]+)$", text, re.M):
        value = _eval_int(m.group(2), h.constants)
        if value is not None:
            h.constants[m.group(1)] = value
    for m in re.finditer(r"\benum\s+\w+\s*\{([^}]*)\}", text):
        nxt = 0
        for item in m.group(1).split(","):
            item = item.strip()
            if not item:
                continue
            name, _, expr = item.partition("=")
            name = name.strip()
            value = _eval_int(expr, h.constants) if expr.strip() else nxt
            if value is None:
                raise ValueError(f"cannot evaluate enum value {item!r}")
            h.constants[name] = value
            nxt = value + 1

    body_text = re.sub(r"^[ \t]*#[^\n]*$", " ", text, flags=re.M)

    for m in re.finditer(r"\bLEP_API\s+([^;{}()]*?)\b(\w+)\s*\(([^()]*)\)\s*;", body_text):
        ret = normalise(m.group(1))
        params: List[str] = []
        raw = " ".join(m.group(3).split())
        if raw not in ("", "void"):
            for p in raw.split(","):
                p = p.strip()
                arr = re.fullmatch(r"(.+?)\s*\b\w+\s*\[.*\]", p)
                if arr:  # an array parameter is a pointer
                    params.append(normalise(arr.group(1) + " *"))
                    continue
                t, _ = _split_decl(p, h.constants)
                params.append(t)
        h.functions[m.group(2)] = (ret, params)

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
