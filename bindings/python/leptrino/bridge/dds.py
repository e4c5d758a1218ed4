"""ROS 2 on DDS: the bridge's topics as a ROS 2 node on Cyclone DDS would
publish them, for ROS 2 nodes on Fast DDS (rmw_fastrtps_cpp, the default
middleware) and Cyclone DDS (rmw_cyclonedds_cpp). Needs the PyPI
`cyclonedds` package (the "bridge" extra).

The conventions (docs/bridge.md, "DDS", cites the sources):
- topic names: "rt" + the ROS name ("rt/cell/a/wrench"); type names: the
  ROS type as package::msg::dds_::Type_, every nested type alike; keyless;
- data: XCDR1 little-endian (encapsulation 00 01 00 00), the very payload
  the bridge puts on Zenoh and in MCAP (serialized in C for the wrench
  topics); writers RELIABLE, VOLATILE, KEEP_LAST(10);
- USER_DATA: "enclave=/;" on the participant, "typehash=RIHS01_...;" on each
  writer and reader;
- the nodes announced on "ros_discovery_info"
  (rmw_dds_common/msg/ParticipantEntitiesInfo; the Gid is 16 bytes from Iron
  on, 24 in Humble: --ros-distro);
- tare/untare: a `NAME/tare` and a `NAME/untare` topic (std_msgs/msg/Empty)
  that any DDS middleware can publish to, and the same names as
  std_srvs/srv/Trigger services in rmw_cyclonedds' mapping (TriggerService:
  rq/NAMERequest, rr/NAMEReply, a 16-byte request header echoed in the
  reply); rmw_fastrtps' services cannot be served (docs/bridge.md says why);
- inputs (`NAME/gravity`, geometry_msgs/msg/Vector3Stamped): a reader whose
  samples are taken as the bytes received and checked by the bridge
  (subscription()), never trusted to deserialize.
"""

from __future__ import annotations

import logging
import os
import struct
import threading
import time
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

from . import cdr
from .commands import CommandRunner
from .ratelog import RateLimitedLog
from .transport import CommandRequest, Endpoint, InputHandler, NodeRef, Publisher, Request, \
    Transport
from .typehash import rihs01

TRIGGER = "std_srvs/srv/Trigger"
EMPTY = "std_msgs/msg/Empty"
WRENCH_STAMPED = "geometry_msgs/msg/WrenchStamped"
VECTOR3_STAMPED = "geometry_msgs/msg/Vector3Stamped"
DIAGNOSTIC_ARRAY = "diagnostic_msgs/msg/DiagnosticArray"

log = logging.getLogger("leptrino.bridge")

#: --ros-distro: the Gid length of rmw_dds_common/msg/Gid in that release.
GID_LENGTH = {"humble": 24, "jazzy": 16, "kilted": 16, "rolling": 16}


def topic_name(fq_name: str) -> str:
    """/cell/a/wrench -> rt/cell/a/wrench (ROS topic prefix "rt")."""
    return "rt" + fq_name


def config_xml(interface: Optional[str]) -> Optional[str]:
    """Cyclone DDS configuration restricting it to one interface address,
    with no multicast and that address as its unicast peer (None: no
    restriction). Combined with CYCLONEDDS_URI by domain_config()."""
    if interface is None:
        return None
    import ipaddress

    ipaddress.ip_address(interface)  # ValueError for a name that is not an address
    return ("<CycloneDDS><Domain Id=\"any\"><General><Interfaces>"
            f"<NetworkInterface address=\"{interface}\"/></Interfaces>"
            "<AllowMulticast>false</AllowMulticast></General>"
            f"<Discovery><ParticipantIndex>auto</ParticipantIndex>"
            "<MaxAutoParticipantIndex>60</MaxAutoParticipantIndex>"
            f"<Peers><Peer address=\"{interface}\"/></Peers></Discovery>"
            "</Domain></CycloneDDS>")


