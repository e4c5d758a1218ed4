"""Zenoh in rmw_zenoh's layout (rmw_zenoh.py): a publisher per topic with
its liveliness token and matching listener, a queryable per service, a
subscriber per input. Needs eclipse-zenoh (the "bridge" extra)."""

from __future__ import annotations

import logging
import threading
import time
from typing import Any, Callable, List, Sequence

from . import rmw_zenoh as rz
from .transport import Endpoint, InputHandler, NodeRef, Publisher, Request, Transport
from .typehash import rihs01

log = logging.getLogger("leptrino.bridge")


def _undeclare(things: List[Any]) -> None:
    for x in things:
        try:
            x.undeclare()
        except Exception:  # the session may be closing
            pass
    things.clear()


class ZenohPublisher(Publisher):
    """A Zenoh publisher; its sequence numbers and GID go in each message's
    attachment; `listening` follows its matching listener."""

    def __init__(self, session: Any, entity: rz.Entity) -> None:
        import zenoh

        self.entity = entity
        self.gid = entity.gid()
        self.seq = 0
        self.pub = session.declare_publisher(
            entity.key(), congestion_control=zenoh.CongestionControl.DROP,
            reliability=zenoh.Reliability.RELIABLE)
        self._matching = bool(self.pub.matching_status.matching)
        self._listener = self.pub.declare_matching_listener(self._on_matching)

    def _on_matching(self, status: Any) -> None:
        self._matching = bool(status.matching)

    @property
    def listening(self) -> bool:
        return self._matching

    def publish(self, payloads: Sequence[bytes], stamps: Sequence[int], now_ns: int) -> None:
        put, pack, gid, glen = self.pub.put, rz.ATTACHMENT.pack, self.gid, rz.GID_SIZE
        seq = self.seq
        for p in payloads:
            seq += 1
            put(p, attachment=pack(seq, now_ns, glen, gid))
        self.seq = seq

    def close(self) -> None:
        _undeclare([self._listener, self.pub])


class _ZenohRequest(Request):
    """A query: the reply carries the request's sequence number and the
    client's GID in its attachment (rmw_zenoh's service servers)."""

    def __init__(self, query: Any) -> None:
        self._q: Any = query
        self._lock = threading.Lock()
        self.seq = 0
        self.gid = b"\x00" * rz.GID_SIZE
        try:
            att = query.attachment
            self.seq, _ts, self.gid = rz.parse_attachment(
                bytes(att.to_bytes()) if att is not None else b"")
            payload = query.payload
            self.payload = bytes(payload.to_bytes()) if payload is not None else b""
        except ValueError as e:
            self.error = str(e)
        who = f"zenoh client {self.gid.hex()}"
        src = getattr(query, "source_info", None)
        sid = getattr(src, "source_id", None) if src is not None else None
        if sid is not None:
            who += f" (source {sid.zid}/{sid.eid})"
        self.requester = who

    def _answer(self, how: Callable[[Any], None]) -> None:
        with self._lock:
            q, self._q = self._q, None
        if q is None:
            return
        try:
            how(q)
        finally:
            q.drop()  # the query is complete: the requester stops waiting now

    def reply(self, payload: bytes) -> None:
        self._answer(lambda q: q.reply(
            q.key_expr, payload, attachment=rz.attachment(self.seq, time.time_ns(), self.gid)))

    def refuse(self, why: str) -> None:
        self._answer(lambda q: q.reply_err(f"malformed request: {why}".encode()))


class ZenohTransport(Transport):
    """The bridge's Zenoh session (opened by the caller, closed here)."""

    name = "zenoh"

    def __init__(self, session: Any, domain: int) -> None:
        self.session = session
        self.domain = domain
        self.zid = str(session.zid())
        self._declared: List[Any] = []  # queryables, subscribers
        self._tokens: List[Any] = []
        self._pubs: List[ZenohPublisher] = []

    def entity(self, kind: str, ep: Endpoint) -> rz.Entity:
        n = ep.node
        return rz.Entity(self.domain, self.zid, n.node_id, ep.entity_id, kind, n.namespace,
                         n.name, ep.name, ep.ros_type, rihs01(ep.ros_type),
                         rz.qos_keyexpr(True, ep.qos_depth))

    def _token(self, ent: rz.Entity) -> None:
        self._tokens.append(self.session.liveliness().declare_token(ent.token()))

    def declare_node(self, node: NodeRef) -> None:
        self._token(rz.Entity(self.domain, self.zid, node.node_id, node.node_id, rz.NODE,
                              node.namespace, node.name))

    def advertise(self, endpoint: Endpoint) -> Publisher:
        ent = self.entity(rz.PUBLISHER, endpoint)
        pub = ZenohPublisher(self.session, ent)
        self._pubs.append(pub)
        self._token(ent)
        return pub

    def serve(self, endpoint: Endpoint, on_request: Callable[[Request], None]) -> None:
        ent = self.entity(rz.SERVICE, endpoint)
        self._declared.append(self.session.declare_queryable(
            ent.key(), lambda q: on_request(_ZenohRequest(q)), complete=True))
        self._token(ent)

    def take(self, endpoint: Endpoint, on_payload: InputHandler) -> None:
        ent = self.entity(rz.SUBSCRIPTION, endpoint)

        def on_sample(sample: Any) -> None:
            try:
                payload = bytes(sample.payload.to_bytes())
            except Exception as e:  # nothing a peer sends may reach zenoh's thread
                on_payload(b"", f"unreadable payload: {e}")
                return
            on_payload(payload, "")

        self._declared.append(self.session.declare_subscriber(ent.key(), on_sample))
        self._token(ent)

    def reachable(self) -> List[str]:
        """The routers and peers this session is connected to now (ids)."""
        info = self.session.info
        return [str(z) for z in list(info.routers_zid()) + list(info.peers_zid())]

    def close(self) -> None:
        _undeclare(self._declared)
        for p in self._pubs:
            p.close()
        self._pubs = []
        _undeclare(self._tokens)
        try:
            self.session.close()
        except Exception:
            pass

