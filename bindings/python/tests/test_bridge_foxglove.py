"""leptrino-bridge --foxglove with an independent Foxglove WebSocket client.

The bridge runs as its own process (the command line) serving two virtual
sensors on a free 127.0.0.1 port. The client here is written from the
Foxglove WebSocket protocol's specification (foxglove/ws-protocol
docs/spec.md: JSON ops, binary Message Data 0x01, Service Call Request 0x02
and Response 0x03, little-endian) with the `websockets` package and
subprotocol foxglove.sdk.v1; it builds its rosbags types from the schemas
the server advertises, decodes every message, checks a replayed ramp
sample for sample and calls the tare and untare services. Bounded waits."""

from __future__ import annotations

import asyncio
import json
import struct
import subprocess
import sys
import time
from typing import Any, Dict, List, Tuple

import pytest
from bridge_net import free_port, wait_for_port
from conftest import RAMP_ROWS

websockets = pytest.importorskip("websockets")  # the "test" extra
pytest.importorskip("foxglove")  # the "bridge" extra

import leptrino  # noqa: E402

ROWS = RAMP_ROWS  # the replayed ramp's length (conftest.ramp)
SUBPROTOCOL = "foxglove.sdk.v1"



def typestore_from(schemas: Dict[str, str]) -> Any:
    """rosbags types built from the advertised ros2msg schemas alone."""
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    ts = get_typestore(Stores.EMPTY)
    for name, text in schemas.items():
        ts.register(get_types_from_msg(text, name))
    return ts


class Client:
    """A minimal Foxglove WebSocket client (the parts used here)."""

    def __init__(self, ws: Any) -> None:
        self.ws = ws
        self.channels: Dict[str, Dict[str, Any]] = {}
        self.services: Dict[str, Dict[str, Any]] = {}
        self.info: Dict[str, Any] = {}
        self.by_sub: Dict[int, List[Tuple[int, bytes, float]]] = {}
        self.responses: Dict[int, Tuple[str, bytes]] = {}

    def handle(self, msg: Any) -> None:
        if isinstance(msg, str):
            op = json.loads(msg)
            if op["op"] == "serverInfo":
                self.info = op
            elif op["op"] == "advertise":
                for ch in op["channels"]:
                    self.channels[ch["topic"]] = ch
            elif op["op"] == "advertiseServices":
                for sv in op["services"]:
                    self.services[sv["name"]] = sv
            elif op["op"] == "serviceCallFailure":
                self.responses[op["callId"]] = ("error", op["message"].encode())
            return
        data = bytes(msg)
        if data[0] == 0x01:  # Message Data
            sub, ts = struct.unpack_from("<IQ", data, 1)
            self.by_sub.setdefault(sub, []).append((ts, data[13:], time.time()))
        elif data[0] == 0x03:  # Service Call Response
            _sid, call, n = struct.unpack_from("<III", data, 1)
            self.responses[call] = (data[13:13 + n].decode(), data[13 + n:])

    async def pump(self, until: Any, timeout: float) -> None:
        end = time.monotonic() + timeout
        while not until() and time.monotonic() < end:
            try:
                msg = await asyncio.wait_for(self.ws.recv(), max(0.01, end - time.monotonic()))
            except asyncio.TimeoutError:
                break
            self.handle(msg)

    async def call(self, name: str, payload: bytes, call_id: int) -> Tuple[str, bytes]:
        sid = self.services[name]["id"]
        await self.ws.send(struct.pack("<BIII", 0x02, sid, call_id, 3) + b"cdr" + payload)
        await self.pump(lambda: call_id in self.responses, 10.0)
        return self.responses[call_id]


async def session(port: int) -> Dict[str, Any]:
    out: Dict[str, Any] = {}
    async with websockets.connect(f"ws://127.0.0.1:{port}", subprotocols=[SUBPROTOCOL],
                                  max_size=None, open_timeout=10) as ws:
        out["subprotocol"] = ws.subprotocol
        c = Client(ws)
        topics = [f"/{s}/{t}" for s in ("a", "r") for t in ("wrench", "wrench_raw", "diagnostics")]
        await c.pump(lambda: set(topics) <= set(c.channels) and len(c.services) >= 4, 10.0)
        out["info"], out["channels"], out["services"] = c.info, dict(c.channels), dict(c.services)
        subs = {"/r/wrench_raw": 1, "/a/wrench": 2, "/a/diagnostics": 3}
        await ws.send(json.dumps({"op": "subscribe", "subscriptions": [
            {"id": i, "channelId": c.channels[t]["id"]} for t, i in subs.items()]}))
        await c.pump(lambda: len(c.by_sub.get(1, [])) >= 1500, 20.0)
        before = len(c.by_sub.get(2, []))
        req = b"\x00\x01\x00\x00\x00"  # std_srvs/srv/Trigger_Request in CDR
        out["tare"] = await c.call("/a/tare", req, 41)
        t_tare = time.time()
        await c.pump(lambda: len(c.by_sub.get(2, [])) >= before + 600, 10.0)
        out["untare"] = await c.call("/a/untare", req, 42)
        out["garbage"] = await c.call("/a/tare", b"\xff\xff\xff\xff", 43)  # not CDR: refused
        t_untare = time.time()
        n = len(c.by_sub.get(2, []))
        await c.pump(lambda: len(c.by_sub.get(2, [])) >= n + 600, 10.0)
        out["t"] = (t_tare, t_untare)
        out["msgs"] = {t: c.by_sub.get(i, []) for t, i in subs.items()}
    return out