#: Cyclone's compatibility with Fast DDS 3 (Kilted's rmw_fastrtps): match
#: eProsima's (vendor id 1.15) endpoints by type name, ignoring the XTypes
#: TypeInformation they send, whose TypeObjects of types with sequences of
#: structs (DiagnosticArray, ParticipantEntitiesInfo) Cyclone rejects as
#: invalid: without it Kilted's nodes see no diagnostics and no node list
#: (docs/ros2-rmw-notes.md; eclipse-cyclonedds/cyclonedds#2333).
COMPAT_XML = ("<CycloneDDS><Domain Id=\"any\"><Compatibility>"
              "<IgnoreTypeInformation>1.15</IgnoreTypeInformation>"
              "</Compatibility></Domain></CycloneDDS>")


def domain_config(interface: Optional[str]) -> str:
    """The configuration given to the domain: COMPAT_XML, then
    CYCLONEDDS_URI (files or XML, comma-separated, as Cyclone reads it), then
    --dds-interface's fragment; a later one wins where they overlap, so a
    user's CYCLONEDDS_URI can still set Compatibility otherwise."""
    parts = [COMPAT_XML, os.environ.get("CYCLONEDDS_URI", "").strip(), config_xml(interface)]
    return ",".join(p for p in parts if p)


@dataclass
class DdsOptions:
    """How the DDS participant is made."""

    interface: Optional[str] = None  # --dds-interface ADDR
    distro: str = "jazzy"  # --ros-distro: the Gid layout of ros_discovery_info
    impl: str = "auto"  # --dds-impl: rclpy, cyclone, or auto (rclpy when it imports)


#: --dds-impl's choices
IMPLS = ("auto", "rclpy", "cyclone")
RCLPY_HINT = ("a ROS 2 installation (source its setup), or the PyPI wheels: "
              "pip install \"leptrino[bridge,ros-jazzy]\" (or ros-kilted; x86_64, CPython 3.11)")


def choose_impl(opts: DdsOptions) -> Tuple[str, str]:
    """The DDS transport --dds runs: ("rclpy" or "cyclone", why). auto: rclpy
    when it and the message packages import and the options suit it (a
    --dds-interface address rclpy can honour: loopback), else Cyclone.
    ValueError for an impl asked for that cannot run."""
    if opts.impl not in IMPLS:
        raise ValueError(f"--dds-impl {opts.impl!r}: one of {', '.join(IMPLS)}")
    if opts.impl == "cyclone":
        return "cyclone", "--dds-impl cyclone"
    from .rclpy_transport import interface_env, unavailable

    missing = unavailable()
    if opts.impl == "rclpy":
        if missing:
            raise ValueError(f"--dds-impl rclpy: cannot import {missing}; needs {RCLPY_HINT}")
        interface_env(opts.interface)  # ValueError: not an address rclpy can honour
        return "rclpy", "--dds-impl rclpy"
    if missing:
        return "cyclone", f"rclpy not available ({missing})"
    try:
        interface_env(opts.interface)
    except ValueError:
        return "cyclone", f"--dds-interface {opts.interface} is not a loopback address"
    return "rclpy", "rclpy imports"


class _Types:
    """The DDS types, made from the one description of each message
    (schema.idl_types), named as rosidl names them for DDS. rmw_cyclonedds'
    request header (the client's writer instance handle, the request's
    sequence number) is put before the fields of a service's request and
    reply: the request/reply addressing, here and in split_request /
    reply_payload only."""

    def __init__(self, gid_len: int) -> None:
        from . import schema
        from .typehash import parse_fields

        header = parse_fields("uint64 client_guid\nint64 sequence_number\n", "std_srvs")
        by_ros = schema.idl_types(
            [WRENCH_STAMPED, DIAGNOSTIC_ARRAY, EMPTY, VECTOR3_STAMPED, TRIGGER + "_Request",
             TRIGGER + "_Response", "rmw_dds_common/msg/ParticipantEntitiesInfo"],
            overrides={"rmw_dds_common/msg/Gid": f"char[{gid_len}] data\n"},
            extra_fields={TRIGGER + "_Request": header, TRIGGER + "_Response": header})
        self.by_ros: Dict[str, Any] = by_ros
        self.WrenchStamped = by_ros[WRENCH_STAMPED]
        self.Empty = by_ros[EMPTY]
        self.TriggerRequest = by_ros[TRIGGER + "_Request"]
        self.TriggerResponse = by_ros[TRIGGER + "_Response"]
        self.ParticipantEntitiesInfo = by_ros["rmw_dds_common/msg/ParticipantEntitiesInfo"]
        # the nested types, made with it
        ann = self.ParticipantEntitiesInfo.__annotations__
        self.Gid = ann["gid"]
        self.NodeEntitiesInfo = _element(ann["node_entities_info_seq"])


