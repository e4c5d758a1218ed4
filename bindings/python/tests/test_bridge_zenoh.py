"""leptrino.bridge on a real Zenoh network on 127.0.0.1: the test opens a
router on a free port, runs the bridge with virtual sensors, and receives
with a separate Zenoh session written from rmw_zenoh's design (key
expressions, attachment, liveliness), decoding each payload with rosbags.
Every wait is bounded; nothing leaves the loopback interface."""

from __future__ import annotations

import threading
import time
from collections import defaultdict
from pathlib import Path
from typing import Any, Dict, Iterator, List, Tuple

import pytest
from bridge_net import free_port, open_zenoh, router  # noqa: F401 (a fixture)
from conftest import RAMP_ROWS
import zenoh  # the "bridge" extra (make test and .ci/checks/60-bridge.sh install it)

import leptrino
from leptrino.bridge import Bridge, NodeOptions, SensorSpec, ZenohOptions
from leptrino.bridge import cdr
from leptrino.bridge import rmw_zenoh as rz

WRENCH_HASH = "RIHS01_8dc3deaf06b2ab281f9f9a742a8961c328ca7cec16e3fd6586d3a5c83fa78f77"
TRIGGER_HASH = "RIHS01_eeff2cd6fa5ad9d27cdf4dec64818317839b62f212a91e6b5304b634b2062c5f"
DIAG_HASH = "RIHS01_5a8a36efb05fb25070fa0fb3810290c0e6cd4862b54a8fb975a1ee8dc55a333e"
ROWS = RAMP_ROWS  # the replayed ramp's length (conftest.ramp)


def wrench_key(sensor: str, topic: str = "wrench", ns: str = "") -> str:
    pre = f"{ns}/" if ns else ""
    return f"0/{pre}{sensor}/{topic}/geometry_msgs::msg::dds_::WrenchStamped_/{WRENCH_HASH}"


@pytest.fixture
def client(router: str) -> Iterator[Any]:
    c = open_zenoh("client", connect=[router])
    try:
        yield c
    finally:
        c.close()


@pytest.fixture(scope="module")
def store() -> Any:
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    ts.register(get_types_from_msg("bool success\nstring message",
                                   "std_srvs/msg/Trigger_Response"))
    return ts



class Received:
    """Everything a subscriber got: key -> [(payload, attachment, t_receipt)]."""

    def __init__(self, session: Any, key: str) -> None:
        self.lock = threading.Lock()
        self.by_key: Dict[str, List[Tuple[bytes, bytes, float]]] = defaultdict(list)
        self.sub = session.declare_subscriber(key, self._on)

    def _on(self, sample: Any) -> None:
        t = time.time()
        att = sample.attachment
        with self.lock:
            self.by_key[str(sample.key_expr)].append(
                (bytes(sample.payload.to_bytes()),
                 bytes(att.to_bytes()) if att is not None else b"", t))

    def get(self, key: str) -> List[Tuple[bytes, bytes, float]]:
        with self.lock:
            return list(self.by_key.get(key, []))

    def wait_for(self, key: str, n: int, timeout: float) -> List[Tuple[bytes, bytes, float]]:
        end = time.monotonic() + timeout
        while time.monotonic() < end and len(self.get(key)) < n:
            time.sleep(0.02)
        return self.get(key)


def make_bridge(router: str, specs: List[SensorSpec], **opts: Any) -> Bridge:
    b = Bridge(specs, NodeOptions(**opts), ZenohOptions(mode="peer", connect=[router]))
    time.sleep(0.3)  # let the subscriptions reach the bridge's session (bounded)
    return b


def decode_all(store: Any, msgs: List[Tuple[bytes, bytes, float]], t: str) -> List[Any]:
    return [store.deserialize_cdr(p, t) for p, _, _ in msgs]


def check_sequence(msgs: List[Tuple[bytes, bytes, float]]) -> bytes:
    """The attachments' sequence numbers go up by one; one GID; returns it."""
    parsed = [rz.parse_attachment(a) for _, a, _ in msgs]
    seqs = [s for s, _, _ in parsed]
    assert seqs == list(range(seqs[0], seqs[0] + len(seqs))), "a gap or a reordering"
    gids = {g for _, _, g in parsed}
    assert len(gids) == 1
    now = time.time_ns()
    assert all(abs(now - ts) < 60e9 for _, ts, _ in parsed)  # source timestamps: ns, UTC
    return gids.pop()