def test_foxglove_client_subscribes_decodes_and_tares(ramp: str) -> None:
    port = free_port()
    proc = subprocess.Popen(
        [sys.executable, "-m", "leptrino.bridge", "--foxglove", f"127.0.0.1:{port}",
         "--sim", "a,constant,amplitude=0.2", "--sim", f"r,replay={ramp}", "--retare", "50"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        wait_for_port(port)  # the server is up when its port answers
        got = asyncio.run(asyncio.wait_for(session(port), 90))
    finally:
        proc.terminate()
        try:
            _, err = proc.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()
            _, err = proc.communicate(timeout=10)
    assert proc.returncode == 0, err
    assert got["subprotocol"] == SUBPROTOCOL
    assert "services" in got["info"]["capabilities"]
    assert "cdr" in got["info"].get("supportedEncodings", [])
    chans = got["channels"]
    for topic in ("/a/wrench", "/r/wrench_raw"):
        ch = chans[topic]
        assert (ch["encoding"], ch["schemaName"], ch["schemaEncoding"]) == (
            "cdr", "geometry_msgs/msg/WrenchStamped", "ros2msg")
    assert chans["/a/diagnostics"]["schemaName"] == "diagnostic_msgs/msg/DiagnosticArray"
    tare = got["services"]["/a/tare"]
    assert tare["type"] == "std_srvs/srv/Trigger"
    assert tare["request"]["encoding"] == "cdr" and tare["response"]["encoding"] == "cdr"
    # the client's own types, from the advertised schemas only
    ts = typestore_from({
        "geometry_msgs/msg/WrenchStamped": chans["/a/wrench"]["schema"],
        "diagnostic_msgs/msg/DiagnosticArray": chans["/a/diagnostics"]["schema"],
        "std_srvs/msg/Trigger_Response": tare["response"]["schema"],
    })
    W = "geometry_msgs/msg/WrenchStamped"

    rated = leptrino.Simulator.model_rated("PFS055YA501U6")
    scale = [float(v) / 10000.0 for v in rated]
    ramp_msgs = got["msgs"]["/r/wrench_raw"]
    assert len(ramp_msgs) >= 1500
    prev = None
    last_ns = 0
    for log_ns, payload, _ in ramp_msgs:  # every sample, in order
        m = ts.deserialize_cdr(payload, W)
        stamp = m.header.stamp.sec * 10**9 + m.header.stamp.nanosec
        assert stamp == log_ns and stamp >= last_ns and m.header.frame_id == "r"
        last_ns = stamp
        fx = round(m.wrench.force.x / scale[0])
        if prev is not None:
            assert fx == (prev + 1 if prev < ROWS - 3001 else -3000), (prev, fx)
        prev = fx
        k = fx + 3000
        assert round(m.wrench.force.y / scale[1]) == -fx
        assert round(m.wrench.force.z / scale[2]) == 3 * (k % 100)
        assert round(m.wrench.torque.x / scale[3]) == 100 * (k % 7)
    assert abs(last_ns - time.time_ns()) < 120e9

    for which, word in (("tare", "50 samples"), ("untare", "removed")):
        enc, payload = got[which]
        assert enc == "cdr", payload
        r = ts.deserialize_cdr(payload, "std_srvs/msg/Trigger_Response")
        assert r.success and word in r.message, r.message
    # a request that is not CDR: a service call failure, and no tare (the wrench after the
    # untare, below, keeps its offset)
    assert got["garbage"][0] == "error" and b"malformed request" in got["garbage"][1]
    t_tare, t_untare = got["t"]
    a = [(t, ts.deserialize_cdr(p, W)) for _, p, t in got["msgs"]["/a/wrench"]]
    size = [(t, abs(m.wrench.force.x) + abs(m.wrench.torque.z)) for t, m in a]
    assert min(v for t, v in size if t < t_tare - 0.5) > 1.0
    tared = [v for t, v in size if t_tare + 0.2 < t < t_untare - 0.1]
    assert tared and max(tared) < 1e-6
    assert min(v for t, v in size if t > t_untare + 0.2) > 1.0
    diags = [ts.deserialize_cdr(p, "diagnostic_msgs/msg/DiagnosticArray")
             for _, p, _ in got["msgs"]["/a/diagnostics"]]
    assert diags and diags[0].status[0].name == "leptrino: a"


def test_layout_file_uses_the_bridges_topics() -> None:
    """docs/foxglove-layout.json plots the six axes of sensor a's topics and
    shows its diagnostics; its services are the bridge's."""
    from conftest import ROOT

    if ROOT is None:
        pytest.skip("not run from a leptrino checkout")
    layout = json.loads((ROOT / "docs" / "foxglove-layout.json").read_text(encoding="utf-8"))
    cfg = layout["configById"]
    plots = [v for k, v in cfg.items() if k.startswith("Plot!")]
    paths = {p["value"] for v in plots for p in v["paths"]}
    want = {f"/a/wrench.wrench.{v}.{c}" for v in ("force", "torque") for c in "xyz"}
    assert len(plots) == 6 and want <= paths
    assert all(p.split(".")[0] in ("/a/wrench", "/a/wrench_raw") for p in paths)
    diag = [v for k, v in cfg.items() if k.startswith("Diagnostic")]
    assert len(diag) == 2 and all(v["topicToRender"] == "/a/diagnostics" for v in diag)
    services = {v["serviceName"] for k, v in cfg.items() if k.startswith("CallService!")}
    assert services == {"/a/tare", "/a/untare"}
    # every panel the layout tree names is configured, and every configured one is placed
    def leaves(node: Any) -> List[str]:
        return [node] if isinstance(node, str) else leaves(node["first"]) + leaves(node["second"])
    assert sorted(leaves(layout["layout"])) == sorted(cfg)
