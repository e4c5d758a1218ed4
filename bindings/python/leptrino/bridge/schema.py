"""The one description of each message the bridge speaks, and what comes of it.

Each message is described once, as its .msg text (ROS 2's interface
definition, as in ros2/common_interfaces, ros2/rcl_interfaces and
ros2/rmw_dds_common), in MESSAGES and SERVICES below. From that text come:

- the RIHS01 type hashes (typehash.py: the fields parsed, REP 2016);
- the MCAP / Foxglove ros2msg schemas (ros2msg_schema());
- the CDR encoder and strict decoder (encode(), decode(): XCDR1, the
  encapsulation header first, each field aligned to its size up to 8
  counted after the header; strings with their NUL; sequences with a uint32
  count);
- the DDS types (idl_types(): cyclonedds IdlStruct classes named as rosidl
  names them for DDS, package::msg::dds_::Type_).

The WrenchStamped of every sample is serialized in C (lep_ros_wrench_cdr:
wrench_batch.py) for speed; a test checks its bytes against encode() here.
"""

from __future__ import annotations

import struct
import types
from dataclasses import dataclass as _dataclass
from typing import Any, Dict, List, Optional, Sequence, Tuple

#: The message definitions (.msg text; constants and comments do not enter a hash).
MESSAGES: Dict[str, str] = {
    "builtin_interfaces/msg/Time": "int32 sec\nuint32 nanosec\n",
    "std_msgs/msg/Header": "builtin_interfaces/Time stamp\nstring frame_id\n",
    "std_msgs/msg/Empty": "",
    "geometry_msgs/msg/Vector3": "float64 x\nfloat64 y\nfloat64 z\n",
    "geometry_msgs/msg/Wrench": "Vector3 force\nVector3 torque\n",
    "geometry_msgs/msg/WrenchStamped": "std_msgs/Header header\nWrench wrench\n",
    "geometry_msgs/msg/Vector3Stamped": "std_msgs/Header header\nVector3 vector\n",
    "diagnostic_msgs/msg/KeyValue": "string key\nstring value\n",
    "diagnostic_msgs/msg/DiagnosticStatus": (
        "byte OK=0\nbyte WARN=1\nbyte ERROR=2\nbyte STALE=3\n"
        "byte level\nstring name\nstring message\nstring hardware_id\nKeyValue[] values\n"),
    "diagnostic_msgs/msg/DiagnosticArray": "std_msgs/Header header\nDiagnosticStatus[] status\n",
    "service_msgs/msg/ServiceEventInfo": (
        "uint8 REQUEST_SENT = 0\nuint8 REQUEST_RECEIVED = 1\nuint8 RESPONSE_SENT = 2\n"
        "uint8 RESPONSE_RECEIVED = 3\n"
        "uint8 event_type\nbuiltin_interfaces/Time stamp\nchar[16] client_gid\n"
        "int64 sequence_number\n"),
}

#: The .srv definitions: request and response, split at "---".
SERVICES: Dict[str, str] = {
    "std_srvs/srv/Trigger": "---\nbool success\nstring message\n",
}

#: What only DDS needs: the node announcement (rmw_dds_common/msg/*.msg; Gid
#: is char[16] from Iron on, char[24] in Humble: dds.GID_LENGTH).
DDS_MESSAGES: Dict[str, str] = {
    "rmw_dds_common/msg/Gid": "char[16] data\n",
    "rmw_dds_common/msg/NodeEntitiesInfo": (
        "string<=256 node_namespace\nstring<=256 node_name\n"
        "Gid[] reader_gid_seq\nGid[] writer_gid_seq\n"),
    "rmw_dds_common/msg/ParticipantEntitiesInfo": (
        "Gid gid\nNodeEntitiesInfo[] node_entities_info_seq\n"),
}

Field = Tuple[str, int, int, int, str]  # name, type id, capacity, string capacity, nested name

# type ids (type_description_interfaces/msg/FieldType), as typehash.py parses them
_NESTED, _STRING, _WSTRING, _BSTRING, _BWSTRING = 1, 17, 18, 21, 22
_PRIM: Dict[int, Tuple[str, int]] = {  # id -> struct format, size
    2: ("b", 1), 3: ("B", 1), 4: ("h", 2), 5: ("H", 2), 6: ("i", 4), 7: ("I", 4),
    8: ("q", 8), 9: ("Q", 8), 10: ("f", 4), 11: ("d", 8), 15: ("?", 1), 16: ("B", 1),
}
_SINGLE, _ARRAY, _BOUNDED_SEQ, _UNBOUNDED_SEQ = 0, 1, 2, 3  # type id // 48


