"""leptrino-bridge --dds: tare/untare as ROS 2 services in rmw_cyclonedds'
mapping, called by independent clients on 127.0.0.1.

Each client here is built as rmw_cyclonedds builds one (docs/bridge.md,
"Services on DDS"): a writer of `rq/<service>Request` and a reader of
`rr/<service>Reply`, types `std_srvs::srv::dds_::Trigger_Request_` /
`Trigger_Response_` of its own whose first two fields are the request header
(the client's 64-bit id, the request's sequence number), USER_DATA
`clientid=...;`, and replies filtered by the client id. Checked: tare then
untare take effect and are answered with the caller's header; two clients
with the same sequence number each get their own reply; malformed requests
(no header as rmw_fastrtps sends, truncated, not CDR, too long) are counted
in diagnostics, logged once and ignored while the wrench keeps streaming.
Every wait is bounded."""

# no "from __future__ import annotations": cyclonedds resolves the IDL
# classes' annotations as objects

import os
import subprocess
import time
from typing import Any, Dict, Iterator, List

import pytest

cyclonedds = pytest.importorskip("cyclonedds")  # the "bridge" extra

from cyclonedds.core import Qos  # noqa: E402
from cyclonedds.domain import Domain, DomainParticipant  # noqa: E402
from cyclonedds.pub import DataWriter  # noqa: E402
from cyclonedds.qos import Policy  # noqa: E402
from cyclonedds.sub import DataReader  # noqa: E402
from cyclonedds.topic import Topic  # noqa: E402
from test_bridge_dds import (LOOPBACK, DiagnosticArray_, ParticipantEntitiesInfo_,  # noqa: E402
                             WrenchStamped_, reader_qos, start_bridge, stop)
from test_bridge_fastdds import peer  # noqa: E402,F401 (the Fast DDS peer, a fixture)
from ros_dds_types import TriggerRequest_, TriggerResponse_  # noqa: E402

from leptrino.bridge import dds  # noqa: E402

TRIGGER_HASH = "RIHS01_eeff2cd6fa5ad9d27cdf4dec64818317839b62f212a91e6b5304b634b2062c5f"


@pytest.fixture(scope="module")
def domain() -> Iterator[int]:
    """A domain of its own: 20..89, apart from test_bridge_dds' 100..229."""
    d = 20 + os.getpid() % 70
    dom = Domain(d, LOOPBACK)
    try:
        yield d
    finally:
        del dom


@pytest.fixture(scope="module")
def participant(domain: int) -> Any:
    return DomainParticipant(domain)


def user_data(ep: Any) -> Dict[str, str]:
    text = bytes(ep.qos[Policy.Userdata].data).decode()
    return dict(kv.split("=", 1) for kv in text.split(";") if kv)


def test_request_header_both_byte_orders() -> None:
    """What parse_trigger_request reads is what a client serializes, and the
    reply decodes with the client's own type, header and all."""
    req = TriggerRequest_(client_guid=0x1122334455667788, sequence_number=-5,
                          structure_needs_at_least_one_member=0)
    le = req.serialize()  # Cyclone's Python serializer: little-endian, padded
    assert le[:2] == b"\x00\x01"
    assert dds.parse_trigger_request(le) == (0x1122334455667788, -5)
    be = (b"\x00\x00\x00\x00" + (0x1122334455667788).to_bytes(8, "big")
          + (-5).to_bytes(8, "big", signed=True) + b"\x00")
    assert dds.parse_trigger_request(be) == (0x1122334455667788, -5)
    for bad in (b"", b"\x00\x01\x00\x00\x00", le[:20], le + bytes(4), b"\x01\x01" + le[2:],
                b"\x00\x02" + le[2:]):
        with pytest.raises(ValueError):
            dds.parse_trigger_request(bad)
    reply = dds.encode_trigger_reply(2**64 - 1, 2**62, True, "tared: \u00e9")
    assert len(reply) % 4 == 0
    got = TriggerResponse_.deserialize(reply)
    assert (got.client_guid, got.sequence_number, got.success, got.message) == (
        2**64 - 1, 2**62, True, "tared: \u00e9")


