"""The node's logic over the transport interface (bridge/transport.py), with
an in-process transport: what every transport gets (topics, services, the
input), the one-at-a-time and busy rule, publishing only to listeners."""

from __future__ import annotations

import itertools
import threading
import time
from typing import Any, Callable, Dict, List, Sequence

import pytest

pytest.importorskip("zenoh")  # the "bridge" extra

from rosbags.typesys import (Stores, get_types_from_msg,  # noqa: E402 (an independent reader)
                             get_typestore)

from leptrino.bridge import NodeOptions, SensorNode, SensorSpec  # noqa: E402
from leptrino.bridge.node import BUSY  # noqa: E402
from leptrino.bridge.transport import (Endpoint, InputHandler, Publisher,  # noqa: E402
                                       Request, Transport)

TRIGGER_REQUEST = b"\x00\x01\x00\x00\x00"


class FakePublisher(Publisher):
    def __init__(self) -> None:
        self.on = False
        self.got: List[bytes] = []

    @property
    def listening(self) -> bool:
        return self.on

    def publish(self, payloads: Sequence[bytes], stamps: Sequence[int], now_ns: int) -> None:
        self.got += payloads


class FakeRequest(Request):
    def __init__(self, payload: bytes, who: str) -> None:
        self.payload, self.requester = payload, who
        self.answers: List[Any] = []
        self.done = threading.Event()

    def reply(self, payload: bytes) -> None:
        self.answers.append(("reply", payload))
        self.done.set()

    def refuse(self, why: str) -> None:
        self.answers.append(("refuse", why))
        self.done.set()


class FakeTransport(Transport):
    name = "fake"

    def __init__(self) -> None:
        self.pubs: Dict[str, FakePublisher] = {}
        self.services: Dict[str, Callable[[Request], None]] = {}
        self.inputs: Dict[str, InputHandler] = {}

    def advertise(self, endpoint: Endpoint) -> Publisher:
        self.pubs[endpoint.name] = p = FakePublisher()
        return p

    def serve(self, endpoint: Endpoint, on_request: Callable[[Request], None]) -> None:
        self.services[endpoint.name] = on_request

    def take(self, endpoint: Endpoint, on_payload: InputHandler) -> None:
        self.inputs[endpoint.name] = on_payload

    def close(self) -> None:
        pass


def _node(read_only: bool = False) -> Any:
    node = SensorNode(SensorSpec("a", sim={"constant": True}),
                      NodeOptions(tare_samples=200, read_only=read_only))
    t = FakeTransport()
    ids = itertools.count(10)
    node.declare(0, lambda: next(ids), [t])
    return node, t


def test_endpoints_on_a_transport() -> None:
    node, t = _node()
    try:
        assert sorted(t.pubs) == ["/a/diagnostics", "/a/wrench", "/a/wrench_raw"]
        assert sorted(t.services) == ["/a/tare", "/a/untare"]
        assert sorted(t.inputs) == ["/a/gravity"]
    finally:
        node.close()
    node, t = _node(read_only=True)
    try:
        assert (t.services, t.inputs) == ({}, {})
    finally:
        node.close()


def test_one_request_at_a_time_the_others_busy_at_once() -> None:
    store = get_typestore(Stores.ROS2_JAZZY)
    store.register(get_types_from_msg("bool success\nstring message",
                                      "std_srvs/msg/Trigger_Response"))
    node, t = _node()
    try:
        node.start()
        time.sleep(0.3)
        reqs = [FakeRequest(TRIGGER_REQUEST, f"client {i}") for i in range(20)]
        for r in reqs:  # all while the first is served (a tare of 200 samples: ~0.17 s)
            t.services["/a/tare" if r.requester != "client 5" else "/a/untare"](r)
        for r in reqs:
            assert r.done.wait(5.0), r.requester
        answers = [store.deserialize_cdr(r.answers[0][1], "std_srvs/msg/Trigger_Response")
                   for r in reqs]
        assert answers[0].success, answers[0].message
        assert all(not a.success and a.message == BUSY for a in answers[1:])
        c = node.counters
        assert (c.tare_requests, c.tare_busy) == (1, 19)
        bad = FakeRequest(b"\x07", "garbage")
        t.services["/a/tare"](bad)
        assert bad.answers[0][0] == "refuse" and c.rejected_requests == 1
        again = FakeRequest(TRIGGER_REQUEST, "later")  # the gate is open again
        t.services["/a/untare"](again)
        assert again.done.wait(5.0)
        assert store.deserialize_cdr(again.answers[0][1],
                                     "std_srvs/msg/Trigger_Response").success
    finally:
        node.stop()
        node.close()


def _until(cond: Callable[[], bool], timeout: float = 10.0) -> None:
    end = time.monotonic() + timeout
    while not cond():
        assert time.monotonic() < end, "not within the time"
        time.sleep(0.02)


def test_published_only_while_someone_listens() -> None:
    node, t = _node()
    w = t.pubs["/a/wrench"]
    try:
        node.start()
        assert node.wrench is not None
        _until(lambda: node.wrench is not None and node.wrench.skipped["fake"] > 100)
        assert w.got == []
        w.on = True
        _until(lambda: len(w.got) > 100)
        assert t.pubs["/a/wrench_raw"].got == []
        w.on = False
        time.sleep(0.1)
        n2 = len(w.got)
        time.sleep(0.3)
        assert len(w.got) == n2
        kv = dict(node.diagnostic_status()[4])
        assert int(kv["skipped_fake_wrench_raw"]) > 500
    finally:
        node.stop()
        node.close()
