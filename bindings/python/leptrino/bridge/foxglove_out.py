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

from .schema import ros2msg_schema
from .transport import Endpoint, InputHandler, Publisher, Request, Transport

log = logging.getLogger("leptrino.bridge")


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


class FoxgloveChannel(Publisher):
    """One topic on the server: logs the payloads while a client subscribes."""

    def __init__(self, ctx: Any, topic: str, ros_type: str,
                 subscribers: _ClientInputs) -> None:
        import foxglove

        self.channel = foxglove.Channel(
            topic, message_encoding="cdr",
            schema=foxglove.Schema(name=ros_type, encoding="ros2msg",
                                   data=ros2msg_schema(ros_type)),
            context=ctx)
        self._log = self.channel.log
        self._subs = subscribers.counter(self.channel.id())

    @property
    def listening(self) -> bool:
        return self._subs[0] > 0

    def publish(self, payloads: Sequence[bytes], stamps: Sequence[int], now_ns: int) -> None:
        log_ = self._log
        for p, t in zip(payloads, stamps):
            log_(p, log_time=t)

    def close(self) -> None:
        try:
            self.channel.close()
        except Exception:
            pass


class _FoxgloveRequest(Request):
    """A service call: the SDK's handler waits (in its own thread) for the
    node's answer, at most REPLY_WAIT_S."""

    REPLY_WAIT_S = 10.0

    def __init__(self, request: Any) -> None:
        self.requester = f"foxglove client {request.client_id}"
        self.payload = bytes(request.payload)
        self._done = threading.Event()
        self._reply: Optional[bytes] = None
        self._why = ""

    def reply(self, payload: bytes) -> None:
        self._reply = payload
        self._done.set()

    def refuse(self, why: str) -> None:
        self._why = why
        self._done.set()

    def wait(self) -> bytes:
        if not self._done.wait(self.REPLY_WAIT_S):
            raise TimeoutError("no answer from the bridge")
        if self._reply is None:
            raise ValueError(f"malformed request: {self._why}")
        return self._reply


class FoxgloveTransport(Transport):
    """A Foxglove WebSocket server on host:port with its own context (so
    that nothing else logged in the process leaks into it). Listens from
    construction (OSError when it cannot); channels are advertised as they
    are made, the services when ready() is called. inputs False (read-only):
    the server offers neither services nor client publishing.

    Services: std_srvs/srv/Trigger in CDR; the SDK's handler thread waits for
    the node's answer; a refused request is a service call failure for the
    client. Inputs: topics clients may publish to (ros2msg schema, CDR); a
    client channel of another encoding or schema is refused message by message."""

    name = "foxglove"

    def __init__(self, host: str, port: int, inputs: bool = True) -> None:
        import foxglove
        from foxglove import Capability

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

    def advertise(self, endpoint: Endpoint) -> Publisher:
        return FoxgloveChannel(self.ctx, endpoint.name, endpoint.ros_type, self._inputs)

    def serve(self, endpoint: Endpoint, on_request: Callable[[Request], None]) -> None:
        from foxglove import MessageSchema, Schema, Service, ServiceSchema

        def handler(request: Any) -> bytes:
            req = _FoxgloveRequest(request)
            on_request(req)
            return req.wait()

        base = endpoint.ros_type
        schema = ServiceSchema(
            name=base,
            request=MessageSchema(encoding="cdr", schema=Schema(
                name=base + "_Request", encoding="ros2msg",
                data=ros2msg_schema(base + "_Request"))),
            response=MessageSchema(encoding="cdr", schema=Schema(
                name=base + "_Response", encoding="ros2msg",
                data=ros2msg_schema(base + "_Response"))))
        self._services.append(Service(name=endpoint.name, schema=schema, handler=handler))

    def take(self, endpoint: Endpoint, on_payload: InputHandler) -> None:
        self._inputs.add(endpoint.name, endpoint.ros_type, on_payload)

    def ready(self) -> None:
        """Offer the services (after every node declared them)."""
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
        self._subs: Dict[int, List[int]] = {}

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

    def counter(self, channel_id: int) -> List[int]:
        """The subscription count of a channel of the server ([n], updated in place)."""
        with self._lock:
            return self._subs.setdefault(channel_id, [0])

    def on_subscribe(self, client: Any, channel: Any) -> None:
        with self._lock:
            self._subs.setdefault(channel.id, [0])[0] += 1

    def on_unsubscribe(self, client: Any, channel: Any) -> None:
        with self._lock:
            n = self._subs.setdefault(channel.id, [0])
            n[0] = max(0, n[0] - 1)
