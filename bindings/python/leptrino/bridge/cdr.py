"""CDR of the messages the bridge makes and takes, through the one schema
(bridge/schema.py: encode() and decode() from each message's description).

A payload is the 4-byte encapsulation header (00 01 00 00: CDR_LE) and the
fields in order, each aligned to its own size (at most 8) counted from the
end of the header; this is what rmw_zenoh (like the DDS middlewares) puts on
the wire and what an MCAP "cdr" channel holds. The per-sample message,
WrenchStamped, is serialized in C (lep_ros_wrench_cdr, wrench_batch.py; a
test holds it to schema.encode); here are the rare ones (diagnostics,
service answers) and the one message the bridge receives, Vector3Stamped
(the gravity input), decoded strictly.
"""

from __future__ import annotations

from typing import Iterable, Sequence, Tuple

from . import schema

#: Encapsulation header: representation id CDR_LE (0x0001), options 0.
CDR_LE_HEADER = schema.CDR_LE_HEADER

#: diagnostic_msgs/msg/DiagnosticStatus levels.
OK, WARN, ERROR, STALE = 0, 1, 2, 3

DiagStatus = Tuple[int, str, str, str, Iterable[Tuple[str, str]]]


def encode_diagnostic_array(sec: int, nanosec: int, frame_id: str,
                            statuses: Sequence[DiagStatus]) -> bytes:
    """diagnostic_msgs/msg/DiagnosticArray; each status is (level, name,
    message, hardware_id, [(key, value), ...])."""
    return schema.encode("diagnostic_msgs/msg/DiagnosticArray", (
        ((sec, nanosec), frame_id),
        [(level, name, message, hw, list(values))
         for level, name, message, hw, values in statuses]))


def encode_trigger_response(success: bool, message: str) -> bytes:
    """std_srvs/srv/Trigger_Response."""
    return schema.encode("std_srvs/srv/Trigger_Response", (success, message))


def decode_trigger_response(payload: bytes) -> Tuple[bool, str]:
    """(success, message) of a std_srvs/srv/Trigger_Response in CDR
    (ValueError for anything else)."""
    success, message = schema.decode("std_srvs/srv/Trigger_Response", payload)
    return bool(success), str(message)


def encode_trigger_request() -> bytes:
    """std_srvs/srv/Trigger_Request (its one placeholder byte)."""
    return schema.encode("std_srvs/srv/Trigger_Request", (0,))


def check_encapsulation(payload: bytes) -> None:
    """ValueError unless payload starts with a CDR (little- or big-endian) header."""
    if len(payload) < 4 or payload[0] != 0 or payload[1] not in (0, 1):
        raise ValueError("not a CDR payload (bad encapsulation header)")


Vector3StampedFields = Tuple[int, int, str, Tuple[float, float, float]]


def encode_vector3_stamped(sec: int, nanosec: int, frame_id: str,
                           vector: Sequence[float]) -> bytes:
    """geometry_msgs/msg/Vector3Stamped."""
    return schema.encode("geometry_msgs/msg/Vector3Stamped",
                         (((sec, nanosec), frame_id), [float(v) for v in vector]))


def decode_vector3_stamped(payload: bytes) -> Vector3StampedFields:
    """(sec, nanosec, frame_id, (x, y, z)) of a geometry_msgs/msg/Vector3Stamped
    in CDR (little- or big-endian); ValueError, saying what is wrong, for
    anything else (schema.decode)."""
    ((sec, nanosec), frame_id), (x, y, z) = schema.decode(
        "geometry_msgs/msg/Vector3Stamped", payload)
    return sec, nanosec, frame_id, (x, y, z)
