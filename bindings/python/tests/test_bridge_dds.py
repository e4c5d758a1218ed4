"""leptrino-bridge --dds received by a real Cyclone DDS reader on 127.0.0.1.

The bridge runs as its own process (the command line, two virtual sensors
replaying a known ramp); this process is an independent ROS 2-style DDS
participant with its own IDL types, named as rosidl names them, restricted
to 127.0.0.1 (no multicast). Checked: every sample of both sensors in order
with its values and stamps, the type names, USER_DATA and QoS the ROS 2
middlewares look at, the node announcement on ros_discovery_info, and the
tare/untare command topics. Every wait is bounded."""

# no "from __future__ import annotations": cyclonedds resolves the IDL
# classes' annotations as objects

import os
import subprocess
import sys
import time
from typing import Any, Dict, Iterator, List

import pytest
from conftest import RAMP_ROWS

cyclonedds = pytest.importorskip("cyclonedds")  # the "bridge" extra

from cyclonedds.core import Qos  # noqa: E402
from cyclonedds.domain import Domain, DomainParticipant  # noqa: E402
from cyclonedds.pub import DataWriter  # noqa: E402
from cyclonedds.qos import Policy  # noqa: E402
from cyclonedds.sub import DataReader  # noqa: E402
from cyclonedds.topic import Topic  # noqa: E402

from ros_dds_types import (DiagnosticArray_, Empty_, ParticipantEntitiesInfo_,  # noqa: E402
                            ParticipantEntitiesInfo24_, WrenchStamped_)

import leptrino  # noqa: E402

WRENCH_HASH = "RIHS01_8dc3deaf06b2ab281f9f9a742a8961c328ca7cec16e3fd6586d3a5c83fa78f77"
ROWS = RAMP_ROWS  # the replayed ramp's length (conftest.ramp)


LOOPBACK = ("<CycloneDDS><Domain Id=\"any\"><General><Interfaces>"
            "<NetworkInterface address=\"127.0.0.1\"/></Interfaces>"
            "<AllowMulticast>false</AllowMulticast></General><Discovery>"
            "<ParticipantIndex>auto</ParticipantIndex>"
            "<MaxAutoParticipantIndex>60</MaxAutoParticipantIndex>"
            "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery></Domain></CycloneDDS>")


@pytest.fixture(scope="module")
def domain() -> Iterator[int]:
    """A domain of its own (other jobs on this machine may use DDS too)."""
    d = 100 + os.getpid() % 100
    dom = Domain(d, LOOPBACK)
    try:
        yield d
    finally:
        del dom


@pytest.fixture(scope="module")
def participant(domain: int) -> Any:
    return DomainParticipant(domain)



def reader_qos(reliable: bool = True) -> Qos:
    rel = Policy.Reliability.Reliable(0) if reliable else Policy.Reliability.BestEffort
    return Qos(rel, Policy.Durability.Volatile, Policy.History.KeepAll,
               Policy.DataRepresentation(use_cdrv0_representation=True))


def start_bridge(domain: int, *args: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "leptrino.bridge", "--dds", "--dds-impl", "cyclone",
         "--dds-interface", "127.0.0.1",
         "--domain", str(domain), *args],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def stop(proc: subprocess.Popen) -> str:
    proc.terminate()
    try:
        _, err = proc.communicate(timeout=20)
    except subprocess.TimeoutExpired:
        proc.kill()
        _, err = proc.communicate(timeout=10)
    return err


def take_until(readers: Dict[str, DataReader], n: int, timeout: float
               ) -> Dict[str, List[Any]]:
    got: Dict[str, List[Any]] = {k: [] for k in readers}
    end = time.monotonic() + timeout
    while time.monotonic() < end and min(len(v) for v in got.values()) < n:
        for k, r in readers.items():
            got[k] += [s for s in r.take(500) if isinstance(s, WrenchStamped_)]
        time.sleep(0.02)
    return got