def test_two_sensors_values_and_continuity(router: str, client: Any, store: Any,
                                           ramp: str) -> None:
    rx = Received(client, "0/**")
    rated = leptrino.Simulator.model_rated("PFS055YA501U6")
    scale = [float(v) / 10000.0 for v in rated]
    specs = [SensorSpec("left", sim={"replay": ramp}, frame_id="left_ft"),
             SensorSpec("right", sim={"replay": ramp})]
    with make_bridge(router, specs) as bridge:
        bridge.start()
        for name in ("left", "right"):
            rx.wait_for(wrench_key(name, "wrench_raw"), 1200, 20.0)
    gids = set()
    for name, frame in (("left", "left_ft"), ("right", "right")):
        raw_msgs = rx.get(wrench_key(name, "wrench_raw"))
        msgs = rx.get(wrench_key(name))
        assert len(raw_msgs) >= 1200 and len(msgs) >= 1200
        gids.add(check_sequence(raw_msgs))
        gids.add(check_sequence(msgs))
        raw = decode_all(store, raw_msgs, "geometry_msgs/msg/WrenchStamped")
        proc = decode_all(store, msgs, "geometry_msgs/msg/WrenchStamped")
        assert {m.header.frame_id for m in raw + proc} == {frame}
        stamps = [m.header.stamp.sec * 10**9 + m.header.stamp.nanosec for m in raw]
        back = [(i, a - b) for i, (a, b) in enumerate(zip(stamps, stamps[1:])) if b < a]
        assert not back, back[:5]  # never backwards
        assert abs(stamps[-1] - time.time_ns()) < 30e9
        prev = None
        for m in raw:
            f, q = m.wrench.force, m.wrench.torque
            fx = round(f.x / scale[0])
            # each sample is the next row of the replayed file
            if prev is not None:
                assert fx == (prev + 1 if prev < ROWS - 3001 else -3000)
            prev = fx
            k = fx + 3000
            assert round(f.y / scale[1]) == -fx
            assert round(f.z / scale[2]) == 3 * (k % 100)
            assert round(q.x / scale[3]) == 100 * (k % 7)
            assert (round(q.y / scale[4]), round(q.z / scale[5])) == (1234, -1234)
        # no tare, filter or rotation asked: wrench is wrench_raw, sample for sample
        # (the two publishers number the samples alike)
        by_seq = {rz.parse_attachment(a)[0]: m for (_, a, _), m in zip(raw_msgs, raw)}
        same = [by_seq[rz.parse_attachment(a)[0]] == m for (_, a, _), m in zip(msgs, proc)
                if rz.parse_attachment(a)[0] in by_seq]
        assert len(same) > 1000 and all(same)
    assert len(gids) == 4  # one GID per publisher


def test_tare_service_changes_the_wrenches(router: str, client: Any, store: Any) -> None:
    rx = Received(client, wrench_key("a", ns="cell"))
    spec = SensorSpec("a", sim={"constant": True, "amplitude": 0.2})
    service = f"0/cell/a/tare/std_srvs::srv::dds_::Trigger_/{TRIGGER_HASH}"
    untare = service.replace("/tare/", "/untare/")
    client_gid = bytes(range(100, 116))

    def call(key: str, seq: int) -> Tuple[Any, Tuple[int, int, bytes], float]:
        replies = list(client.get(
            key, payload=cdr.encode_trigger_request(),
            attachment=rz.attachment(seq, time.time_ns(), client_gid),
            target=zenoh.QueryTarget.ALL_COMPLETE, timeout=10.0))
        assert len(replies) == 1 and replies[0].ok is not None
        ok = replies[0].ok
        resp = store.deserialize_cdr(bytes(ok.payload.to_bytes()),
                                     "std_srvs/msg/Trigger_Response")
        return resp, rz.parse_attachment(bytes(ok.attachment.to_bytes())), time.time()

    def forces_after(t: float, n: int) -> List[float]:
        end = time.monotonic() + 10
        while time.monotonic() < end:
            got = [m for m in rx.get(wrench_key("a", ns="cell")) if m[2] > t + 0.05]
            if len(got) >= n:
                ws = decode_all(store, got, "geometry_msgs/msg/WrenchStamped")
                return [abs(w.wrench.force.x) + abs(w.wrench.torque.z) for w in ws]
            time.sleep(0.02)
        raise AssertionError("no wrenches after the service call")

    with make_bridge(router, [spec], namespace="/cell", tare_samples=50) as bridge:
        bridge.start()
        before = forces_after(time.time() - 1, 200)
        assert min(before) > 1.0  # 0.2 x rated: far from zero
        resp, (seq, ts, gid), t_tared = call(service, 7)
        assert resp.success, resp.message
        assert "50 samples" in resp.message
        assert seq == 7 and gid == client_gid and abs(ts - time.time_ns()) < 60e9
        assert max(forces_after(t_tared, 200)) < 1e-6
        resp, (seq, _, _), t_untared = call(untare, 8)
        assert resp.success and seq == 8
        assert min(forces_after(t_untared, 200)) > 1.0