class Client:
    """An rmw_cyclonedds-style client of one std_srvs/srv/Trigger service."""

    def __init__(self, p: Any, service: str, clientid: str) -> None:
        qos = Qos(Policy.Reliability.Reliable(1_000_000_000), Policy.Durability.Volatile,
                  Policy.History.KeepLast(10),
                  Policy.DataRepresentation(use_cdrv0_representation=True),
                  Policy.Userdata(f"clientid={clientid};typehash={TRIGGER_HASH};".encode()))
        tq = Qos(Policy.DataRepresentation(use_cdrv0_representation=True))
        self.writer = DataWriter(p, Topic(p, f"rq{service}Request", TriggerRequest_, qos=tq),
                                 qos=qos)
        self.reader = DataReader(p, Topic(p, f"rr{service}Reply", TriggerResponse_, qos=tq),
                                 qos=qos)
        # what rmw_cyclonedds puts in the header (the binding gives it signed)
        self.guid = self.writer.instance_handle % 2**64
        self.others: List[TriggerResponse_] = []  # replies to other clients

    def wait_matched(self, timeout: float = 10.0) -> None:
        end = time.monotonic() + timeout
        while time.monotonic() < end and not (
                self.writer.get_publication_matched_status().current_count
                and self.reader.get_subscription_matched_status().current_count):
            time.sleep(0.05)
        assert self.writer.get_publication_matched_status().current_count == 1
        assert self.reader.get_subscription_matched_status().current_count == 1

    def call(self, seq: int, timeout: float = 10.0) -> TriggerResponse_:
        self.wait_matched()
        self.writer.write(TriggerRequest_(client_guid=self.guid, sequence_number=seq,
                                          structure_needs_at_least_one_member=0))
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            for r in self.reader.take(10):
                if not isinstance(r, TriggerResponse_):
                    continue
                if r.client_guid != self.guid:  # as rmw_cyclonedds' take_response filters
                    self.others.append(r)
                elif r.sequence_number == seq:
                    return r
            time.sleep(0.01)
        raise AssertionError(f"no reply to request {seq} within {timeout} s")


def wrench_reader(p: Any, name: str) -> DataReader:
    return DataReader(p, Topic(p, f"rt{name}/wrench", WrenchStamped_),
                      qos=reader_qos(reliable=False))


def forces(rd: DataReader, n: int, timeout: float = 15.0) -> List[float]:
    rd.take(5000)  # what came before
    end = time.monotonic() + timeout
    out: List[Any] = []
    while time.monotonic() < end and len(out) < n:
        out += [s for s in rd.take(500) if isinstance(s, WrenchStamped_)]
        time.sleep(0.02)
    assert len(out) >= n, f"{len(out)} wrench messages in {timeout} s"
    return [abs(m.wrench.force.x) + abs(m.wrench.torque.z) for m in out]


def diagnostics(rd: DataReader, timeout: float = 5.0) -> Dict[str, str]:
    """The values of the next diagnostics message."""
    rd.take(100)
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        got = [s for s in rd.take(10) if isinstance(s, DiagnosticArray_)]
        if got:
            return {v.key: v.value for v in got[-1].status[0].values}
        time.sleep(0.05)
    raise AssertionError("no diagnostics")


