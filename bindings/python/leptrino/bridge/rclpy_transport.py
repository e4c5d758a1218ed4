"""ROS 2 on DDS through rclpy: the bridge's nodes as real ROS 2 nodes on the
rmw rclpy loads (RMW_IMPLEMENTATION; rmw_fastrtps_cpp when unset, the
default middleware), so that services, the node list and type matching are
the rmw's own on every distribution (docs/ros2-rmw-notes.md: on Jazzy and
Kilted the Cyclone path cannot answer rmw_fastrtps' service calls, and on
Kilted it needs IgnoreTypeInformation for diagnostics and the node list).

Needs rclpy and the message packages of the types the bridge speaks
(geometry_msgs, diagnostic_msgs, std_srvs, std_msgs): a ROS 2 installation,
or the PyPI wheels of the "ros-jazzy" / "ros-kilted" extras (x86_64).
`--dds` takes this transport when they import (`--dds-impl auto`), else the
Cyclone transport (dds.py); `--dds-impl rclpy|cyclone` forces either.

- a Context of its own (the --domain id; SignalHandlerOptions.NO: the
  bridge keeps its SIGINT/SIGTERM handling), one rclpy node per sensor
  (no parameter services, no /rosout: the bridge logs through Python);
- publishers RELIABLE, VOLATILE, KEEP_LAST(depth), fed the bridge's CDR bytes
  as they are (Publisher.publish(bytes) is rcl's serialized publish in
  rclpy's Jazzy and Kilted sources); `listening` is get_subscription_count();
- tare/untare: std_srvs/srv/Trigger services in a reentrant callback group of
  a multi-threaded executor, so that while one request is served (in the
  node's request thread) another is answered busy at once; and the
  std_msgs/msg/Empty command topic on the same name, as on Cyclone;
- inputs (gravity) and command topics: raw subscriptions (bytes, checked by
  the node), best effort so that reliable and best-effort publishers match;
- who asked: rclpy hands a service callback no client id (the request header
  stays in the executor), so a service request is "rclpy client of NAME";
  a command topic's sample names its publisher's GID where rclpy gives it
  (Kilted's MessageInfo has publisher_gid, Jazzy's has not).
- close(): requests still waiting are answered, publishers withdrawn (under
  their lock: nothing publishes on a destroyed one), the executor shut down,
  the nodes destroyed, then the context shut down.
"""

from __future__ import annotations

import importlib
import ipaddress
import logging
import os
import threading
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

from . import cdr
from .transport import CommandRequest, Endpoint, InputHandler, NodeRef, Publisher, Request, \
    Transport

log = logging.getLogger("leptrino.bridge")

TRIGGER = "std_srvs/srv/Trigger"
EMPTY = "std_msgs/msg/Empty"
#: The modules the transport imports: rclpy and the message packages.
MODULES = ("rclpy", "std_srvs.srv", "std_msgs.msg", "geometry_msgs.msg", "diagnostic_msgs.msg")
#: How long a service callback waits for the node's answer (a tare takes at
#: most 3 s; beyond this the client is answered that none came).
ANSWER_WAIT_S = 10.0


def unavailable() -> str:
    """"" when rclpy and the message packages import, else why not."""
    for m in MODULES:
        try:
            importlib.import_module(m)
        except Exception as e:  # ImportError, or a ROS library that fails to load
            return f"{m}: {e}"
    return ""


def interface_env(interface: Optional[str]) -> Dict[str, str]:
    """--dds-interface for rclpy: a loopback address is ROS 2's own
    localhost-only discovery (ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST from
    Iron on, ROS_LOCALHOST_ONLY=1 before: rclpy < 4); another address cannot
    be given to the rmw from here (ValueError: its own configuration does it)."""
    if interface is None:
        return {}
    if not ipaddress.ip_address(interface).is_loopback:
        raise ValueError(f"--dds-interface {interface}: through rclpy only a loopback address "
                         "(localhost-only discovery); restrict another interface in the rmw's "
                         "configuration (FASTRTPS_DEFAULT_PROFILES_FILE, CYCLONEDDS_URI) or use "
                         "--dds-impl cyclone")
    try:
        from importlib.metadata import version

        major = int(version("rclpy").split(".")[0])
    except Exception:  # no metadata: taken as a current release
        major = 99
    if major < 4:  # Humble
        return {"ROS_LOCALHOST_ONLY": "1"}
    return {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}