def test_liveliness_tokens_answer_a_query(router: str, client: Any) -> None:
    with make_bridge(router, [SensorSpec("a", sim={})]) as bridge:
        zid = bridge.zid
        tokens = {str(r.ok.key_expr) for r in
                  client.liveliness().get("@ros2_lv/0/**", timeout=5.0) if r.ok is not None}
        head = f"@ros2_lv/0/{zid}/0/"
        assert f"{head}0/NN/%/%/a" in tokens
        qos = "::,10:,:,:,,"
        mp = [t for t in tokens if "/MP/" in t]
        assert sorted(t.split("/")[9] for t in mp) == ["%a%diagnostics", "%a%wrench",
                                                      "%a%wrench_raw"]
        assert all(t.startswith(head) and t.endswith(qos) for t in mp)
        assert (f"/MP/%/%/a/%a%wrench/geometry_msgs::msg::dds_::WrenchStamped_/{WRENCH_HASH}/"
                f"{qos}") in "".join(mp)
        assert any(t.endswith(f"/%a%diagnostics/diagnostic_msgs::msg::dds_::"
                              f"DiagnosticArray_/{DIAG_HASH}/{qos}") for t in mp)
        ss = sorted(t.split("/")[9] for t in tokens if "/SS/" in t)
        assert ss == ["%a%tare", "%a%untare"]
        ids = [t.split("/")[4] for t in tokens]
        assert len(ids) == len(set(ids))  # one entity id each
    gone = [r for r in client.liveliness().get("@ros2_lv/0/**", timeout=2.0)
            if r.ok is not None]
    assert gone == []  # closing the bridge withdraws them


def test_diagnostics_once_a_second(router: str, client: Any, store: Any) -> None:
    key = f"0/a/diagnostics/diagnostic_msgs::msg::dds_::DiagnosticArray_/{DIAG_HASH}"
    rx = Received(client, key)
    with make_bridge(router, [SensorSpec("a", sim={})], tare_at_start=20) as bridge:
        bridge.start()
        got = rx.wait_for(key, 2, 10.0)
    assert len(got) >= 2
    check_sequence(got)
    msg = decode_all(store, got[-1:], "diagnostic_msgs/msg/DiagnosticArray")[0]
    (st,) = msg.status
    kv = {v.key: v.value for v in st.values}
    assert st.name == "leptrino: a" and st.level == 0, st.message
    assert 1000 < float(kv["measured_rate_hz"]) < 1400
    assert float(kv["nominal_rate_hz"]) == 1200
    for k in ("gaps", "lost", "errors", "overloads", "reconnects", "disconnects"):
        assert int(kv[k]) >= 0
    assert kv["tared"] == "true" and any(float(kv[f"tare_offset_{a}"]) != 0
                                         for a in ("fx", "fy", "fz", "mx", "my", "mz"))