def text(type_name: str) -> str:
    """The .msg text of a message, or of a service's _Request / _Response."""
    if type_name in MESSAGES:
        return MESSAGES[type_name]
    if type_name in DDS_MESSAGES:
        return DDS_MESSAGES[type_name]
    base, _, part = type_name.rpartition("_")
    if base in SERVICES and part in ("Request", "Response"):
        return SERVICES[base].partition("---")[0 if part == "Request" else 2]
    raise KeyError(type_name)


def fields(type_name: str, overrides: Optional[Dict[str, str]] = None) -> List[Field]:
    """The fields of a type, parsed from its one description (an empty
    message: rosidl's one placeholder byte). overrides: type -> .msg text."""
    from .typehash import parse_fields

    t = (overrides or {}).get(type_name)
    if t is not None:
        return parse_fields(t, type_name.split("/")[0])
    got = _FIELDS.get(type_name)
    if got is None:
        got = _FIELDS[type_name] = parse_fields(text(type_name), type_name.split("/")[0])
    return got


_FIELDS: Dict[str, List[Field]] = {}


# -- CDR ----------------------------------------------------------------------

CDR_LE_HEADER = b"\x00\x01\x00\x00"


def encode(type_name: str, value: Sequence[Any]) -> bytes:
    """A message in CDR little-endian, encapsulation header first. value: the
    fields in order, nested messages as sequences of their fields, arrays
    and sequences as lists. ValueError for what the type cannot hold."""
    out = bytearray()
    _encode(out, type_name, value)
    return CDR_LE_HEADER + bytes(out)


def _encode(out: bytearray, type_name: str, value: Sequence[Any]) -> None:
    fs = fields(type_name)
    if len(value) != len(fs):
        raise ValueError(f"{type_name}: {len(fs)} fields, {len(value)} values")
    for (name, tid, cap, _strcap, nested), v in zip(fs, value):
        kind, base = divmod(tid, 48)
        if kind == _SINGLE:
            _encode_one(out, base, nested, v)
            continue
        items = list(v)
        if kind == _ARRAY and len(items) != cap:
            raise ValueError(f"{type_name}.{name}: {len(items)} items, not {cap}")
        if kind == _BOUNDED_SEQ and len(items) > cap:
            raise ValueError(f"{type_name}.{name}: more than {cap} items")
        if kind != _ARRAY:
            _put(out, "I", 4, len(items))
        for x in items:
            _encode_one(out, base, nested, x)


def _put(out: bytearray, fmt: str, size: int, v: Any) -> None:
    out += b"\x00" * (-len(out) % size)
    out += struct.pack("<" + fmt, v)


def _encode_one(out: bytearray, base: int, nested: str, v: Any) -> None:
    if base == _NESTED:
        _encode(out, nested, v)
    elif base in (_STRING, _BSTRING):
        raw = str(v).encode("utf-8")
        if b"\x00" in raw:
            raise ValueError("a CDR string cannot hold a NUL character")
        _put(out, "I", 4, len(raw) + 1)
        out += raw + b"\x00"
    elif base in _PRIM:
        fmt, size = _PRIM[base]
        _put(out, fmt, size, bool(v) if fmt == "?" else v)
    else:
        raise ValueError(f"type id {base}: not supported")


def decode(type_name: str, payload: bytes) -> Tuple[Any, ...]:
    """A message in CDR (little- or big-endian) -> its fields in order (the
    form encode() takes). ValueError, saying what is wrong, for anything
    else: a bad encapsulation header, a length that is not the message's (up
    to 3 bytes of padding after it are allowed, as DDS pads a sample to 4
    bytes), a string that is not NUL-terminated UTF-8."""
    if len(payload) < 4 or payload[0] != 0 or payload[1] not in (0, 1):
        raise ValueError("not a CDR payload (bad encapsulation header)")
    r = _Reader(memoryview(payload)[4:], "<" if payload[1] == 1 else ">", len(payload))
    v = r.message(type_name)
    if not r.at <= len(r.body) < r.at + 4:
        raise ValueError(f"{len(payload)} bytes, not the {4 + r.at} of this {type_name}")
    return v


