"""leptrino-bridge with a tool on the sensor: `wrench` compensated by the
session, `wrench_raw` not; the `NAME/gravity` input on each transport (a
Zenoh router and client session, a Cyclone DDS writer, a Foxglove
WebSocket client written from the protocol's specification, all on
127.0.0.1); garbage on each input refused and counted; --limit episodes in
the diagnostics (and so in the MCAP file).

The virtual sensor carries the tool at its own gravity and cannot turn, so
after a new gravity g is published the compensated wrench is
w(g_sim) - w(g): the model (F = m g, M = c x m g) is computed here with
numpy, independently of the library. Every wait is bounded."""

# no "from __future__ import annotations": cyclonedds resolves the IDL
# classes' annotations as objects

import json
import math
import os
import struct
import subprocess
import sys
import time
from pathlib import Path
from typing import Any, Callable, Dict, List, Tuple

import numpy as np
import pytest

zenoh = pytest.importorskip("zenoh")  # the "bridge" extra
pytest.importorskip("mcap")

import leptrino  # noqa: E402
from leptrino.bridge import Bridge, NodeOptions, SensorSpec, ZenohOptions  # noqa: E402
from leptrino.bridge import cdr  # noqa: E402
from bridge_net import free_port, open_zenoh, router  # noqa: E402, F401 (router: a fixture)

G0 = 9.80665
TOOL = (1.5, 0.02, -0.01, 0.06)  # kg, m
SIM = {"payload": ",".join(map(str, TOOL)), "constant": True, "amplitude": "0"}
G_SIM = (0.0, 0.0, -G0)
TILT = math.radians(30.0)
G_NEW = (G0 * math.sin(TILT), 0.0, -G0 * math.cos(TILT))
#: geometry_msgs/msg/Vector3Stamped's type hash in ROS 2 Jazzy (as rosbags lists it)
VEC3_HASH = "RIHS01_d4829622288cbb443886e7ea94ea5671a3b1be6bab4ad04224432a65f7d7887a"
#: one count of the virtual sensor's model (rated / 10000): the tool's weight is rounded
#: to counts by the sensor (at most half a count off)
TOL = np.array(leptrino.Simulator.model_rated("PFS055YA501U6"), dtype=float) / 10000.0

_GOOD = cdr.encode_vector3_stamped(1, 0, "a", (0.0, 0.0, -G0))


def garbage(transport: str) -> List[bytes]:
    """A wrong length, a bad encapsulation header, a NaN, a zero vector (the
    last is refused last: its reason is the last refusal). A Cyclone writer
    refuses to write a short sample (the DDS reader can only ever get what a
    writer's serializer let through), so on DDS the wrong length is 8 bytes
    too many."""
    wrong = _GOOD + bytes(8) if transport == "dds" else _GOOD[:-8]
    return [wrong, b"\x07\x07\x00\x00" + _GOOD[4:],
            cdr.encode_vector3_stamped(1, 0, "a", (0.0, float("nan"), -G0)),
            cdr.encode_vector3_stamped(1, 0, "a", (0.0, 0.0, 0.0))]


def weight(g: Tuple[float, float, float]) -> np.ndarray:
    """The tool's gravity wrench at g: (m g, c x m g)."""
    f = TOOL[0] * np.asarray(g)
    return np.concatenate([f, np.cross(np.asarray(TOOL[1:]), f)])


def wait(pred: Callable[[], bool], timeout: float, what: str) -> None:
    end = time.monotonic() + timeout
    while not pred():
        assert time.monotonic() < end, f"timed out waiting for {what}"
        time.sleep(0.02)


def read_mcap(path: Path) -> Dict[str, List[Tuple[int, Any]]]:
    """topic -> [(log_time ns, decoded message)]."""
    from mcap.reader import make_reader
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    out: Dict[str, List[Tuple[int, Any]]] = {}
    with open(path, "rb") as f:
        for schema, ch, m in make_reader(f).iter_messages():
            out.setdefault(ch.topic, []).append(
                (m.log_time, ts.deserialize_cdr(m.data, schema.name)))
    return out