def _element(seq_type: Any) -> Any:
    """The element type of a cyclonedds types.sequence[T]."""
    return seq_type.__metadata__[0].subtype


class DdsWriter(Publisher):
    """One ROS 2 publisher on DDS: writes payloads already in CDR (the
    bridge's bytes) without making a Python sample of them; `listening`
    while it has matched readers (publication_matched)."""

    def __init__(self, dds: DdsTransport, fq_name: str, ros_type: str) -> None:
        from cyclonedds._clayer import ddspy_write
        from cyclonedds.core import Listener
        from cyclonedds.pub import DataWriter
        from cyclonedds.topic import Topic

        self.matched = 0
        self.topic: Any = Topic(dds.participant, topic_name(fq_name), dds.types.by_ros[ros_type],
                                qos=dds.topic_qos())
        self.writer: Any = DataWriter(
            dds.participant, self.topic, qos=dds.endpoint_qos(rihs01(ros_type), reliable=True),
            listener=Listener(on_publication_matched=self._on_matched))
        self.gid = self.writer.guid.bytes
        self._ref = self.writer._ref
        self._write = ddspy_write

    def _on_matched(self, _writer: Any, status: Any) -> None:
        self.matched = int(status.current_count)

    @property
    def listening(self) -> bool:
        return self.matched > 0

    def publish(self, payloads: Sequence[bytes], stamps: Sequence[int], now_ns: int) -> None:
        write, ref = self._write, self._ref
        for p in payloads:
            rc = write(ref, p if not len(p) & 3 else pad4(p))
            if rc < 0:
                log.debug("dds write: %d", rc)

    def close(self) -> None:
        self.writer = None
        self.topic = None


def pad4(payload: bytes) -> bytes:
    """A serialized sample padded to a multiple of 4 bytes, as Cyclone's
    Python writer pads its own."""
    return payload + b"\x00" * (-len(payload) % 4)


