"""The one interface every transport of the bridge implements.

A transport (Zenoh in rmw_zenoh's layout: zenoh_transport.py; DDS: dds.py;
Foxglove live: foxglove_out.py; an MCAP file: mcap_out.py) carries the
topics, services and inputs of the bridge's nodes. The node's logic
(node.py: the topics per sensor, diagnostics, tare and untare with the
one-at-a-time and busy rule, the gravity input, limits, read-only, who asked)
is written once over this interface; each transport only moves bytes:

- advertise(endpoint) -> Publisher: publish() serialized messages (CDR,
  encapsulation header first), `listening` says whether anyone receives them
  now (Zenoh's matching status, DDS matched readers, Foxglove subscriptions,
  an MCAP file while recording); the node serializes and publishes a topic
  only while it is True;
- serve(endpoint, on_request): a service; each request reaches on_request as
  a Request (the request message in CDR, who asked) that is answered once,
  with reply(bytes) or refuse(why), from any thread, at once or later;
- take(endpoint, on_payload): an input topic; each message's bytes go to
  on_payload(payload, refuse) where refuse is a reason the transport already
  has to refuse it ("" when none);
- ready() after every node declared its endpoints; close().
"""

from __future__ import annotations

import abc
from dataclasses import dataclass
from typing import Callable, List, Sequence, Tuple


@dataclass(frozen=True)
class NodeRef:
    """A ROS 2 node of the bridge: its namespace (normalized, "/" for none),
    its name and the number the bridge gave it (rmw_zenoh's node id)."""

    namespace: str
    name: str
    node_id: int


@dataclass(frozen=True)
class Endpoint:
    """A topic or service of a node: fully qualified name, ROS type
    ("geometry_msgs/msg/WrenchStamped", "std_srvs/srv/Trigger"), the entity id
    the bridge gave it, its QoS depth."""

    node: NodeRef
    name: str
    ros_type: str
    entity_id: int
    qos_depth: int = 10


class Publisher(abc.ABC):
    """One topic on one transport."""

    @property
    @abc.abstractmethod
    def listening(self) -> bool:
        """Whether anyone receives this topic now (cheap: read per batch)."""

    @abc.abstractmethod
    def publish(self, payloads: Sequence[bytes], stamps: Sequence[int], now_ns: int) -> None:
        """Messages (CDR) with their stamps (ns) and the time of publication (ns)."""

    def close(self) -> None:  # noqa: B027 (optional: most publishers go with their transport)
        """Withdraw the topic (default: nothing to do)."""


class Request(abc.ABC):
    """A service request as a transport received it.

    payload: the request message in CDR (the transport's own addressing taken
    off); requester: who asked, as the transport can tell ("zenoh client
    <gid>", "dds client <guid>", "foxglove client <id>"); error: set by the
    transport when the request cannot be read (the node counts and refuses it).
    Answered once, by reply() or refuse(), from any thread."""

    payload: bytes = b""
    requester: str = ""
    error: str = ""

    @abc.abstractmethod
    def reply(self, payload: bytes) -> None:
        """Send the response message (CDR)."""

    @abc.abstractmethod
    def refuse(self, why: str) -> None:
        """A malformed request: say why where the transport can (an error
        reply), or drop it where it cannot."""


class CommandRequest(Request):
    """A sample of a command topic (std_msgs/msg/Empty on a service's name):
    a request nobody can be answered for."""

    def __init__(self, payload: bytes, requester: str) -> None:
        self.payload = payload
        self.requester = requester

    def reply(self, payload: bytes) -> None:
        return None

    def refuse(self, why: str) -> None:
        return None


#: on_payload(payload, refuse) of an input: refuse is "" or why the transport refuses it
InputHandler = Callable[[bytes, str], None]


class Transport(abc.ABC):
    """A transport of the bridge (see the module's docstring)."""

    #: short name, in logs and diagnostics ("zenoh", "dds", "foxglove", "mcap")
    name: str = ""
    #: whether this transport also offers each service as a command topic
    #: (std_msgs/msg/Empty on the service's name: DDS, for any DDS middleware)
    command_topics: bool = False
    #: whether it takes services and inputs at all (MCAP: no)
    interactive: bool = True

    def declare_node(self, node: NodeRef) -> None:  # noqa: B027 (optional: Zenoh, DDS only)
        """A node before its endpoints (default: nothing to declare)."""

    @abc.abstractmethod
    def advertise(self, endpoint: Endpoint) -> Publisher:
        """A topic the node publishes."""

    def serve(self, endpoint: Endpoint, on_request: Callable[[Request], None]) -> None:
        """A service: on_request(request) for each request, in the
        transport's thread (it must return soon: the node answers later)."""
        raise NotImplementedError(f"{self.name}: no services")

    def take(self, endpoint: Endpoint, on_payload: InputHandler) -> None:
        """An input topic: on_payload(bytes, refuse) for each message, in the
        transport's thread (it must not raise)."""
        raise NotImplementedError(f"{self.name}: no inputs")

    def ready(self) -> None:  # noqa: B027 (optional: DDS, Foxglove only)
        """Every node declared (default: nothing to do)."""

    def diagnostics(self, node: NodeRef) -> List[Tuple[str, str]]:
        """Key/values this transport adds to a node's diagnostics."""
        return []

    @abc.abstractmethod
    def close(self) -> None:
        """Withdraw everything; idempotent."""
