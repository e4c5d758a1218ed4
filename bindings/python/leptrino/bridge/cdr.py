"""CDR (XCDR1, little-endian) encoding of the messages the bridge publishes.

A payload is the 4-byte encapsulation header (00 01 00 00: CDR_LE) and the
fields in order, each aligned to its own size (at most 8) counted from the
end of the header; a string is a uint32 length that counts its terminating
NUL, then the bytes and the NUL; a sequence is a uint32 count and the
elements. This is what rmw_zenoh (like the DDS middlewares) puts on the wire
and what an MCAP "cdr" channel holds. The per-sample message,
WrenchStamped, is serialized in C (lep_ros_wrench_cdr, wrench_batch.py);
here are the rare ones (diagnostics, service answers) and the one message
the bridge receives, Vector3Stamped (the gravity input), decoded strictly.
"""

from __future__ import annotations

import struct
from typing import Iterable, List, Sequence, Tuple

#: Encapsulation header: representation id CDR_LE (0x0001), options 0.
CDR_LE_HEADER = b"\x00\x01\x00\x00"


class CdrWriter:
    """Appends fields with CDR alignment. Not thread-safe; one per message."""

    __slots__ = ("_parts", "_n")

    def __init__(self) -> None:
        self._parts: List[bytes] = [CDR_LE_HEADER]
        self._n = 0  # bytes after the encapsulation header

    def _align(self, size: int) -> None:
        pad = -self._n % size
        if pad:
            self._parts.append(b"\x00" * pad)
            self._n += pad

    def _put(self, fmt: str, size: int, value: object) -> None:
        self._align(size)
        self._parts.append(struct.pack("<" + fmt, value))
        self._n += size

    def uint8(self, v: int) -> None:
        self._put("B", 1, v)

    def bool(self, v: bool) -> None:
        self._put("?", 1, bool(v))

    def int32(self, v: int) -> None:
        self._put("i", 4, v)

    def uint32(self, v: int) -> None:
        self._put("I", 4, v)

    def float64(self, v: float) -> None:
        self._put("d", 8, v)

    def string(self, s: str) -> None:
        raw = s.encode("utf-8")
        if b"\x00" in raw:
            raise ValueError("a CDR string cannot hold a NUL character")
        self.uint32(len(raw) + 1)
        self._parts.append(raw + b"\x00")
        self._n += len(raw) + 1

    def time(self, sec: int, nanosec: int) -> None:
        self.int32(sec)
        self.uint32(nanosec)

    def header(self, sec: int, nanosec: int, frame_id: str) -> None:
        self.time(sec, nanosec)
        self.string(frame_id)

    def getvalue(self) -> bytes:
        return b"".join(self._parts)


#: diagnostic_msgs/msg/DiagnosticStatus levels.
OK, WARN, ERROR, STALE = 0, 1, 2, 3

DiagStatus = Tuple[int, str, str, str, Iterable[Tuple[str, str]]]


def encode_diagnostic_array(sec: int, nanosec: int, frame_id: str,
                            statuses: Sequence[DiagStatus]) -> bytes:
    """diagnostic_msgs/msg/DiagnosticArray; each status is (level, name,
    message, hardware_id, [(key, value), ...])."""
    w = CdrWriter()
    w.header(sec, nanosec, frame_id)
    w.uint32(len(statuses))
    for level, name, message, hardware_id, values in statuses:
        w.uint8(level)
        w.string(name)
        w.string(message)
        w.string(hardware_id)
        kv = list(values)
        w.uint32(len(kv))
        for k, v in kv:
            w.string(k)
            w.string(v)
    return w.getvalue()


def encode_trigger_response(success: bool, message: str) -> bytes:
    """std_srvs/srv/Trigger_Response."""
    w = CdrWriter()
    w.bool(success)
    w.string(message)
    return w.getvalue()


def encode_trigger_request() -> bytes:
    """std_srvs/srv/Trigger_Request (its one placeholder byte)."""
    w = CdrWriter()
    w.uint8(0)
    return w.getvalue()


def check_encapsulation(payload: bytes) -> None:
    """ValueError unless payload starts with a CDR (little- or big-endian) header."""
    if len(payload) < 4 or payload[0] != 0 or payload[1] not in (0, 1):
        raise ValueError("not a CDR payload (bad encapsulation header)")


Vector3StampedFields = Tuple[int, int, str, Tuple[float, float, float]]


def encode_vector3_stamped(sec: int, nanosec: int, frame_id: str,
                           vector: Sequence[float]) -> bytes:
    """geometry_msgs/msg/Vector3Stamped."""
    w = CdrWriter()
    w.header(sec, nanosec, frame_id)
    for v in vector:
        w.float64(float(v))
    return w.getvalue()


def decode_vector3_stamped(payload: bytes) -> Vector3StampedFields:
    """(sec, nanosec, frame_id, (x, y, z)) of a geometry_msgs/msg/Vector3Stamped
    in CDR (little- or big-endian). ValueError, saying what is wrong, for
    anything else: a bad encapsulation header, a length that is not the
    message's (up to 3 bytes of padding after it are allowed, as DDS pads a
    sample to 4 bytes), a string that is not NUL-terminated UTF-8."""
    check_encapsulation(payload)
    e = "<" if payload[1] == 1 else ">"
    body = memoryview(payload)[4:]
    if len(body) < 12:
        raise ValueError(f"{len(payload)} bytes: too short for a Vector3Stamped")
    sec, nanosec, n = struct.unpack_from(e + "iII", body, 0)
    if n < 1 or 12 + n > len(body):
        raise ValueError(f"frame_id length {n} does not fit in {len(payload)} bytes")
    raw = bytes(body[12:12 + n])
    if raw[-1] != 0 or b"\x00" in raw[:-1]:
        raise ValueError("frame_id is not a NUL-terminated string")
    try:
        frame_id = raw[:-1].decode("utf-8")
    except UnicodeDecodeError:
        raise ValueError("frame_id is not UTF-8") from None
    at = 12 + n
    at += -at % 8
    end = at + 24
    if not end <= len(body) < end + 4:
        raise ValueError(f"{len(payload)} bytes, not the {4 + end} of this Vector3Stamped")
    x, y, z = struct.unpack_from(e + "ddd", body, at)
    return sec, nanosec, frame_id, (x, y, z)
