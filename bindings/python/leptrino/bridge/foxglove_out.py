"""Foxglove live: the bridge's topics on a Foxglove WebSocket server
(the PyPI `foxglove-sdk`, the "bridge" extra), with the schemas and
payloads of its MCAP file (ros2msg schemas, CDR messages), the tare and
untare services as Foxglove services (std_srvs/srv/Trigger in CDR), and
inputs (`NAME/gravity`) as topics a client may publish to (client advertise
and message data, CDR; the bridge checks every message).

Foxglove (app or web) connects with "Open connection" -> Foxglove WebSocket
-> ws://HOST:PORT; docs/bridge.md tells how from another host and where the
layout is.
"""

from __future__ import annotations

import logging
import threading
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

from . import cdr
from .mcap_out import ros2msg_schema
from .ratelog import RateLimitedLog

log = logging.getLogger("leptrino.bridge")

TRIGGER_REQUEST_MSG = ""  # std_srvs/srv/Trigger: an empty request
TRIGGER_RESPONSE_MSG = "bool success\nstring message\n"


def parse_address(text: str) -> Tuple[str, int]:
    """[HOST:]PORT -> (host, port); the host defaults to 127.0.0.1.
    ValueError for anything else."""
    host, sep, port = text.rpartition(":")
    if not sep:
        host = "127.0.0.1"
    host = host.strip("[]") or "127.0.0.1"
    if not port.isdigit() or not 0 <= int(port) <= 65535:
        raise ValueError(f"--foxglove {text!r}: expected [HOST:]PORT")
    return host, int(port)


class FoxgloveChannel:
    """One topic on the server: logs the payloads as they are published."""

    def __init__(self, ctx: Any, topic: str, ros_type: str) -> None:
        import foxglove

        self.channel = foxglove.Channel(
            topic, message_encoding="cdr",
            schema=foxglove.Schema(name=ros_type, encoding="ros2msg",
                                   data=ros2msg_schema(ros_type)),
            context=ctx)
        self._log = self.channel.log

    def publish(self, payloads: Sequence[bytes], stamps: Sequence[int], now_ns: int) -> None:
        log_ = self._log
        for p, t in zip(payloads, stamps):
            log_(p, log_time=t)

    def close(self) -> None:
        try:
            self.channel.close()
        except Exception:
            pass


class FoxgloveServer:
    """A Foxglove WebSocket server on host:port with its own context (so
    that nothing else logged in the process leaks into it). Listens from
    construction (OSError when it cannot); channels are advertised as they
    are made, the services by add_services(). inputs False (read-only):
    the server offers neither services nor client publishing."""

    def __init__(self, host: str, port: int, inputs: bool = True) -> None:
        import foxglove
        from foxglove import Capability

        self._refusals = RateLimitedLog()
        self.ctx = foxglove.Context()
        self.host = host
        self._services: List[Any] = []
        self._inputs = _ClientInputs()
        try:
            self._server: Any = foxglove.start_server(
                name="leptrino-bridge", host=host, port=port, context=self.ctx,
                capabilities=([Capability.Services, Capability.ClientPublish] if inputs
                              else []),
                supported_encodings=["cdr"], server_listener=self._inputs)
        except Exception as e:  # the SDK's error for a port in use, a bad host
            raise OSError(f"--foxglove {host}:{port}: {e}") from None

    def channel(self, topic: str, ros_type: str) -> FoxgloveChannel:
        return FoxgloveChannel(self.ctx, topic, ros_type)

    def service(self, name: str, call: Callable[[str], Tuple[bool, str]],
                rejected: Callable[[], None]) -> None:
        """A std_srvs/srv/Trigger service: call(requester) runs in the
        server's thread (requester: "foxglove client <id>", the id the
        server gave the connection); its answer goes back as
        Trigger_Response in CDR. A request that is not CDR is refused (the
        client gets a service call failure), counted by rejected() and
        logged at most every 5 s, and calls nothing."""
        from foxglove import MessageSchema, Schema, Service, ServiceSchema

        def handler(request: Any) -> bytes:
            who = f"foxglove client {request.client_id}"
            try:
                cdr.check_encapsulation(bytes(request.payload))
            except ValueError as e:
                rejected()
                self._refusals.warning("%s: request by %s refused: %s", name, who, e)
                raise ValueError(f"malformed request: {e}") from None
            ok, message = call(who)
            return cdr.encode_trigger_response(ok, message)

        schema = ServiceSchema(
            name="std_srvs/srv/Trigger",
            request=MessageSchema(encoding="cdr", schema=Schema(
                name="std_srvs/srv/Trigger_Request", encoding="ros2msg",
                data=TRIGGER_REQUEST_MSG.encode())),
            response=MessageSchema(encoding="cdr", schema=Schema(
                name="std_srvs/srv/Trigger_Response", encoding="ros2msg",
                data=TRIGGER_RESPONSE_MSG.encode())))
        self._services.append(Service(name=name, schema=schema, handler=handler))

    def client_topic(self, topic: str, ros_type: str,
                     on_payload: Callable[[bytes, str], Any]) -> None:
        """A topic clients may publish to (ros2msg schema ros_type, CDR):
        each message's bytes go to on_payload(data, "") in the server's
        thread (it must not raise); on a client channel of this topic with
        another encoding or schema, on_payload(data, why) so that the
        message is refused and counted like any bad one."""
        self._inputs.add(topic, ros_type, on_payload)

    def add_services(self) -> None:
        """Offer the services made by service() (after every node declared them)."""
        if self._services:
            self._server.add_services(self._services)

    @property
    def port(self) -> int:
        return int(self._server.port) if self._server is not None else 0

    def close(self) -> None:
        if self._server is not None:
            try:
                self._server.stop()
            except Exception:
                pass
            self._server = None




class _ClientInputs:
    """The server's listener for what clients publish: channels advertised
    on a known topic are mapped to its handler; messages of any other
    channel are ignored (one log line per channel)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._topics: Dict[str, Tuple[str, Callable[[bytes, str], Any]]] = {}
        self._channels: Dict[Tuple[int, int], Tuple[str, Callable[[bytes, str], Any], str]] = {}

    def add(self, topic: str, ros_type: str, on_payload: Callable[[bytes, str], Any]) -> None:
        with self._lock:
            self._topics[topic] = (ros_type, on_payload)

    def on_client_advertise(self, client: Any, channel: Any) -> None:
        with self._lock:
            known = self._topics.get(channel.topic)
        if known is None:
            log.warning("foxglove: client %s advertised %s: not an input of the bridge "
                        "(its messages are ignored)", client.id, channel.topic)
            return
        ros_type, handler = known
        wrong = ""
        if channel.encoding != "cdr":
            wrong = f"encoding {channel.encoding!r}, not cdr"
        elif channel.schema_name and channel.schema_name != ros_type:
            wrong = f"schema {channel.schema_name!r}, not {ros_type}"
        with self._lock:
            self._channels[(client.id, channel.id)] = (channel.topic, handler, wrong)

    def on_client_unadvertise(self, client: Any, client_channel_id: int) -> None:
        with self._lock:
            self._channels.pop((client.id, client_channel_id), None)

    def on_message_data(self, client: Any, client_channel_id: int, data: bytes) -> None:
        with self._lock:
            ch = self._channels.get((client.id, client_channel_id))
        if ch is None:
            return
        _topic, handler, wrong = ch
        handler(bytes(data), wrong)

    def on_subscribe(self, client: Any, channel: Any) -> None:
        return None

    def on_unsubscribe(self, client: Any, channel: Any) -> None:
        return None