class _Reader:
    def __init__(self, body: memoryview, endian: str, total: int) -> None:
        self.body, self.e, self.at, self.total = body, endian, 0, total

    def take(self, fmt: str, size: int) -> Any:
        self.at += -self.at % size
        if self.at + size > len(self.body):
            raise ValueError(f"{self.total} bytes: too short")
        v = struct.unpack_from(self.e + fmt, self.body, self.at)[0]
        self.at += size
        return v

    def string(self) -> str:
        n = self.take("I", 4)
        if n < 1 or self.at + n > len(self.body):
            raise ValueError(f"string length {n} does not fit in {self.total} bytes")
        raw = bytes(self.body[self.at:self.at + n])
        self.at += n
        if raw[-1] != 0 or b"\x00" in raw[:-1]:
            raise ValueError("a string is not NUL-terminated")
        try:
            return raw[:-1].decode("utf-8")
        except UnicodeDecodeError:
            raise ValueError("a string is not UTF-8") from None

    def one(self, base: int, nested: str) -> Any:
        if base == _NESTED:
            return self.message(nested)
        if base in (_STRING, _BSTRING):
            return self.string()
        fmt, size = _PRIM[base]
        return self.take(fmt, size)

    def message(self, type_name: str) -> Tuple[Any, ...]:
        out: List[Any] = []
        for _name, tid, cap, _s, nested in fields(type_name):
            kind, base = divmod(tid, 48)
            if kind == _SINGLE:
                out.append(self.one(base, nested))
                continue
            n = cap if kind == _ARRAY else self.take("I", 4)
            if n > self.total:
                raise ValueError(f"sequence of {n} in {self.total} bytes")
            out.append([self.one(base, nested) for _ in range(n)])
        return tuple(out)


# -- ros2msg (MCAP, Foxglove) ---------------------------------------------------

_SEPARATOR = "=" * 80


def ros2msg_schema(ros_type: str) -> bytes:
    """The ros2msg schema text of a type: its definition, then each type it
    references (by full name, sorted), as rosbag2 writes them."""
    from .typehash import type_description

    desc = type_description(ros_type)
    body = text(ros_type).strip("\n")
    parts: List[str] = [body] if body else []
    for ref in desc["referenced_type_descriptions"]:
        name = ref["type_name"]
        parts.append(f"{_SEPARATOR}\nMSG: {name}\n{text(name).rstrip(chr(10))}")
    return ("\n".join(parts) + "\n").encode("utf-8") if parts else b""


# -- DDS (cyclonedds) -------------------------------------------------------------

def dds_type_name(ros_type: str) -> str:
    """"geometry_msgs/msg/WrenchStamped" -> "geometry_msgs::msg::dds_::WrenchStamped_"."""
    pkg, kind, name = ros_type.split("/")
    return f"{pkg}::{kind}::dds_::{name}_"


def idl_types(names: Sequence[str], overrides: Optional[Dict[str, str]] = None,
              extra_fields: Optional[Dict[str, List[Field]]] = None) -> Dict[str, Any]:
    """cyclonedds IdlStruct classes for the types named and every type they
    reference, by ROS type name. overrides: type -> .msg text used instead
    (the Gid of another release); extra_fields: fields put before a type's
    own (rmw_cyclonedds' request header on a service's request and reply)."""
    from cyclonedds.idl import IdlStruct
    from cyclonedds.idl import types as t

    prim: Dict[int, Any] = {2: t.int8, 3: t.uint8, 4: t.int16, 5: t.uint16, 6: t.int32,
                            7: t.uint32, 8: t.int64, 9: t.uint64, 10: t.float32,
                            11: t.float64, 15: bool, 16: t.uint8}
    made: Dict[str, Any] = {}

    def element(base: int, strcap: int, nested: str) -> Any:
        if base == _NESTED:
            return make(nested)
        if base in (_STRING, _BSTRING):
            return t.bounded_str[strcap] if strcap else str
        return prim[base]

    def make(name: str) -> Any:
        if name in made:
            return made[name]
        annotations: Dict[str, Any] = {}
        for fname, tid, cap, strcap, nested in (list((extra_fields or {}).get(name, []))
                                                + fields(name, overrides)):
            kind, base = divmod(tid, 48)
            et = element(base, strcap, nested)
            annotations[fname] = (et if kind == _SINGLE else t.array[et, cap]
                                  if kind == _ARRAY else t.sequence[et, cap]
                                  if kind == _BOUNDED_SEQ else t.sequence[et])
        def body(ns: Dict[str, Any], annotations: Dict[str, Any] = annotations) -> None:
            ns["__annotations__"] = annotations

        cls = types.new_class(name.rsplit("/", 1)[-1], (IdlStruct,),
                              {"typename": dds_type_name(name)}, body)
        made[name] = _dataclass(cls)
        return made[name]

    return {n: make(n) for n in names}
