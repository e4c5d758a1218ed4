"""leptrino-bridge --read-only, and who tared: on each transport (a Zenoh
service, a DDS service and command topic, a Foxglove service), a tare
request to a read-only bridge finds nothing to answer it (no queryable, no
matching DDS reader, no Foxglove service) and changes nothing: the wrench
keeps its offset, nothing is counted as tared, the streams go on. Without
--read-only the same request tares, and the log and the diagnostics (so the
MCAP file) name the requester. Everything on 127.0.0.1, every wait bounded.
"""

# no "from __future__ import annotations": cyclonedds resolves the IDL
# classes' annotations as objects

import asyncio
import json
import logging
import struct
import subprocess
import sys
import time
from pathlib import Path
from typing import Any, Dict, List, Tuple

import pytest

pytest.importorskip("zenoh")  # the "bridge" extra
pytest.importorskip("cyclonedds")
pytest.importorskip("foxglove")
websockets = pytest.importorskip("websockets")  # the "test" extra

import zenoh  # noqa: E402
from bridge_net import free_port, wait_for_port  # noqa: E402
from cyclonedds.pub import DataWriter  # noqa: E402
from cyclonedds.sub import DataReader  # noqa: E402
from cyclonedds.topic import Topic  # noqa: E402
from test_bridge_dds import DiagnosticArray_, Empty_, reader_qos  # noqa: E402
from test_bridge_dds import start_bridge, stop  # noqa: E402
from test_bridge_dds_services import Client as DdsClient  # noqa: E402
from test_bridge_dds_services import TriggerRequest_  # noqa: E402
from test_bridge_dds_services import diagnostics, domain, forces  # noqa: E402,F401
from test_bridge_dds_services import participant, wrench_reader  # noqa: E402,F401
from test_bridge_foxglove import SUBPROTOCOL  # noqa: E402
from test_bridge_foxglove import Client as FoxClient  # noqa: E402
from test_bridge_zenoh import TRIGGER_HASH, Received, client, router  # noqa: E402,F401
from test_bridge_zenoh import store, wrench_key  # noqa: E402,F401

from leptrino.bridge import Bridge, NodeOptions, SensorSpec, ZenohOptions  # noqa: E402
from leptrino.bridge import cdr  # noqa: E402
from leptrino.bridge import rmw_zenoh as rz  # noqa: E402
from leptrino.bridge.node import AUDIT_LOGGER  # noqa: E402

CONSTANT = "a,constant,amplitude=0.2"  # 0.2 x rated on every axis: far from zero


def sizes(store: Any, msgs: List[Tuple[bytes, bytes, float]]) -> List[float]:
    ws = [store.deserialize_cdr(p, "geometry_msgs/msg/WrenchStamped") for p, _, _ in msgs]
    return [abs(w.wrench.force.x) + abs(w.wrench.torque.z) for w in ws]


def wait_after(rx: Received, key: str, t: float, n: int, timeout: float = 10.0) -> List[Any]:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        got = [m for m in rx.get(key) if m[2] > t]
        if len(got) >= n:
            return got
        time.sleep(0.02)
    raise AssertionError(f"fewer than {n} wrenches after {t}")


def mcap_diagnostics(path: Path, store: Any) -> List[Dict[str, str]]:
    """The diagnostics' values of sensor a, as recorded in the MCAP file."""
    from mcap.reader import make_reader

    out = []
    with open(path, "rb") as f:
        for _schema, channel, message in make_reader(f).iter_messages(topics=["/a/diagnostics"]):
            m = store.deserialize_cdr(message.data, "diagnostic_msgs/msg/DiagnosticArray")
            out.append({kv.key: kv.value for kv in m.status[0].values})
    return out