def _ros_class(ros_type: str) -> Any:
    """geometry_msgs/msg/WrenchStamped -> the rosidl Python class."""
    pkg, kind, name = ros_type.split("/")
    return getattr(importlib.import_module(f"{pkg}.{kind}"), name)


class RclpyPublisher(Publisher):
    """One ROS 2 publisher: the bridge's CDR bytes published as they are."""

    def __init__(self, node: Any, pub: Any) -> None:
        self._node = node
        self._pub: Any = pub
        self._lock = threading.Lock()

    @property
    def listening(self) -> bool:
        pub = self._pub
        if pub is None:
            return False
        try:
            return int(pub.get_subscription_count()) > 0
        except Exception:  # destroyed meanwhile
            return False

    def publish(self, payloads: Sequence[bytes], stamps: Sequence[int], now_ns: int) -> None:
        with self._lock:
            pub = self._pub
            if pub is None:
                return
            for p in payloads:
                pub.publish(p)

    def close(self) -> None:
        with self._lock:
            pub, self._pub = self._pub, None
        if pub is not None:
            try:
                self._node.destroy_publisher(pub)
            except Exception as e:  # the node is gone already
                log.debug("rclpy: destroy publisher: %s", e)


class _ServiceCall(Request):
    """A Trigger request taken by rclpy: the service callback waits (in its
    executor thread) until the node answers with reply() or refuse()."""

    def __init__(self, payload: bytes, requester: str) -> None:
        self.payload = payload
        self.requester = requester
        self.answer: Tuple[bool, str] = (False, "no answer from the bridge")
        self.done = threading.Event()

    def reply(self, payload: bytes) -> None:
        self.answer = cdr.decode_trigger_response(payload)
        self.done.set()

    def refuse(self, why: str) -> None:
        self.answer = (False, f"refused: {why}")
        self.done.set()