def test_one_sensor_unplugged_while_the_other_publishes(router: str, client: Any,
                                                       store: Any, tmp_path: Path) -> None:
    rx = Received(client, "0/**")
    link = str(tmp_path / "b-port")
    specs = [SensorSpec("a", sim={}),
             SensorSpec("b", sim={"link": link, "hangup_after": 1.0, "reopen_after": 400})]
    with make_bridge(router, specs) as bridge:
        bridge.start()
        # wait (bounded) until b is back and has published for a while
        end = time.monotonic() + 20
        resumed = False
        while time.monotonic() < end and not resumed:
            time.sleep(0.1)
            tb = [t for _, _, t in rx.get(wrench_key("b"))]
            gaps = [(x, y) for x, y in zip(tb, tb[1:]) if y - x > 0.3]
            resumed = bool(gaps) and tb[-1] - gaps[0][1] > 1.0
        node_b = bridge.nodes[1]
        health_b = node_b.sensor.health
    assert resumed, "b did not come back after its hang-up"
    assert health_b.reconnects >= 1 and health_b.disconnects >= 1
    gap_from, gap_to = gaps[0]
    # a kept publishing through b's absence, without a gap or a lost message
    a_msgs = rx.get(wrench_key("a"))
    check_sequence(a_msgs)
    ta = [t for _, _, t in a_msgs]
    during = [t for t in ta if gap_from < t < gap_to]
    assert len(during) > 0.5 * 1200 * (gap_to - gap_from) * 0.5
    # b's own sequence numbers continue across its reconnect (one publisher)
    check_sequence(rx.get(wrench_key("b")))
    diag = [store.deserialize_cdr(p, "diagnostic_msgs/msg/DiagnosticArray") for p, _, _ in
            rx.get(f"0/b/diagnostics/diagnostic_msgs::msg::dds_::DiagnosticArray_/{DIAG_HASH}")]
    assert any(int({v.key: v.value for v in d.status[0].values}["reconnects"]) >= 1
               for d in diag) or health_b.reconnects >= 1


def test_a_stalled_sensor_does_not_delay_the_others(router: str, client: Any) -> None:
    """b stalls (its port stays, nothing comes: the session declares the
    stream lost and its reconnection attempts wait on a sensor that does not
    answer); a goes on publishing without a pause or a lost message. (A
    reader shared by the sensors that did not hand b to a thread of its own
    failed here: docs/bridge.md, "One reading thread for all sensors".)"""
    rx = Received(client, "0/**")
    specs = [SensorSpec("a", sim={}),
             SensorSpec("b", sim={"stall_after": 1.0, "stall": 3000})]
    with make_bridge(router, specs, data_timeout_s=0.3) as bridge:
        bridge.start()
        time.sleep(4.5)
        errors_b = bridge.nodes[1].counters.read_errors
    tb = [t for _, _, t in rx.get(wrench_key("b"))]
    b_gaps = [(x, y) for x, y in zip(tb, tb[1:]) if y - x > 0.5]
    assert b_gaps, "b did not stall"
    assert errors_b >= 1  # its stream was lost and the session tried again
    a_msgs = rx.get(wrench_key("a"))
    check_sequence(a_msgs)
    ta = [t for _, _, t in a_msgs if b_gaps[0][0] <= t <= b_gaps[0][1]]
    assert ta and max(y - x for x, y in zip(ta, ta[1:])) < 0.2, "a paused during b's stall"


def test_bad_arguments_are_refused(router: str) -> None:
    with pytest.raises(ValueError, match="differ"):
        Bridge([SensorSpec("a", sim={}), SensorSpec("a", sim={})], None,
               ZenohOptions(connect=[router]))
    with pytest.raises(ValueError, match="sensor name"):
        SensorSpec("a-b", sim={})
    with pytest.raises(ValueError, match="port or virtual"):
        SensorSpec("a")
    with pytest.raises(ValueError, match="client"):
        ZenohOptions(mode="client", listen=["tcp/127.0.0.1:0"]).config()
    with pytest.raises(leptrino.PortError):
        Bridge([SensorSpec("a", port="/nonexistent/port")], None,
               ZenohOptions(connect=[router]))


def _run_bridge(*args: str) -> Any:
    import subprocess
    import sys

    from conftest import subprocess_env

    return subprocess.run([sys.executable, "-m", "leptrino.bridge", *args], capture_output=True,
                          text=True, env=subprocess_env(), timeout=60)


def test_no_router_is_said(router: str) -> None:
    """Nobody to receive: said at the start and at the end (exit 0: the run
    itself went well); with a router there, nothing of the kind is said."""
    nobody = f"tcp/127.0.0.1:{free_port()}"
    p = _run_bridge("--sim", "a", "--connect", nobody, "--duration", "1")
    assert p.returncode == 0, p.stderr
    assert "zenoh session" in p.stderr
    assert "no Zenoh router or peer reachable" in p.stderr and nobody in p.stderr, p.stderr
    assert "nothing published was received" in p.stderr
    p = _run_bridge("--sim", "a", "--connect", router, "--duration", "1")
    assert p.returncode == 0, p.stderr
    assert "reachable" not in p.stderr and "nothing published" not in p.stderr, p.stderr
