"""RIHS01 type hashes (REP 2016) computed from message definitions.

ROS 2 (rosidl_generator_type_description) describes each interface as a
TypeDescription: the type's fields (name; type id, capacity, string
capacity, nested type name) plus every type it references, sorted by name.
That description, without default values, is written as JSON with ", " and
": " separators in a fixed key order; its SHA-256 is the hash, written
"RIHS01_<64 hex digits>". The definitions are
bridge/schema.py's (.msg text as in ros2/common_interfaces and
ros2/rcl_interfaces); this module computes the hashes from them; nothing
here is a stored hash.
"""

from __future__ import annotations

import hashlib
import json
import re
from typing import Any, Dict, List, Optional, Set, Tuple

# the definitions: bridge/schema.py, the one description of each message
from .schema import MESSAGES, SERVICES

Description = Dict[str, Any]

#: Field type ids of type_description_interfaces/msg/FieldType.
_BASIC_IDS: Dict[str, int] = {
    "int8": 2, "uint8": 3, "int16": 4, "uint16": 5, "int32": 6, "uint32": 7,
    "int64": 8, "uint64": 9, "float32": 10, "float64": 11, "char": 3,
    "bool": 15, "byte": 16, "string": 17, "wstring": 18,
}
_NESTED = 1
_BOUNDED_STRING = 21
_BOUNDED_WSTRING = 22
#: Added to the element's id for a fixed array, a bounded and an unbounded sequence.
_ARRAY, _BOUNDED_SEQ, _UNBOUNDED_SEQ = 48, 96, 144

_TYPE_RE = re.compile(
    r"^(?P<base>[A-Za-z_][\w/]*)(?:<=(?P<strcap>\d+))?(?:\[(?P<seq>(?:<=)?\d*)\])?$")
_CONST_RE = re.compile(r"^\S+\s+[A-Z][A-Z0-9_]*\s*=")
_NAME_RE = re.compile(r"^[a-z][a-z0-9_]*$")

Field = Tuple[str, int, int, int, str]  # name, type id, capacity, string capacity, nested name


def _qualify(base: str, package: str) -> str:
    """A nested type's full name: "Wrench" in geometry_msgs -> geometry_msgs/msg/Wrench."""
    if base == "Header":
        return "std_msgs/msg/Header"
    parts = base.split("/")
    if len(parts) == 1:
        return f"{package}/msg/{base}"
    if len(parts) == 2:
        return f"{parts[0]}/msg/{parts[1]}"
    return base


def parse_fields(text: str, package: str) -> List[Field]:
    """The fields of a .msg body (constants, comments and blank lines skipped).
    ValueError for a line that is neither."""
    out: List[Field] = []
    for raw in text.splitlines():
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if _CONST_RE.match(line):
            continue  # a constant
        parts = line.split()
        m = _TYPE_RE.match(parts[0])
        if m is None or len(parts) < 2 or not _NAME_RE.match(parts[1]):
            raise ValueError(f"not a field: {raw!r}")
        base, name = m.group("base"), parts[1]
        strcap = int(m.group("strcap") or 0)
        nested = ""
        if base in _BASIC_IDS:
            tid = _BASIC_IDS[base]
            if strcap:
                tid = _BOUNDED_STRING if base == "string" else _BOUNDED_WSTRING
        else:
            tid = _NESTED
            nested = _qualify(base, package)
        cap = 0
        seq = m.group("seq")
        if seq is not None:
            if seq == "":
                tid += _UNBOUNDED_SEQ
            elif seq.startswith("<="):
                tid += _BOUNDED_SEQ
                cap = int(seq[2:])
            else:
                tid += _ARRAY
                cap = int(seq)
        out.append((name, tid, cap, strcap, nested))
    if not out:  # rosidl gives an empty structure one placeholder member
        out.append(("structure_needs_at_least_one_member", _BASIC_IDS["uint8"], 0, 0, ""))
    return out


def _individual(type_name: str, fields: List[Field]) -> Description:
    return {
        "type_name": type_name,
        "fields": [
            {"name": n, "type": {"type_id": t, "capacity": c, "string_capacity": s,
                                 "nested_type_name": nt}}
            for (n, t, c, s, nt) in fields
        ],
    }


def _catalogue() -> Dict[str, Description]:
    """Every individual description known here, services expanded as rosidl
    does (the service type, its request, response and event messages)."""
    cat: Dict[str, Description] = {}
    for name, text in MESSAGES.items():
        cat[name] = _individual(name, parse_fields(text, name.split("/")[0]))
    for name, text in SERVICES.items():
        pkg = name.split("/")[0]
        req_text, _, resp_text = text.partition("---")
        req, resp, event = name + "_Request", name + "_Response", name + "_Event"
        cat[req] = _individual(req, parse_fields(req_text, pkg))
        cat[resp] = _individual(resp, parse_fields(resp_text, pkg))
        cat[event] = _individual(event, [
            ("info", _NESTED, 0, 0, "service_msgs/msg/ServiceEventInfo"),
            ("request", _NESTED + _BOUNDED_SEQ, 1, 0, req),
            ("response", _NESTED + _BOUNDED_SEQ, 1, 0, resp),
        ])
        cat[name] = _individual(name, [
            ("request_message", _NESTED, 0, 0, req),
            ("response_message", _NESTED, 0, 0, resp),
            ("event_message", _NESTED, 0, 0, event),
        ])
    return cat


def type_description(type_name: str,
                     catalogue: Optional[Dict[str, Description]] = None) -> Description:
    """The full TypeDescription of a type: itself and every type it reaches,
    the referenced ones sorted by name. KeyError for an unknown type."""
    cat = catalogue if catalogue is not None else _catalogue()
    top = cat[type_name]
    seen: Set[str] = set()
    queue = [f["type"]["nested_type_name"] for f in top["fields"] if f["type"]["nested_type_name"]]
    while queue:
        t = queue.pop()
        if t in seen:
            continue
        seen.add(t)
        queue += [f["type"]["nested_type_name"] for f in cat[t]["fields"]
                  if f["type"]["nested_type_name"]]
    return {"type_description": top,
            "referenced_type_descriptions": [cat[t] for t in sorted(seen)]}


def canonical_json(description: Description) -> str:
    """The text REP 2016 hashes: compact JSON with ", " and ": " separators,
    keys in the order above, ASCII only."""
    return json.dumps(description, ensure_ascii=True, allow_nan=False,
                      separators=(", ", ": "), sort_keys=False)


def rihs01(type_name: str) -> str:
    """"RIHS01_" + the SHA-256 of the canonical JSON of the type's description."""
    text = canonical_json(type_description(type_name))
    return "RIHS01_" + hashlib.sha256(text.encode("utf-8")).hexdigest()