def test_tare_untare_services_two_clients(participant: Any, domain: int) -> None:
    p = participant
    rd = wrench_reader(p, "/cell/a")
    drd = DataReader(p, Topic(p, "rt/cell/a/diagnostics", DiagnosticArray_), qos=reader_qos())
    info = DataReader(p, Topic(p, "ros_discovery_info", ParticipantEntitiesInfo_),
                      qos=Qos(Policy.Reliability.Reliable(0), Policy.Durability.TransientLocal,
                              Policy.History.KeepLast(1)))
    tare_a = Client(p, "/cell/a/tare", "1.2.3.4.5.6.7.8.9.a.b.c.0.0.0.1")
    untare_b = Client(p, "/cell/a/untare", "1.2.3.4.5.6.7.8.9.a.b.c.0.0.0.2")
    untare_a = Client(p, "/cell/a/untare", "1.2.3.4.5.6.7.8.9.a.b.c.0.0.0.3")
    assert len({tare_a.guid, untare_b.guid, untare_a.guid}) == 3
    proc = start_bridge(domain, "--sim", "a,constant,amplitude=0.2", "--namespace", "/cell",
                        "--retare", "50")
    try:
        assert min(forces(rd, 200)) > 1.0
        r = tare_a.call(seq=1)
        assert (r.client_guid, r.sequence_number, r.success) == (tare_a.guid, 1, True)
        assert r.message.startswith("tared over 50 samples"), r.message
        assert max(forces(rd, 200)) < 1e-6  # the tare applies
        kv = diagnostics(drd)
        assert kv["tared"] == "true" and float(kv["tare_offset_fx"]) != 0.0

        # two clients of untare with the same sequence number: each gets its own
        ra = untare_a.call(seq=5)
        rb = untare_b.call(seq=5)
        assert (ra.client_guid, ra.sequence_number, ra.message) == (untare_a.guid, 5,
                                                                    "tare removed")
        assert (rb.client_guid, rb.sequence_number, rb.success) == (untare_b.guid, 5, True)
        # b's reply reached a's reader too (one reply topic): told apart by the guid
        end = time.monotonic() + 5
        while time.monotonic() < end and not untare_a.others:
            untare_a.others += [s for s in untare_a.reader.take(10)
                                if isinstance(s, TriggerResponse_)]
            time.sleep(0.02)
        assert [o.client_guid for o in untare_a.others] == [untare_b.guid]
        assert untare_b.others and all(o.client_guid == untare_a.guid for o in untare_b.others)
        assert min(forces(rd, 200)) > 1.0  # un-tared
        assert diagnostics(drd)["tared"] == "false"

        # the endpoints as a ROS 2 graph sees them
        ep = untare_a.reader.get_matched_publication_data(
            untare_a.reader.get_matched_publications()[0])
        sub = untare_a.writer.get_matched_subscription_data(
            untare_a.writer.get_matched_subscriptions()[0])
        nodes = [n for s in info.read(10) if isinstance(s, ParticipantEntitiesInfo_)
                 for n in s.node_entities_info_seq]
    finally:
        err = stop(proc)
    assert proc.returncode == 0, err
    assert (ep.topic_name, ep.type_name) == ("rr/cell/a/untareReply",
                                             "std_srvs::srv::dds_::Trigger_Response_")
    assert (sub.topic_name, sub.type_name) == ("rq/cell/a/untareRequest",
                                               "std_srvs::srv::dds_::Trigger_Request_")
    ud_w, ud_r = user_data(ep), user_data(sub)
    assert ud_w["serviceid"] == ud_r["serviceid"]  # the pair, as rmw_cyclonedds pairs them
    assert ud_w["typehash"] == ud_r["typehash"] == TRIGGER_HASH
    assert ep.qos[Policy.Reliability] == Policy.Reliability.Reliable(100_000_000)
    assert ep.qos[Policy.Durability] == Policy.Durability.Volatile
    assert ep.qos[Policy.History] == Policy.History.KeepLast(10)
    (node,) = [n for n in nodes if n.node_name == "a"][-1:]
    assert ep.key.bytes in {bytes(g.data) for g in node.writer_gid_seq}
    assert sub.key.bytes in {bytes(g.data) for g in node.reader_gid_seq}