def test_cyclone_reader_gets_every_sample(participant: Any, domain: int, ramp: str) -> None:
    rated = leptrino.Simulator.model_rated("PFS055YA501U6")
    scale = [float(v) / 10000.0 for v in rated]
    readers: Dict[str, DataReader] = {}
    topics = []
    for name in ("left", "right"):
        for topic in ("wrench", "wrench_raw"):
            tp = Topic(participant, f"rt/{name}/{topic}", WrenchStamped_,
                       qos=Qos(Policy.DataRepresentation(use_cdrv0_representation=True)))
            topics.append(tp)
            readers[f"{name}/{topic}"] = DataReader(participant, tp, qos=reader_qos())
    info = DataReader(participant, Topic(participant, "ros_discovery_info",
                                         ParticipantEntitiesInfo_),
                      qos=Qos(Policy.Reliability.Reliable(0), Policy.Durability.TransientLocal,
                              Policy.History.KeepLast(1)))
    proc = start_bridge(domain, "--sim", f"left,replay={ramp}", "--sim", f"right,replay={ramp}",
                        "--frame-id", "left=left_ft")
    try:
        got = take_until(readers, 2400, 30.0)
        # what a ROS 2 middleware matches on: names, USER_DATA, QoS
        handles = readers["left/wrench"].get_matched_publications()
        assert len(handles) == 1
        ep = readers["left/wrench"].get_matched_publication_data(handles[0])
        infos = [s for s in info.read(10) if isinstance(s, ParticipantEntitiesInfo_)]
    finally:
        err = stop(proc)
    assert proc.returncode == 0, err
    assert ep.topic_name == "rt/left/wrench"
    assert ep.type_name == "geometry_msgs::msg::dds_::WrenchStamped_"
    assert ep.qos[Policy.Userdata].data == f"typehash={WRENCH_HASH};".encode()
    assert ep.qos[Policy.Reliability] == Policy.Reliability.Reliable(100_000_000)
    assert ep.qos[Policy.Durability] == Policy.Durability.Volatile
    assert ep.qos[Policy.History] == Policy.History.KeepLast(10)
    # the node announcement: both nodes, their writers' GIDs among them
    assert infos, "nothing on ros_discovery_info"
    nodes = {n.node_name: n for n in infos[-1].node_entities_info_seq}
    assert set(nodes) == {"left", "right"} and nodes["left"].node_namespace == "/"
    writer_gids = {bytes(g.data) for g in nodes["left"].writer_gid_seq}
    # 3 topics and the 2 services' reply writers; the tare, untare and
    # gravity topics' readers and the services' request readers
    assert ep.key.bytes in writer_gids and len(writer_gids) == 5
    assert len(nodes["left"].reader_gid_seq) == 5
    assert bytes(infos[-1].gid.data) == ep.participant_key.bytes

    for name, frame in (("left", "left_ft"), ("right", "right")):
        raw, proc_ = got[f"{name}/wrench_raw"], got[f"{name}/wrench"]
        assert len(raw) >= 2400 and len(proc_) >= 2400, (name, len(raw), len(proc_))
        assert {m.header.frame_id for m in raw + proc_} == {frame}
        stamps = [m.header.stamp.sec * 10**9 + m.header.stamp.nanosec for m in raw]
        assert all(b >= a for a, b in zip(stamps, stamps[1:]))
        assert abs(stamps[-1] - time.time_ns()) < 60e9
        prev = None
        for m in raw:  # every sample, in order: the next row of the ramp each time
            f, q = m.wrench.force, m.wrench.torque
            fx = round(f.x / scale[0])
            if prev is not None:
                assert fx == (prev + 1 if prev < ROWS - 3001 else -3000), (name, prev, fx)
            prev = fx
            k = fx + 3000
            assert round(f.y / scale[1]) == -fx
            assert round(f.z / scale[2]) == 3 * (k % 100)
            assert round(q.x / scale[3]) == 100 * (k % 7)
            assert (round(q.y / scale[4]), round(q.z / scale[5])) == (1234, -1234)
        # nothing asked of the session: wrench is wrench_raw, stamp for stamp
        by_stamp = {(m.header.stamp.sec, m.header.stamp.nanosec, m.wrench.force.x): m
                    for m in raw}
        same = [by_stamp.get((m.header.stamp.sec, m.header.stamp.nanosec,
                              m.wrench.force.x)) == m for m in proc_]
        assert sum(same) > 2000