def six(msgs: List[Tuple[int, Any]], lo: int, hi: int) -> np.ndarray:
    w = [m.wrench for t, m in msgs if lo <= t <= hi]
    assert len(w) >= 100, (len(w), lo, hi)
    return np.array([[x.force.x, x.force.y, x.force.z, x.torque.x, x.torque.y, x.torque.z]
                     for x in w])


def diag_values(msg: Any) -> Dict[str, str]:
    return {kv.key: kv.value for kv in msg.status[0].values}


# -- the senders: one per transport, each independent of the bridge's code ---
class ZenohSender:
    def __init__(self, router: str) -> None:
        self.s = open_zenoh("client", connect=[router])
        self.key = f"0/a/gravity/geometry_msgs::msg::dds_::Vector3Stamped_/{VEC3_HASH}"
        self.seq = 0

    def ready(self) -> bool:
        """The bridge's subscription is in the graph (its liveliness token)."""
        toks = [str(r.ok.key_expr) for r in self.s.liveliness().get("@ros2_lv/0/**", timeout=2.0)
                if r.ok is not None]
        return any("/MS/%/%/a/%a%gravity/geometry_msgs::msg::dds_::Vector3Stamped_/"
                   + VEC3_HASH + "/" in k for k in toks)

    def send(self, payload: bytes) -> None:
        self.seq += 1
        self.s.put(self.key, payload,
                   attachment=struct.pack("<qqB16s", self.seq, time.time_ns(), 16, b"G" * 16))

    def close(self) -> None:
        self.s.close()


class DdsSender:
    """A Cyclone participant of its own writing rt/a/gravity (raw CDR, so
    that garbage can be written too)."""

    def __init__(self, domain: int) -> None:
        from cyclonedds.core import Qos
        from cyclonedds.domain import DomainParticipant
        from cyclonedds.pub import DataWriter
        from ros_dds_types import Vector3Stamped_
        from cyclonedds.qos import Policy
        from cyclonedds.topic import Topic

        qos = Qos(Policy.Reliability.Reliable(1_000_000_000), Policy.Durability.Volatile,
                  Policy.History.KeepLast(10),
                  Policy.DataRepresentation(use_cdrv0_representation=True),
                  Policy.Userdata(f"typehash={VEC3_HASH};".encode()))
        self.p = DomainParticipant(domain)
        self.topic = Topic(self.p, "rt/a/gravity", Vector3Stamped_,
                           qos=Qos(Policy.DataRepresentation(use_cdrv0_representation=True)))
        self.w = DataWriter(self.p, self.topic, qos=qos)

    def ready(self) -> bool:
        return bool(self.w.get_matched_subscriptions())

    def send(self, payload: bytes) -> None:
        from cyclonedds._clayer import ddspy_write

        assert ddspy_write(self.w._ref, payload) >= 0

    def close(self) -> None:
        self.w = None
        self.p = None


class FoxgloveSender:
    """A WebSocket client (subprotocol foxglove.sdk.v1) advertising a client
    channel on /a/gravity and sending Client Message Data (opcode 0x01)."""

    def __init__(self, port: int) -> None:
        from contextlib import ExitStack

        from websockets.sync.client import connect

        self._stack = ExitStack()  # closed by close()
        self.ws = self._stack.enter_context(connect(
            f"ws://127.0.0.1:{port}", subprotocols=["foxglove.sdk.v1"], open_timeout=10))
        info = json.loads(self.ws.recv(timeout=10))
        assert info["op"] == "serverInfo" and "clientPublish" in info["capabilities"], info
        schema = "std_msgs/Header header\nVector3 vector\n"
        self.ws.send(json.dumps({"op": "advertise", "channels": [{
            "id": 7, "topic": "/a/gravity", "encoding": "cdr",
            "schemaName": "geometry_msgs/msg/Vector3Stamped", "schemaEncoding": "ros2msg",
            "schema": schema}]}))

    def ready(self) -> bool:
        return True

    def send(self, payload: bytes) -> None:
        self.ws.send(struct.pack("<BI", 0x01, 7) + payload)

    def close(self) -> None:
        self._stack.close()