class DdsTransport(Transport):
    """The bridge's one DDS participant (domain, USER_DATA enclave=/;), its
    ros_discovery_info writer (the nodes and their endpoints), its writers,
    readers and services. Services are also offered as command topics
    (std_msgs/msg/Empty on the service's name) that any DDS middleware can
    publish to."""

    name = "dds"
    command_topics = True

    def __init__(self, domain: int, opts: DdsOptions) -> None:
        from cyclonedds.core import Qos
        from cyclonedds.domain import Domain, DomainParticipant
        from cyclonedds.qos import Policy

        if opts.distro not in GID_LENGTH:
            raise ValueError(f"--ros-distro {opts.distro!r}: one of {', '.join(GID_LENGTH)}")
        self.Policy = Policy
        self.Qos = Qos
        self.types = _Types(GID_LENGTH[opts.distro])
        self.gid_len = GID_LENGTH[opts.distro]
        cfg = domain_config(opts.interface)
        try:
            self._domain = Domain(domain, cfg)
            self.participant: Any = DomainParticipant(domain,
                                                      qos=Qos(Policy.Userdata(b"enclave=/;")))
        except Exception as e:  # cyclonedds' DDSException: a bad configuration, no interface
            raise OSError(f"DDS domain {domain}: {e}") from None
        self._nodes: Dict[Tuple[str, str], Tuple[List[bytes], List[bytes]]] = {}
        self._lock = threading.Lock()
        self._readers: List[Any] = []
        self._writers: List[DdsWriter] = []
        self._services: Dict[Tuple[str, str], List[TriggerService]] = {}
        # replies waiting for the client's reply reader to match (at most 1 s each)
        self.replies = CommandRunner("bridge-dds-replies", 64)
        self._service_ids = 0
        from cyclonedds.pub import DataWriter
        from cyclonedds.topic import Topic

        info_qos = Qos(Policy.Reliability.Reliable(0), Policy.Durability.TransientLocal,
                       Policy.History.KeepLast(1),
                       Policy.DataRepresentation(use_cdrv0_representation=True))
        self._info_topic = Topic(self.participant, "ros_discovery_info",
                                 self.types.ParticipantEntitiesInfo, qos=info_qos)
        self._info_writer: Any = DataWriter(self.participant, self._info_topic, qos=info_qos)

    def topic_qos(self) -> Any:
        P = self.Policy
        return self.Qos(P.DataRepresentation(use_cdrv0_representation=True))

    def endpoint_qos(self, typehash: str, reliable: bool, user_data: str = "") -> Any:
        """user_data: more "key=value;" pairs put before the type hash."""
        P = self.Policy
        rel = P.Reliability.Reliable(100_000_000) if reliable else P.Reliability.BestEffort
        return self.Qos(rel, P.Durability.Volatile, P.History.KeepLast(10),
                        P.DataRepresentation(use_cdrv0_representation=True),
                        P.Userdata(f"{user_data}typehash={typehash};".encode()))

    def gid(self, guid16: bytes) -> Any:
        return self.types.Gid(data=list(guid16) + [0] * (self.gid_len - 16))

    def _entities(self, node: NodeRef) -> Tuple[List[bytes], List[bytes]]:
        """(reader GIDs, writer GIDs) of a node, for ros_discovery_info (under _lock)."""
        return self._nodes.setdefault((node.namespace, node.name), ([], []))

    def declare_node(self, node: NodeRef) -> None:
        with self._lock:
            self._entities(node)

    def advertise(self, endpoint: Endpoint) -> Publisher:
        w = DdsWriter(self, endpoint.name, endpoint.ros_type)
        with self._lock:
            self._writers.append(w)
            self._entities(endpoint.node)[1].append(w.gid)
        return w

    def _raw_reader(self, fq_name: str, ros_type: str, topic_prefix: str,
                    on_sample: Callable[[Any, bytes, Any], None], qos: Any,
                    on_matched: Optional[Callable[[Any, Any], None]] = None) -> Any:
        """A reader whose samples are taken as bytes (never deserialized by
        Cyclone into Python objects): on_sample(reader, bytes, info) for each
        valid one, in Cyclone's listener thread, until the reader is empty."""
        from cyclonedds._clayer import ddspy_take
        from cyclonedds.core import InstanceState, Listener, SampleState, ViewState
        from cyclonedds.sub import DataReader
        from cyclonedds.topic import Topic

        mask = SampleState.Any | ViewState.Any | InstanceState.Any

        def on_data(reader: Any) -> None:
            while True:
                taken = ddspy_take(reader._ref, mask, 16)
                if isinstance(taken, int):  # an error code
                    log.debug("dds take %s: %d", fq_name, taken)
                    return
                if not taken:
                    return
                for data, info in taken:
                    if info.valid_data:
                        on_sample(reader, bytes(data), info)

        topic = Topic(self.participant, topic_prefix + fq_name, self.types.by_ros[ros_type],
                      qos=self.topic_qos())
        listener = (Listener(on_data_available=on_data) if on_matched is None else
                    Listener(on_data_available=on_data, on_subscription_matched=on_matched))
        reader = DataReader(self.participant, topic, qos=qos, listener=listener)
        self._readers.append((topic, reader))
        return reader

    def take(self, endpoint: Endpoint, on_payload: InputHandler) -> None:
        """A ROS 2 subscription: each sample's serialized bytes (encapsulation
        header first) go to on_payload, which checks them. Best effort, so
        that reliable and best-effort publishers both match."""
        reader = self._raw_reader(
            endpoint.name, endpoint.ros_type, "rt",
            lambda _r, data, _i: on_payload(data, ""),
            self.endpoint_qos(rihs01(endpoint.ros_type), reliable=False))
        with self._lock:
            self._entities(endpoint.node)[0].append(reader.guid.bytes)

    def serve(self, endpoint: Endpoint, on_request: Callable[[Request], None]) -> None:
        """The service in rmw_cyclonedds' mapping (TriggerService) and its
        command topic (std_msgs/msg/Empty on the same name; a sample is a
        request nobody can be answered for: requester "dds writer <GUID>")."""
        svc = TriggerService(self, endpoint.name, on_request, self._next_service_id())

        def on_command(reader: Any, data: bytes, info: Any) -> None:
            on_request(CommandRequest(data, f"dds writer {_writer_guid(reader, info)}"))

        reader = self._raw_reader(endpoint.name, EMPTY, "rt", on_command,
                                  self.endpoint_qos(rihs01(EMPTY), reliable=False))
        with self._lock:
            self._services.setdefault((endpoint.node.namespace, endpoint.node.name),
                                      []).append(svc)
            readers, writers = self._entities(endpoint.node)
            readers += [reader.guid.bytes, svc.reader.guid.bytes]
            writers.append(svc.writer.guid.bytes)

    def diagnostics(self, node: NodeRef) -> List[Tuple[str, str]]:
        """dds_headerless_clients: matched clients whose requests cannot be
        answered (no rmw_cyclonedds request header: TriggerService)."""
        svcs = self._services.get((node.namespace, node.name), [])
        values = [("dds_impl", "cyclone")]
        if svcs:
            values.append(("dds_headerless_clients",
                           str(sum(s.headerless_clients for s in svcs))))
        return values

    def _next_service_id(self) -> str:
        """A client/service id as rmw_cyclonedds makes one: the participant's
        GUID prefix (12 bytes) then a counter (4 bytes, big-endian), in hex
        bytes joined by dots (the pair's USER_DATA `serviceid=`)."""
        with self._lock:
            self._service_ids += 1
            n = self._service_ids
        raw = self.participant.guid.bytes[:12] + n.to_bytes(4, "big")
        return ".".join(f"{b:x}" for b in raw)

    def ready(self) -> None:
        """Publish the nodes on ros_discovery_info (after every endpoint is made)."""
        T = self.types
        with self._lock:
            infos = [T.NodeEntitiesInfo(node_namespace=ns, node_name=name,
                                        reader_gid_seq=[self.gid(g) for g in readers],
                                        writer_gid_seq=[self.gid(g) for g in writers])
                     for (ns, name), (readers, writers) in self._nodes.items()]
        self._info_writer.write(T.ParticipantEntitiesInfo(
            gid=self.gid(self.participant.guid.bytes), node_entities_info_seq=infos))

    announce = ready

    def close(self) -> None:
        """Withdraw the nodes (an empty announcement), then delete everything."""
        if self.participant is None:
            return
        try:
            T = self.types
            self._info_writer.write(T.ParticipantEntitiesInfo(
                gid=self.gid(self.participant.guid.bytes), node_entities_info_seq=[]))
        except Exception:
            pass
        self.replies.stop()
        self._readers = []
        for w in self._writers:
            w.close()
        self._writers = []
        self._services = {}
        self._info_writer = None
        self.participant = None
        self._domain = None


