"""rmw_zenoh's layout on Zenoh: key expressions, liveliness tokens, attachments.

Followed: ROS 2 Jazzy Jalisco with rmw_zenoh_cpp 0.2.x (zenoh 1.x), as its
docs/design.md describes it (ros2/rmw_zenoh, sections "Topic and Service name
mapping to Zenoh key expressions", "Graph Cache", "Publishers", "Service
Servers"). See docs/bridge.md for the citations.

- data key:  <domain>/<fully qualified name without the leading />/<dds type>/<RIHS01 hash>
- liveliness token of a node:
    @ros2_lv/<domain>/<zid>/<node id>/<node id>/NN/<enclave>/<namespace>/<node>
  of a publisher (MP), subscription (MS) or service server (SS):
    @ros2_lv/<domain>/<zid>/<node id>/<entity id>/<kind>/<enclave>/<namespace>/<node>/
        <mangled name>/<dds type>/<hash>/<qos>
  where a mangled name has each "/" replaced by "%" and "%" stands for empty.
- attachment of a put, a request and a reply: int64 sequence number and
  int64 source timestamp (ns since the epoch), little-endian, then the GID as
  zenoh's serializer writes a 16-byte array: its length (one LEB128 byte, 16)
  and the 16 bytes; 33 bytes in all.
"""

from __future__ import annotations

import hashlib
import re
import struct
from dataclasses import dataclass
from typing import Tuple

ADMIN_SPACE = "@ros2_lv"
GID_SIZE = 16
#: sequence number, source timestamp (ns), GID length, GID (attachment_helpers.cpp)
ATTACHMENT = struct.Struct("<qqB16s")
ATTACHMENT_SIZE = ATTACHMENT.size  # 33

NODE, PUBLISHER, SERVICE = "NN", "MP", "SS"
SUBSCRIPTION = "MS"

_NAME_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def check_name(name: str, what: str = "name") -> str:
    """A ROS 2 name token (letters, digits, underscores, not starting with a
    digit); ValueError otherwise."""
    if not _NAME_RE.match(name):
        raise ValueError(f"{what} {name!r}: use letters, digits and underscores "
                         "(not starting with a digit)")
    return name


def normalize_namespace(ns: str) -> str:
    """"", "/" -> "/"; "robot1" or "/robot1/" -> "/robot1". ValueError for a bad token."""
    parts = [p for p in ns.strip().split("/") if p]
    for p in parts:
        check_name(p, "namespace part")
    return "/" + "/".join(parts)


def dds_type_name(ros_type: str) -> str:
    """"geometry_msgs/msg/WrenchStamped" -> "geometry_msgs::msg::dds_::WrenchStamped_"."""
    pkg, kind, name = ros_type.split("/")
    return f"{pkg}::{kind}::dds_::{name}_"


def mangle(name: str) -> str:
    """A name with "/" replaced by "%"; the empty name and "/" are "%"."""
    if name in ("", "/"):
        return "%"
    return name.replace("/", "%")


def fully_qualified(namespace: str, *names: str) -> str:
    ns = normalize_namespace(namespace)
    return (ns.rstrip("/") + "/" + "/".join(names)) if names else ns


def data_key(domain: int, fq_name: str, ros_type: str, type_hash: str) -> str:
    """The key a topic's messages (or a service's queries) travel on."""
    return f"{int(domain)}/{fq_name.strip('/')}/{dds_type_name(ros_type)}/{type_hash}"


def qos_keyexpr(reliable: bool = True, depth: int = 10) -> str:
    """rmw_zenoh's compact QoS: <reliability>:<durability>:<history>,<depth>:
    <deadline>:<lifespan>:<liveliness>, each field empty when it is the
    default (reliable, volatile, keep last, infinite durations, automatic).
    Best effort is reliability 2."""
    return ("" if reliable else "2") + f"::,{int(depth)}:,:,:,,"


@dataclass(frozen=True)
class Entity:
    """One ROS 2 graph entity and the strings rmw_zenoh derives from it."""

    domain: int
    zid: str  # the Zenoh session id as text
    node_id: int
    entity_id: int
    kind: str  # NN, MP, MS or SS
    namespace: str  # normalized, "/" when none
    node: str
    name: str = ""  # fully qualified topic or service name
    ros_type: str = ""
    type_hash: str = ""
    qos: str = ""

    def token(self) -> str:
        head = (f"{ADMIN_SPACE}/{self.domain}/{self.zid}/{self.node_id}/{self.entity_id}/"
                f"{self.kind}/%/{mangle(self.namespace)}/{self.node}")
        if self.kind == NODE:
            return head
        return (f"{head}/{mangle(self.name)}/{dds_type_name(self.ros_type)}/"
                f"{self.type_hash}/{self.qos}")

    def key(self) -> str:
        return data_key(self.domain, self.name, self.ros_type, self.type_hash)

    def gid(self) -> bytes:
        """16 bytes naming this entity: here the first 16 bytes of the SHA-256
        of its liveliness token (rmw_zenoh hashes the token too; subscribers
        only compare GIDs)."""
        return hashlib.sha256(self.token().encode()).digest()[:GID_SIZE]


def attachment(sequence_number: int, source_timestamp_ns: int, gid: bytes) -> bytes:
    """The 33-byte attachment of a put, a request or a reply."""
    if len(gid) != GID_SIZE:
        raise ValueError("a GID is 16 bytes")
    return ATTACHMENT.pack(sequence_number, source_timestamp_ns, GID_SIZE, gid)


def parse_attachment(data: bytes) -> Tuple[int, int, bytes]:
    """(sequence number, source timestamp ns, GID); ValueError when malformed."""
    if len(data) != ATTACHMENT_SIZE:
        raise ValueError(f"attachment is {len(data)} bytes, not {ATTACHMENT_SIZE}")
    seq, ts, n, gid = ATTACHMENT.unpack(data)
    if n != GID_SIZE:
        raise ValueError(f"attachment GID length {n}, not {GID_SIZE}")
    return seq, ts, gid