@pytest.mark.parametrize("read_only", [True, False])
def test_zenoh_tare_service(router: str, client: Any, store: Any, tmp_path: Path,
                            caplog: Any, read_only: bool) -> None:
    key = wrench_key("a")
    rx = Received(client, key)
    tokens: List[str] = []
    service = f"0/a/tare/std_srvs::srv::dds_::Trigger_/{TRIGGER_HASH}"
    client_gid = bytes(range(200, 216))
    mcap = tmp_path / "a.mcap"
    caplog.set_level(logging.INFO, logger=AUDIT_LOGGER)
    with Bridge([SensorSpec("a", sim={"constant": True, "amplitude": 0.2})],
                NodeOptions(tare_samples=50, read_only=read_only),
                ZenohOptions(mode="peer", connect=[router]), mcap_path=str(mcap)) as bridge:
        bridge.start()
        time.sleep(0.3)  # the bridge's declarations reach the router (bounded)
        assert min(sizes(store, wait_after(rx, key, 0.0, 200))) > 1.0
        tokens = [str(r.ok.key_expr) for r in client.liveliness().get("@ros2_lv/**",
                                                                          timeout=5.0)
                  if r.ok is not None]
        replies = list(client.get(
            service, payload=cdr.encode_trigger_request(),
            attachment=rz.attachment(3, time.time_ns(), client_gid),
            target=zenoh.QueryTarget.ALL_COMPLETE, timeout=3.0))
        t_asked = time.time()
        after = sizes(store, wait_after(rx, key, t_asked + 0.05, 200))
        node = bridge.nodes[0]
        kv = dict(node.diagnostic_status()[4])
    assert kv["read_only"] == ("true" if read_only else "false")
    assert any("/a/wrench" in t or "%a%wrench" in t for t in tokens), tokens
    if read_only:
        assert replies == []  # nothing declared: nobody answers
        assert not any("tare" in t or "gravity" in t for t in tokens), tokens
        assert min(after) > 1.0  # the wrench keeps its offset
        assert (kv["tared"], kv["tare_requests"], kv["last_request"]) == ("false", "0", "")
        assert any("read-only" in r.getMessage() for r in caplog.records)
    else:
        assert len(replies) == 1 and replies[0].ok is not None
        assert max(after) < 1e-6  # tared
        who = f"tare by zenoh client {client_gid.hex()}"
        assert kv["tared"] == "true" and kv["last_request"].startswith(who), kv
        assert [r for r in caplog.records if who in r.getMessage()]
        recorded = [d["last_request"] for d in mcap_diagnostics(mcap, store)]
        assert any(r.startswith(who) for r in recorded), recorded


def test_dds_service_and_command_topic(participant: Any, domain: int) -> None:
    """Read-only: no reader matches the service's request writer nor the
    command topic's writer, nothing tares; then a bridge without it answers
    and logs the client's GUID."""
    p = participant
    rd = wrench_reader(p, "/a")
    drd = DataReader(p, Topic(p, "rt/a/diagnostics", DiagnosticArray_), qos=reader_qos())
    svc = DdsClient(p, "/a/tare", "1.2.3.4.5.6.7.8.9.a.b.c.0.0.2.1")
    cmd = DataWriter(p, Topic(p, "rt/a/tare", Empty_), qos=reader_qos(reliable=False))
    proc = start_bridge(domain, "--sim", CONSTANT, "--retare", "50", "--read-only")
    try:
        assert min(forces(rd, 200)) > 1.0
        time.sleep(1.0)  # discovery had its time: the wrench reader matched meanwhile
        assert svc.writer.get_publication_matched_status().current_count == 0
        assert svc.reader.get_subscription_matched_status().current_count == 0
        assert cmd.get_publication_matched_status().current_count == 0
        svc.writer.write(TriggerRequest_(
            client_guid=svc.guid, sequence_number=1, structure_needs_at_least_one_member=0))
        cmd.write(Empty_(structure_needs_at_least_one_member=0))
        assert min(forces(rd, 600)) > 1.0  # streaming on, nothing tared
        kv = diagnostics(drd)
        assert (kv["read_only"], kv["tared"], kv["tare_requests"]) == ("true", "false", "0")
    finally:
        err = stop(proc)
    assert proc.returncode == 0, err
    assert "read-only" in err

    proc = start_bridge(domain, "--sim", CONSTANT, "--retare", "50")
    try:
        assert min(forces(rd, 200)) > 1.0
        r = svc.call(seq=2)
        assert r.success, r.message
        assert max(forces(rd, 200)) < 1e-6
        kv = diagnostics(drd)
        assert kv["read_only"] == "false"
        assert kv["last_request"].startswith(f"tare by dds client {svc.guid:016x} at "), kv
        end = time.monotonic() + 10  # the command topic: its writer's GUID
        while time.monotonic() < end and not cmd.get_publication_matched_status().current_count:
            time.sleep(0.05)
        cmd.write(Empty_(structure_needs_at_least_one_member=0))
        end = time.monotonic() + 10
        while time.monotonic() < end and kv["tare_requests"] != "2":
            kv = diagnostics(drd)
        assert kv["last_request"].startswith(f"tare by dds writer {cmd.guid} at "), kv
    finally:
        err = stop(proc)
    assert proc.returncode == 0, err
    assert f"tare by dds client {svc.guid:016x}" in err  # said without --verbose
    assert f"tare by dds writer {cmd.guid}" in err