class RclpyTransport(Transport):
    """The bridge's nodes as rclpy nodes (see the module's docstring)."""

    name = "dds"
    command_topics = True

    def __init__(self, domain: int, interface: Optional[str] = None) -> None:
        import rclpy
        from rclpy.callback_groups import ReentrantCallbackGroup
        from rclpy.signals import SignalHandlerOptions
        from rclpy.utilities import get_rmw_implementation_identifier

        for k, v in interface_env(interface).items():
            os.environ.setdefault(k, v)  # read by rcl at init; the user's own setting wins
        self._rclpy: Any = rclpy
        self.context: Any = rclpy.Context()
        try:
            rclpy.init(context=self.context, domain_id=domain,
                       signal_handler_options=SignalHandlerOptions.NO,
                       args=["--ros-args", "--disable-external-lib-logs"])
        except Exception as e:  # rclpy's RCLError: a bad domain id, no rmw
            raise OSError(f"rclpy: domain {domain}: {e}") from None
        self.rmw = str(get_rmw_implementation_identifier())
        self.impl = f"rclpy ({self.rmw})"
        self._group: Any = ReentrantCallbackGroup()
        self._nodes: Dict[Tuple[str, str], Any] = {}
        self._keep: List[Any] = []  # services and subscriptions (rclpy keeps them, too)
        self._lock = threading.Lock()
        self._waiting: List[_ServiceCall] = []
        self._closing = False
        self._executor: Any = None
        self._spin: Optional[threading.Thread] = None

    def _node(self, node: NodeRef) -> Any:
        key = (node.namespace, node.name)
        n = self._nodes.get(key)
        if n is None:
            n = self._rclpy.create_node(node.name, namespace=node.namespace,
                                        context=self.context, start_parameter_services=False,
                                        enable_rosout=False)
            self._nodes[key] = n
        return n

    def declare_node(self, node: NodeRef) -> None:
        self._node(node)

    def advertise(self, endpoint: Endpoint) -> Publisher:
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

        qos = QoSProfile(depth=endpoint.qos_depth, history=HistoryPolicy.KEEP_LAST,
                         reliability=ReliabilityPolicy.RELIABLE,
                         durability=DurabilityPolicy.VOLATILE)
        n = self._node(endpoint.node)
        return RclpyPublisher(n, n.create_publisher(_ros_class(endpoint.ros_type), endpoint.name,
                                                    qos))

    def _input_qos(self, depth: int) -> Any:
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

        return QoSProfile(depth=depth, history=HistoryPolicy.KEEP_LAST,
                          reliability=ReliabilityPolicy.BEST_EFFORT,
                          durability=DurabilityPolicy.VOLATILE)

    def _raw_subscription(self, endpoint: Endpoint, ros_type: str,
                          on_sample: Callable[[bytes, Dict[str, Any]], None]) -> None:
        def callback(data: bytes, info: Dict[str, Any]) -> None:
            try:
                on_sample(bytes(data), info)
            except Exception as e:  # must not reach the executor
                log.warning("%s: %s", endpoint.name, e)

        sub = self._node(endpoint.node).create_subscription(
            _ros_class(ros_type), endpoint.name, callback, self._input_qos(endpoint.qos_depth),
            raw=True)
        self._keep.append(sub)

    def take(self, endpoint: Endpoint, on_payload: InputHandler) -> None:
        self._raw_subscription(endpoint, endpoint.ros_type,
                               lambda data, _info: on_payload(data, ""))

    def serve(self, endpoint: Endpoint, on_request: Callable[[Request], None]) -> None:
        """The Trigger service and its command topic (std_msgs/msg/Empty)."""
        from rclpy.serialization import serialize_message

        who = f"rclpy client of {endpoint.name}"

        def callback(request: Any, response: Any) -> Any:
            call = _ServiceCall(bytes(serialize_message(request)), who)
            with self._lock:
                if self._closing:
                    call.refuse("the bridge is closing")
                else:
                    self._waiting.append(call)
            if not call.done.is_set():
                on_request(call)
                if not call.done.wait(ANSWER_WAIT_S):
                    call.answer = (False, f"no answer within {ANSWER_WAIT_S:g} s")
            with self._lock:
                if call in self._waiting:
                    self._waiting.remove(call)
            response.success, response.message = call.answer
            return response

        srv = self._node(endpoint.node).create_service(
            _ros_class(TRIGGER), endpoint.name, callback, callback_group=self._group)
        self._keep.append(srv)

        def on_command(data: bytes, info: Dict[str, Any]) -> None:
            on_request(CommandRequest(data, f"rclpy publisher {_gid(info)} on {endpoint.name}"))

        self._raw_subscription(endpoint, EMPTY, on_command)

    def ready(self) -> None:
        """Every node declared: spin them, a thread per node to spare (a
        request being served holds one) and two more."""
        from rclpy.executors import MultiThreadedExecutor

        self._executor = MultiThreadedExecutor(num_threads=len(self._nodes) + 2,
                                               context=self.context)
        for n in self._nodes.values():
            self._executor.add_node(n)
        self._spin = threading.Thread(target=self._run, name="bridge-rclpy", daemon=True)
        self._spin.start()

    def _run(self) -> None:
        try:
            self._executor.spin()
        except Exception as e:  # the context shut down under it
            log.debug("rclpy executor: %s", e)

    def diagnostics(self, node: NodeRef) -> List[Tuple[str, str]]:
        return [("dds_impl", self.impl)]

    def close(self) -> None:
        """Answer what waits, withdraw, stop the executor, destroy the
        nodes, shut the context down. Idempotent."""
        with self._lock:
            if self._closing:
                return
            self._closing = True
            waiting, self._waiting = self._waiting, []
        for call in waiting:
            call.refuse("the bridge is closing")
        if self._executor is not None:
            try:
                self._executor.shutdown(timeout_sec=2.0)
            except Exception as e:
                log.debug("rclpy executor shutdown: %s", e)
        if self._spin is not None:
            self._spin.join(3.0)
        for n in self._nodes.values():
            try:
                n.destroy_node()  # its publishers, services, subscriptions
            except Exception as e:
                log.debug("rclpy: destroy node: %s", e)
        self._nodes = {}
        self._keep = []
        try:
            self.context.try_shutdown()
        except Exception as e:
            log.debug("rclpy: shutdown: %s", e)


def _gid(info: Dict[str, Any]) -> str:
    """A sample's publisher GID in hex where rclpy gives it, else "unknown"."""
    gid = info.get("publisher_gid") if isinstance(info, dict) else None
    data = gid.get("data") if isinstance(gid, dict) else None
    return bytes(data).hex() if data else "unknown"