DdsParticipant = DdsTransport  # the name before the transport interface


def _writer_guid(reader: Any, info: Any) -> str:
    """The GUID of the writer of a sample taken from reader (info: its
    SampleInfo; "unknown" when the writer is gone already)."""
    try:
        ep = reader.get_matched_publication_data(info.publication_handle)
        return str(ep.key) if ep is not None else "unknown"
    except Exception:
        return "unknown"


#: Bytes of rmw_cyclonedds' request header: the client's writer instance
#: handle (uint64) and the request's sequence number (int64), right after the
#: 4-byte encapsulation header (serdata.hpp cdds_request_header_t).
REQUEST_HEADER_SIZE = 16


def parse_user_data(data: bytes) -> Dict[str, str]:
    """USER_DATA "key=value;key=value;" (as rmw_dds_common and rmw_cyclonedds
    write it) -> {key: value}; anything else is skipped."""
    out: Dict[str, str] = {}
    for item in data.decode("utf-8", "replace").split(";"):
        key, sep, value = item.partition("=")
        if sep and key:
            out[key] = value
    return out


# -- request/reply addressing: rmw_cyclonedds' request header (all of it here) --

def split_request(payload: bytes) -> Tuple[int, int, bytes]:
    """A request as rmw_cyclonedds sends it -> (client guid, sequence number,
    the request message in CDR: encapsulation header and body). ValueError
    when it is not CDR or too short for the header."""
    if len(payload) < 4 or payload[0] != 0 or payload[1] not in (0, 1):
        raise ValueError("not a CDR payload (bad encapsulation header)")
    if len(payload) < 4 + REQUEST_HEADER_SIZE:
        raise ValueError(f"{len(payload) - 4} bytes after the encapsulation header: no room "
                         "for a request header")
    guid, seq = struct.unpack_from("<Qq" if payload[1] == 1 else ">Qq", payload, 4)
    return guid, seq, payload[:4] + payload[4 + REQUEST_HEADER_SIZE:]


