"""The bridge's network inputs under a flood of garbage, on a real Zenoh
network on 127.0.0.1: malformed tare/untare requests (no attachment, a
short one, a payload that is not CDR, an empty one, 64 KiB of noise) and
malformed gravity messages, thousands a second for two seconds, at one
sensor of two, and valid tare requests at the other faster than a tare
takes. Each is refused and counted, none changes a sensor, the log says so in a
few lines, not thousands, and both sensors' wrenches keep their 1.2 kHz
meanwhile. Bounded: about 6 s."""

from __future__ import annotations

import os
import threading
import time
from typing import Any, List

from bridge_net import open_zenoh, router  # noqa: F401 (router: a fixture)

from leptrino.bridge import Bridge, NodeOptions, SensorSpec, ZenohOptions
from leptrino.bridge import cdr
from leptrino.bridge import rmw_zenoh as rz
from leptrino.bridge.typehash import rihs01

TRIGGER, VECTOR3_STAMPED = "std_srvs/srv/Trigger", "geometry_msgs/msg/Vector3Stamped"


def key(name: str, ros_type: str) -> str:
    """The key of a service or input of domain 0 in rmw_zenoh's layout."""
    return rz.data_key(0, name, ros_type, rihs01(ros_type))

FLOOD_S = 2.0


def garbage_requests() -> List[Any]:
    """(payload, attachment) pairs a service must refuse."""
    good_att = rz.attachment(1, time.time_ns(), bytes(16))
    noise = os.urandom(65536)
    return [(b"\x00\x01\x00\x00\x00", None),          # no attachment
            (b"\x00\x01\x00\x00\x00", good_att[:5]),  # a short attachment
            (b"\xff\xff\xff\xff", good_att),          # not CDR
            (noise, good_att),                        # 64 KiB of noise
            (b"", b"")]                               # nothing at all


def test_a_flood_of_garbage_is_refused_and_the_streams_keep_their_rate(router: str,
                                                                        caplog: Any) -> None:
    specs = [SensorSpec("a", sim={"constant": True, "amplitude": 0.2}),
             SensorSpec("b", sim={"constant": True, "amplitude": 0.2})]
    client = open_zenoh("client", connect=[router])
    arrivals: dict[str, List[float]] = {"a": [], "b": []}
    lock = threading.Lock()

    def on_wrench(sample: Any) -> None:
        name = str(sample.key_expr).split("/")[1]
        with lock:
            arrivals[name].append(time.monotonic())

    try:
        with Bridge(specs, NodeOptions(), ZenohOptions(mode="peer", connect=[router])) as bridge:
            keys = {n.spec.name: n for n in bridge.nodes}
            sub = client.declare_subscriber("0/*/wrench/**", on_wrench)
            bridge.start()
            time.sleep(1.0)  # streams up, subscriptions matched
            a = keys["a"]
            tare_key = key("/a/tare", TRIGGER)
            untare_key = key("/a/untare", TRIGGER)
            gravity_pub = client.declare_publisher(key("/a/gravity", VECTOR3_STAMPED))
            requests = garbage_requests()
            gravity = [b"", b"\x00\x01\x00\x00", os.urandom(4096), b"\x00\x01\x00\x00" + bytes(60)]
            replies: List[bool] = []

            def on_reply(reply: Any) -> None:
                replies.append(reply.ok is not None)

            sent = {"requests": 0, "gravity": 0, "valid": 0}
            b_tare = key("/b/tare", TRIGGER)
            answers: List[bool] = []  # valid tares at b: their Trigger success flags

            def on_answer(reply: Any) -> None:
                if reply.ok is not None:  # Trigger_Response in CDR: bool success after the header
                    answers.append(bytes(reply.ok.payload.to_bytes())[4] != 0)

            def flood_requests() -> None:
                n = 0
                while time.monotonic() - t0 < FLOOD_S:
                    payload, att = requests[n % len(requests)]
                    key = tare_key if n % 2 == 0 else untare_key
                    kw = {"attachment": att} if att is not None else {}
                    client.get(key, handler=on_reply, payload=payload, timeout=2.0, **kw)
                    n += 1
                sent["requests"] = n

            def flood_gravity() -> None:
                n = 0
                while time.monotonic() - t0 < FLOOD_S:
                    gravity_pub.put(gravity[n % len(gravity)])
                    n += 1
                    if n % 100 == 0:
                        time.sleep(0.001)  # thousands a second, not an unbounded burst
                sent["gravity"] = n

            def flood_valid_tares() -> None:
                n = 0
                while time.monotonic() - t0 < FLOOD_S:
                    client.get(b_tare, handler=on_answer, payload=cdr.encode_trigger_request(),
                               attachment=rz.attachment(n, time.time_ns(), bytes(range(16))),
                               timeout=5.0)
                    n += 1
                    time.sleep(0.005)
                sent["valid"] = n

            t0 = time.monotonic()
            senders = [threading.Thread(target=f)
                       for f in (flood_requests, flood_gravity, flood_valid_tares)]
            for th in senders:
                th.start()
            for th in senders:
                th.join(FLOOD_S + 5.0)
            t1 = time.monotonic()
            end = t1 + 2.0  # replies and counters settle (a tare takes 100 samples)
            while time.monotonic() < end and len(answers) < sent["valid"]:
                time.sleep(0.05)
            time.sleep(0.2)
            rate_window = (t0 + 0.2, t1)  # the flood's own span, after its start
            with lock:
                rates = {n: sum(1 for t in ts if rate_window[0] <= t < rate_window[1])
                         / (rate_window[1] - rate_window[0]) for n, ts in arrivals.items()}
            ca, cb = a.counters, keys["b"].counters
            n_answers = len(answers)
            gref = a.gravity.refused
            tared = list(a.sensor.tare_offsets)
            sub.undeclare()
    finally:
        client.close()
    nq, ng = sent["requests"], sent["gravity"]
    print(f"flood: {nq} requests and {ng} gravity messages in {t1 - t0:.2f} s "
          f"({(nq + ng) / (t1 - t0):.0f}/s); refused: {ca.rejected_requests} requests, "
          f"{gref} gravity; replies {len(replies)} (ok {sum(replies)}); "
          f"wrench rate a {rates['a']:.0f} Hz, b {rates['b']:.0f} Hz; valid tares at b "
          f"{sent['valid']}: answered {n_answers} ({sum(answers)} tared, {cb.tare_busy} busy)")
    assert (nq + ng) / (t1 - t0) > 1000 and nq / (t1 - t0) > 200, "not a flood"
    assert ca.rejected_requests > 0.9 * nq and ca.rejected_requests <= nq
    assert not any(replies), "a malformed request was answered as a success"
    assert ca.tare_requests == 0 and all(v == 0 for v in tared)  # nothing tared
    assert 0.9 * ng < gref <= ng  # every gravity message refused
    assert cb.rejected_requests == 0
    # valid tares faster than one can be served: each served or refused as busy at once,
    # none left queued, and every requester answered
    assert cb.tare_busy + cb.tare_requests == sent["valid"]
    assert 1 <= cb.tare_requests < sent["valid"] / 2
    assert n_answers == sent["valid"] and sum(answers) == cb.tare_requests
    # and the log is not flooded: one line per input kind and 5 s (bridge/ratelog.py)
    refused_lines = [r for r in caplog.records if "refused" in r.getMessage()]
    assert 1 <= len(refused_lines) <= 4, [r.getMessage() for r in refused_lines]
    for name, hz in rates.items():
        assert hz > 0.9 * 1200, f"{name}: {hz:.0f} Hz during the flood"