def test_malformed_requests_are_counted_and_ignored(participant: Any, domain: int,
                                                    peer: str) -> None:
    """The Fast DDS peer writes raw requests under the request type's name (as
    rmw_fastrtps does: no type information, no request header)."""
    p = participant
    rd = wrench_reader(p, "/b")
    drd = DataReader(p, Topic(p, "rt/b/diagnostics", DiagnosticArray_), qos=reader_qos())
    client = Client(p, "/b/tare", "1.2.3.4.5.6.7.8.9.a.b.c.0.0.1.1")
    bad = {
        "no header (rmw_fastrtps' request)": "00010000" + "00" * 4,
        "truncated header": "00010000" + "00" * 12,
        "not CDR": "07070000" + "00" * 20,
        "too long": "00010000" + "00" * 40,
    }
    proc = start_bridge(domain, "--sim", "b,constant,amplitude=0.2", "--retare", "50")
    try:
        client.wait_matched()
        assert min(forces(rd, 100)) > 1.0
        kv = diagnostics(drd)
        assert (kv["rejected_requests"], kv["dds_headerless_clients"]) == ("0", "0")
        r = subprocess.run([peer, "raw", str(domain), "15", "rq/b/tareRequest",
                            "std_srvs::srv::dds_::Trigger_Request_", *bad.values()],
                           capture_output=True, text=True, timeout=45)
        assert r.returncode == 0, r.stderr
        # Cyclone drops the two shorter than the request type while
        # deserializing; the bridge rejects the two others and counts the
        # client that sends no header
        end = time.monotonic() + 10
        while time.monotonic() < end:
            kv = diagnostics(drd)
            if (kv["rejected_requests"], kv["dds_headerless_clients"]) == ("2", "1"):
                break
        assert (kv["rejected_requests"], kv["dds_headerless_clients"]) == ("2", "1"), kv
        assert min(forces(rd, 600)) > 1.0  # streaming on, and nothing tared
        r2 = client.call(seq=42)  # the service still answers
        assert (r2.client_guid, r2.sequence_number, r2.success) == (client.guid, 42, True)
        assert max(forces(rd, 100)) < 1e-6
    finally:
        err = stop(proc)
    assert proc.returncode == 0, err
    ignored = [line for line in err.splitlines() if "b/tare: request refused" in line]
    assert len(ignored) == 1, err  # rate-limited: one line for the burst
    assert len([line for line in err.splitlines() if "without rmw_cyclonedds' request header"
                in line]) == 1, err


def test_busy_requests_are_answered_busy(participant: Any, domain: int) -> None:
    """Requests that come while a tare is served are answered at once with
    success false and the busy message (not dropped), and counted."""
    p = participant
    rd = wrench_reader(p, "/a")
    drd = DataReader(p, Topic(p, "rt/a/diagnostics", DiagnosticArray_), qos=reader_qos())
    c = Client(p, "/a/tare", "1.2.3.4.5.6.7.8.9.a.b.c.0.0.0.9")
    proc = start_bridge(domain, "--sim", "a,constant,amplitude=0.2", "--retare", "600")
    try:
        forces(rd, 100)
        c.wait_matched()
        for seq in range(1, 9):  # a tare of 600 samples takes 0.5 s: these come meanwhile
            c.writer.write(TriggerRequest_(client_guid=c.guid, sequence_number=seq,
                                           structure_needs_at_least_one_member=0))
        got: Dict[int, Any] = {}
        end = time.monotonic() + 10
        while time.monotonic() < end and len(got) < 8:
            for r in c.reader.take(10):
                if isinstance(r, TriggerResponse_) and r.client_guid == c.guid:
                    got[r.sequence_number] = r
            time.sleep(0.01)
        assert sorted(got) == list(range(1, 9)), sorted(got)
        assert got[1].success and got[1].message.startswith("tared over 600"), got[1].message
        busy = [s for s in range(2, 9) if not got[s].success]
        assert busy and all(got[s].message.startswith("busy:") for s in busy)
        kv = diagnostics(drd)
        assert int(kv["tare_busy"]) == len(busy) and int(kv["tare_requests"]) == 8 - len(busy)
    finally:
        err = stop(proc)
    assert proc.returncode == 0, err