def reply_payload(guid: int, seq: int, response: bytes) -> bytes:
    """The reply to a request: rmw_cyclonedds' header (the request's guid and
    sequence number) then the response message (CDR little-endian, its
    encapsulation header first). The header is 16 bytes, so the response's
    fields keep their alignment."""
    return pad4(response[:4] + struct.pack("<Qq", guid, seq) + response[4:])


def parse_trigger_request(payload: bytes) -> Tuple[int, int]:
    """An rmw_cyclonedds std_srvs/srv/Trigger request -> (client guid, sequence
    number). ValueError for anything else: not CDR, no room for the header
    (a request without it, as rmw_fastrtps sends), a wrong length."""
    guid, seq, body = split_request(payload)
    # Trigger_Request's one byte, at most 3 bytes of padding
    if not 1 <= len(body) - 4 <= 4:
        raise ValueError(f"{len(payload) - 4} bytes after the encapsulation header, expected "
                         f"{REQUEST_HEADER_SIZE + 1} (a request header and the request)")
    return guid, seq


def encode_trigger_reply(guid: int, seq: int, success: bool, message: str) -> bytes:
    """The reply to a Trigger request (reply_payload of Trigger_Response)."""
    return reply_payload(guid, seq, cdr.encode_trigger_response(success, message))


class _ServiceRequest(Request):
    """A request taken by a TriggerService; reply() writes the reply with the
    request's header once the client's reply reader is matched (at once when
    it is, else from the transport's reply thread, waiting at most
    TriggerService.MATCH_WAIT_S)."""

    def __init__(self, svc: TriggerService, raw: bytes, writer_handle: int) -> None:
        self._svc = svc
        self._handle = writer_handle
        self.guid = self.seq = 0
        try:
            self.guid, self.seq = parse_trigger_request(raw)
            self.payload = raw[:4] + raw[4 + REQUEST_HEADER_SIZE:]
        except ValueError as e:
            self.error = str(e)
        self.requester = f"dds client {self.guid:016x}"

    def reply(self, payload: bytes) -> None:
        svc, data = self._svc, reply_payload(self.guid, self.seq, payload)
        if svc.client_reader_matched(self._handle):
            svc.write(data, self.seq)
        elif not svc.replies.submit(svc.name, lambda: svc.write_when_matched(
                data, self.seq, self._handle)):
            svc.write(data, self.seq)  # too many waiting: write it now

    def refuse(self, why: str) -> None:
        return None  # rmw_cyclonedds has no error reply: the request is dropped