def test_tare_command_topic_and_diagnostics(participant: Any, domain: int) -> None:
    tp = Topic(participant, "rt/cell/a/wrench", WrenchStamped_)
    rd = DataReader(participant, tp, qos=reader_qos(reliable=False))  # best effort matches too
    dtp = Topic(participant, "rt/cell/a/diagnostics", DiagnosticArray_)
    drd = DataReader(participant, dtp, qos=reader_qos())
    cmd = {k: DataWriter(participant, Topic(participant, f"rt/cell/a/{k}", Empty_),
                         qos=Qos(Policy.Reliability.Reliable(0)))
           for k in ("tare", "untare")}
    proc = start_bridge(domain, "--sim", "a,constant,amplitude=0.2", "--namespace", "/cell",
                        "--retare", "50")

    def forces(n: int) -> List[float]:
        end = time.monotonic() + 15
        out: List[Any] = []
        while time.monotonic() < end and len(out) < n:
            out += [s for s in rd.take(500) if isinstance(s, WrenchStamped_)]
            time.sleep(0.02)
        assert len(out) >= n
        return [abs(m.wrench.force.x) + abs(m.wrench.torque.z) for m in out]

    def command(k: str) -> None:
        end = time.monotonic() + 10
        while time.monotonic() < end and not cmd[k].get_publication_matched_status().current_count:
            time.sleep(0.05)
        cmd[k].write(Empty_(structure_needs_at_least_one_member=0))
        time.sleep(1.0)  # the tare averages 50 samples (42 ms) and the stream goes on
        rd.take(5000)

    try:
        assert min(forces(200)) > 1.0
        command("tare")
        assert max(forces(200)) < 1e-6
        diags: List[Any] = []
        end = time.monotonic() + 5
        while time.monotonic() < end and not diags:
            diags = [s for s in drd.take(10) if isinstance(s, DiagnosticArray_)]
            time.sleep(0.05)
        kv = {v.key: v.value for v in diags[-1].status[0].values}
        assert kv["tared"] == "true" and diags[-1].status[0].name == "leptrino: a"
        command("untare")
        assert min(forces(200)) > 1.0
    finally:
        err = stop(proc)
    assert proc.returncode == 0, err


def test_humble_node_announcement(domain: int) -> None:
    """--ros-distro humble: the Gid is 24 bytes, the GUID then zeros."""
    # a domain (and a participant) of its own for the other layout: 200..229,
    # apart from the module's 100..199 (DDS domain ids end at 232)
    d = 200 + domain % 30
    dom = Domain(d, LOOPBACK)
    p = DomainParticipant(d)
    info = DataReader(p, Topic(p, "ros_discovery_info", ParticipantEntitiesInfo24_),
                      qos=Qos(Policy.Reliability.Reliable(0), Policy.Durability.TransientLocal,
                              Policy.History.KeepLast(1)))
    proc = start_bridge(d, "--sim", "h", "--ros-distro", "humble", "--namespace", "/lab")
    try:
        got: List[Any] = []
        end = time.monotonic() + 15
        while time.monotonic() < end and not got:
            got = [s for s in info.read(10) if isinstance(s, ParticipantEntitiesInfo24_)]
            time.sleep(0.05)
    finally:
        err = stop(proc)
        del dom
    assert proc.returncode == 0, err
    assert got, "nothing on ros_discovery_info"
    (node,) = got[-1].node_entities_info_seq
    assert (node.node_namespace, node.node_name) == ("/lab", "h")
    gids = [bytes(g.data) for g in [got[-1].gid, *node.writer_gid_seq, *node.reader_gid_seq]]
    # participant, 5 writers, 5 readers
    assert len(gids) == 11 and all(len(g) == 24 and g[16:] == bytes(8) for g in gids)
    assert len(set(gids)) == 11