async def fox_session(port: int, read_only: bool) -> Dict[str, Any]:
    out: Dict[str, Any] = {}
    async with websockets.connect(f"ws://127.0.0.1:{port}", subprotocols=[SUBPROTOCOL],
                                  max_size=None, open_timeout=10) as ws:
        c = FoxClient(ws)
        await c.pump(lambda: "/a/wrench" in c.channels and (read_only or len(c.services) >= 2),
                     10.0)
        await c.pump(lambda: False, 0.5)  # services advertised late would come now
        out["services"], out["info"] = dict(c.services), c.info
        await ws.send(json.dumps({"op": "subscribe", "subscriptions": [
            {"id": 1, "channelId": c.channels["/a/wrench"]["id"]}]}))
        await c.pump(lambda: len(c.by_sub.get(1, [])) >= 300, 10.0)
        req = b"\x00\x01\x00\x00\x00"  # std_srvs/srv/Trigger_Request in CDR
        if read_only:  # a call to a service id the server does not have
            await ws.send(struct.pack("<BIII", 0x02, 1, 7, 3) + b"cdr" + req)
            await c.pump(lambda: 7 in c.responses, 2.0)
        else:
            out["tare"] = await c.call("/a/tare", req, 7)
        out["response"] = c.responses.get(7)
        t = time.time()
        await c.pump(lambda: len([m for m in c.by_sub.get(1, []) if m[2] > t + 0.3]) >= 300,
                     10.0)
        out["after"] = [m for m in c.by_sub.get(1, []) if m[2] > t + 0.3]
    return out


@pytest.mark.parametrize("read_only", [True, False])
def test_foxglove_tare_service(read_only: bool) -> None:
    from rosbags.typesys import Stores, get_typestore

    port = free_port()
    proc = subprocess.Popen(
        [sys.executable, "-m", "leptrino.bridge", "--foxglove", f"127.0.0.1:{port}",
         "--sim", CONSTANT, "--retare", "50", *(["--read-only"] if read_only else [])],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        wait_for_port(port)  # the server is up when its port answers
        got = asyncio.run(asyncio.wait_for(fox_session(port, read_only), 60))
    finally:
        err = stop(proc)
    assert proc.returncode == 0, err
    ts = get_typestore(Stores.ROS2_JAZZY)
    after = [ts.deserialize_cdr(d, "geometry_msgs/msg/WrenchStamped") for _, d, _ in
             got["after"]]
    size = [abs(w.wrench.force.x) + abs(w.wrench.torque.z) for w in after]
    assert len(size) >= 300  # the stream went on
    if read_only:
        assert got["services"] == {}
        caps = got["info"]["capabilities"]
        assert "services" not in caps and "clientPublish" not in caps, caps
        assert got["response"] is None or got["response"][0] == "error"
        assert min(size) > 1.0  # not tared
        assert "read-only" in err
        assert "tare by" not in err
    else:
        assert set(got["services"]) == {"/a/tare", "/a/untare"}
        assert {"services", "clientPublish"} <= set(got["info"]["capabilities"])
        assert max(size) < 1e-6
        lines = [ln for ln in err.splitlines() if "a: tare by foxglove client " in ln]
        assert len(lines) == 1 and ": done" in lines[0], err