def run_transport(transport: str, tmp_path: Path, router: str) -> None:
    mcap = tmp_path / "out.mcap"
    spec = SensorSpec("a", sim=dict(SIM), payload=TOOL)
    domain = 150 + os.getpid() % 50
    kw: Dict[str, Any] = {}
    if transport == "zenoh":
        kw["zenoh_opts"] = ZenohOptions(mode="client", connect=[router])
    elif transport == "dds":
        pytest.importorskip("cyclonedds")
        from leptrino.bridge.dds import DdsOptions

        kw["dds_opts"] = DdsOptions(interface="127.0.0.1", impl="cyclone")  # its Cyclone writer
    else:
        pytest.importorskip("foxglove")
        pytest.importorskip("websockets")
        kw["foxglove"] = ("127.0.0.1", free_port())
    bridge = Bridge([spec], NodeOptions(domain=domain if transport == "dds" else 0),
                    mcap_path=str(mcap), **kw)
    sender: Any = None
    try:
        bridge.start()
        node = bridge.nodes[0]
        if transport == "zenoh":
            sender = ZenohSender(router)
        elif transport == "dds":
            sender = DdsSender(domain)
        else:
            sender = FoxgloveSender(bridge.foxglove.port)  # type: ignore[union-attr]
        wait(sender.ready, 15.0, f"{transport}: the bridge's gravity subscription")
        wait(lambda: node.counters.samples > 1200, 15.0, "a second of samples")
        t0 = time.time_ns()
        good = cdr.encode_vector3_stamped(1, 0, "a", G_NEW)
        end = time.monotonic() + 10.0
        while node.gravity.accepted == 0 and time.monotonic() < end:
            sender.send(good)  # again until it arrives: discovery may still settle
            time.sleep(0.2)
        assert node.gravity.accepted >= 1
        assert node.gravity.by_transport == {transport: node.gravity.accepted}
        t1 = time.time_ns()
        time.sleep(0.6)
        for g in garbage(transport):
            sender.send(g)
            time.sleep(0.05)  # in order (a DDS reader takes them in its own order)
        wait(lambda: node.gravity.refused >= 4, 10.0, "four refusals")
        t2 = time.time_ns()
        before = node.counters.samples
        time.sleep(0.6)
        assert node.counters.samples > before + 300  # `wrench` kept streaming
        assert node.alive
        t3 = time.time_ns()
        time.sleep(1.2)  # one more periodic diagnostics
    finally:
        if sender is not None:
            sender.close()
        bridge.close()

    got = read_mcap(mcap)
    lag = 50_000_000  # a batch read before a change may be published just after it
    # before: the tool's weight removed from `wrench`, present in `wrench_raw`
    w0, r0 = six(got["/a/wrench"], 0, t0), six(got["/a/wrench_raw"], 0, t0)
    assert np.all(np.abs(w0.mean(axis=0)) <= TOL), w0.mean(axis=0)
    assert np.all(np.abs(r0.mean(axis=0) - weight(G_SIM)) <= TOL), r0.mean(axis=0)
    # after the new gravity, and after the garbage (which changed nothing)
    want = weight(G_SIM) - weight(G_NEW)
    assert abs(want[0]) > 5.0  # the check is not about a tiny difference
    for lo, hi in ((t1 + lag, t2), (t2 + lag, t3)):
        w1 = six(got["/a/wrench"], lo, hi)
        r1 = six(got["/a/wrench_raw"], lo, hi)
        assert np.all(np.abs(w1.mean(axis=0) - want) <= TOL), (w1.mean(axis=0), want)
        assert np.all(np.abs(r1.mean(axis=0) - weight(G_SIM)) <= TOL)  # never compensated
    last = diag_values(got["/a/diagnostics"][-1][1])
    assert last["gravity_refused"] == "4", last
    assert int(last["gravity_updates"]) >= 1
    assert last["gravity"] == " ".join(f"{x:.6g}" for x in G_NEW)
    assert transport in last["gravity_last_refusal"] and "zero" in last["gravity_last_refusal"]
    assert last["payload"] == "1.5 kg at 0.02 -0.01 0.06 m"


@pytest.mark.parametrize("transport", ["zenoh", "dds", "foxglove"])
def test_gravity_input_changes_the_compensation(transport: str, tmp_path: Path,
                                                router: str) -> None:
    run_transport(transport, tmp_path, router)


LIMITS = "fx=50,fy=50,fz=50,mx=2,my=2,mz=2"