class TriggerService:
    """A std_srvs/srv/Trigger service as rmw_cyclonedds maps it (see
    docs/bridge.md): a reader of `rq<name>Request` and a writer of
    `rr<name>Reply`, RELIABLE, VOLATILE, KEEP_LAST(10) (ROS 2's services
    profile), USER_DATA `serviceid=<id>;typehash=<Trigger's>;` on both.

    Each request is taken raw and handed to on_request (the node checks it,
    answers or refuses it); the reply carries the request's header, and is
    written once the client's reply reader (the reader with the request
    writer's `clientid`) is matched, or after MATCH_WAIT_S.

    A request shorter than the request type (no header: rmw_fastrtps') never
    reaches the bridge: Cyclone drops it while deserializing, with a line of
    its own. So a matched request writer without a `clientid` (rmw_fastrtps'
    clients have none) is counted in headerless_clients and logged, pointing
    to the command topic."""

    MATCH_WAIT_S = 1.0

    def __init__(self, dds: DdsTransport, fq_name: str,
                 on_request: Callable[[Request], None], service_id: str) -> None:
        from cyclonedds._clayer import ddspy_write
        from cyclonedds.pub import DataWriter
        from cyclonedds.topic import Topic

        self.name = fq_name
        self.replies = dds.replies
        self._Userdata = dds.Policy.Userdata
        self._write = ddspy_write
        self._client_log = RateLimitedLog()
        self.headerless_clients = 0
        qos = dds.endpoint_qos(rihs01(TRIGGER), reliable=True,
                               user_data=f"serviceid={service_id};")
        self.reply_topic = Topic(dds.participant, f"rr{fq_name}Reply",
                                 dds.types.TriggerResponse, qos=dds.topic_qos())
        self.writer = DataWriter(dds.participant, self.reply_topic, qos=qos)
        self.reader = dds._raw_reader(
            fq_name + "Request", TRIGGER + "_Request", "rq",
            lambda _r, data, info: on_request(
                _ServiceRequest(self, data, info.publication_handle)), qos,
            on_matched=self._on_match)

    def _on_match(self, _reader: Any, status: Any) -> None:
        if status.current_count_change <= 0:
            return
        try:
            ep = self.reader.get_matched_publication_data(status.last_publication_handle)
        except Exception:  # gone already
            return
        if ep is None or "clientid" in parse_user_data(self._user_data(ep)):
            return
        self.headerless_clients += 1
        self._client_log.warning(
            "%s: a client without rmw_cyclonedds' request header (rmw_fastrtps?) matched; "
            "its requests cannot be answered: it can publish std_msgs/msg/Empty on the "
            "topic %s instead", self.name, self.name)

    def write(self, data: bytes, seq: int) -> None:
        rc = self._write(self.writer._ref, data)
        if rc < 0:
            log.info("%s: reply to request %d not written (%d)", self.name, seq, rc)

    def write_when_matched(self, data: bytes, seq: int, writer_handle: int) -> None:
        end = time.monotonic() + self.MATCH_WAIT_S
        while not self.client_reader_matched(writer_handle) and time.monotonic() < end:
            time.sleep(0.01)
        self.write(data, seq)

    def client_reader_matched(self, writer_handle: int) -> bool:
        """Whether the reply writer has matched the requesting client's reply
        reader (by its USER_DATA clientid, as rmw_cyclonedds checks); a
        client without a clientid is taken as matched."""
        try:
            ep = self.reader.get_matched_publication_data(writer_handle)
        except Exception:  # the client's writer is gone
            return True
        clientid = parse_user_data(self._user_data(ep)).get("clientid") if ep else None
        if clientid is None:
            return True
        try:
            for h in self.writer.get_matched_subscriptions():
                sub = self.writer.get_matched_subscription_data(h)
                if sub is not None and parse_user_data(
                        self._user_data(sub)).get("clientid") == clientid:
                    return True
        except Exception:
            return True
        return False

    def _user_data(self, ep: Any) -> bytes:
        try:
            return bytes(ep.qos[self._Userdata].data)
        except Exception:  # no USER_DATA
            return b""