def test_cli_payload_and_limit_episodes(tmp_path: Path) -> None:
    """The command line: --payload removes the weight from `wrench` only;
    --limit with the virtual sensor's overload episodes (4x rated, every
    0.25 s for 0.05 s) gives WARN diagnostics naming the axes, in the MCAP."""
    mcap = tmp_path / "lim.mcap"
    sim = "a," + ",".join(f"{k}={v}" for k, v in SIM.items() if k != "constant")
    r = subprocess.run(
        [sys.executable, "-m", "leptrino.bridge", "--sim", sim + ",constant",
         "--sim", "b,constant,amplitude=0,overload-every=0.25,overload-duration=0.05",
         "--payload", "a=" + ",".join(map(str, TOOL)), "--limit", LIMITS,
         "--mcap", str(mcap), "--duration", "2.5"],
        capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    got = read_mcap(mcap)
    w, raw = six(got["/a/wrench"], 0, 2**63), six(got["/a/wrench_raw"], 0, 2**63)
    assert np.all(np.abs(w.mean(axis=0)) <= TOL), w.mean(axis=0)
    assert np.all(np.abs(raw.mean(axis=0) - weight(G_SIM)) <= TOL), raw.mean(axis=0)
    # a: within its limits all along
    assert all(m.status[0].level == 0 for _, m in got["/a/diagnostics"][1:])
    assert diag_values(got["/a/diagnostics"][-1][1])["limit_episodes"] == "0"
    # b: each overload (of one axis) is a limit episode, said at once (WARN,
    # the axis named) and cleared (OK again)
    diags = [m.status[0] for _, m in got["/b/diagnostics"]]
    warns = [s for s in diags if s.level == 1]
    assert len(warns) >= 5, [s.message for s in diags]
    named = set()
    for s in warns:
        axis = {kv.key: kv.value for kv in s.values}["beyond_limit"]
        assert axis in ("fx", "fy", "fz", "mx", "my", "mz"), axis
        assert s.message == f"beyond limit: {axis}", s.message
        named.add(axis)
    assert len(named) >= 2, named
    last = {kv.key: kv.value for kv in diags[-1].values}
    assert last["limits"] == LIMITS
    assert int(last["limit_episodes"]) >= 5
    assert diags[-1].level == 0 or last["beyond_limit"]


def test_limit_from_the_first_sample_is_not_no_data(tmp_path: Path) -> None:
    """A sensor beyond its limit from the first sample on (the virtual sensor's
    default sine starts near fz = -99 N): the diagnostics said at once for
    that episode are WARN naming the axis, with the samples counted, never
    ERROR "no data" while data flow."""
    mcap = tmp_path / "first.mcap"
    r = subprocess.run(
        [sys.executable, "-m", "leptrino.bridge", "--sim", "a", "--limit", "fz=50",
         "--mcap", str(mcap), "--duration", "1.5"],
        capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    diags = [m.status[0] for _, m in read_mcap(mcap)["/a/diagnostics"]]
    first = diags[0]
    values = {kv.key: kv.value for kv in first.values}
    assert (first.level, first.message) == (1, "beyond limit: fz"), (first.level, first.message,
                                                                      values)
    assert int(values["published"]) > 0, values
    assert all(d.level != 2 for d in diags), [(d.level, d.message) for d in diags]


def test_cli_refuses_bad_payload_gravity_and_limit() -> None:
    for args, words in ((["--payload", "a=-1,0,0,0"], "negative"),
                        (["--payload", "1,2,3"], "4 comma-separated"),
                        (["--payload", "b=1,0,0,0"], "no sensor named 'b'"),
                        (["--gravity", "0,0,0"], "zero vector"),
                        (["--gravity", "0,nan,-9.8"], "3 comma-separated"),
                        (["--limit", "fz=0"], "AXIS=VALUE"),
                        (["--limit", "fq=3"], "AXIS=VALUE")):
        r = subprocess.run([sys.executable, "-m", "leptrino.bridge", "--sim", "a",
                            "--mcap", os.devnull, "--overwrite", "--duration", "1", *args],
                           capture_output=True, text=True, timeout=60)
        assert r.returncode == 2, (args, r.stderr)
        assert words in r.stderr, (args, r.stderr)
