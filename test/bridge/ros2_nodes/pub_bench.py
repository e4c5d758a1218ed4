#!/usr/bin/env python3
"""What publishing one sensor costs on DDS: WrenchStamped on two topics
(NAME/wrench, NAME/wrench_raw) at --rate Hz, in batches as the bridge
publishes them (one batch every --latency s), for --seconds; prints the
process's CPU as % of one core, as JSON.

--impl cyclone: Cyclone DDS' Python binding, the bridge's DDS path today
                (ddspy_write of the pre-serialized CDR, as dds.py's DdsWriter);
                run it where `cyclonedds` is installed (the bridge's venv).
--impl rclpy:   rclpy on RMW_IMPLEMENTATION (rmw_fastrtps_cpp), publishing the
                same pre-serialized CDR bytes (Publisher.publish(bytes));
--impl rclpy-msg: rclpy, a WrenchStamped object per sample (for scale).
--impl none:    the loop and the encoding alone (what the others add to).

The payload is the CDR the bridge's C encoder makes (encapsulation 00 01,
stamp, frame_id, six doubles); this script encodes it in Python once per
sample in every mode, so the modes differ only in the publishing."""

import argparse
import json
import os
import struct
import time


def cdr_wrench(sec, nsec, frame, v):
    f = frame.encode() + b"\0"
    body = struct.pack("<iiI", sec, nsec, len(f)) + f
    body += b"\0" * (-(len(body)) % 8)  # doubles align to 8 from the start of the body
    return b"\x00\x01\x00\x00" + body + struct.pack("<6d", *v)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--impl", choices=("none", "cyclone", "rclpy", "rclpy-msg"), required=True)
    ap.add_argument("--name", default="a")
    ap.add_argument("--rate", type=float, default=1200.0)
    ap.add_argument("--latency", type=float, default=0.002)
    ap.add_argument("--seconds", type=float, default=15.0)
    ap.add_argument("--domain", type=int, default=int(os.environ.get("ROS_DOMAIN_ID", "0")))
    a = ap.parse_args()
    topics = (f"/{a.name}/wrench", f"/{a.name}/wrench_raw")
    t_setup = time.monotonic()
    if a.impl == "none":  # the loop and the encoding alone
        def publish(i, payload, _msg):
            pass
    elif a.impl == "cyclone":
        from dataclasses import dataclass
        from cyclonedds._clayer import ddspy_write
        from cyclonedds.core import Qos
        from cyclonedds.domain import Domain, DomainParticipant
        from cyclonedds.idl import IdlStruct
        from cyclonedds.idl import types as t
        from cyclonedds.pub import DataWriter
        from cyclonedds.qos import Policy
        from cyclonedds.topic import Topic

        @dataclass
        class Time(IdlStruct, typename="builtin_interfaces::msg::dds_::Time_"):
            sec: t.int32
            nanosec: t.uint32

        @dataclass
        class Header(IdlStruct, typename="std_msgs::msg::dds_::Header_"):
            stamp: Time
            frame_id: str

        @dataclass
        class Vector3(IdlStruct, typename="geometry_msgs::msg::dds_::Vector3_"):
            x: t.float64
            y: t.float64
            z: t.float64

        @dataclass
        class Wrench(IdlStruct, typename="geometry_msgs::msg::dds_::Wrench_"):
            force: Vector3
            torque: Vector3

        @dataclass
        class WrenchStamped(IdlStruct, typename="geometry_msgs::msg::dds_::WrenchStamped_"):
            header: Header
            wrench: Wrench

        cfg = ("<CycloneDDS><Domain Id=\"any\"><General><Interfaces>"
               "<NetworkInterface address=\"127.0.0.1\"/></Interfaces>"
               "<AllowMulticast>false</AllowMulticast></General><Discovery>"
               "<ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>60"
               "</MaxAutoParticipantIndex><Peers><Peer address=\"127.0.0.1\"/></Peers>"
               "</Discovery></Domain></CycloneDDS>")
        dom = Domain(a.domain, cfg)  # noqa: F841 (kept alive)
        dp = DomainParticipant(a.domain, qos=Qos(Policy.Userdata(b"enclave=/;")))
        q = Qos(Policy.Reliability.Reliable(100_000_000), Policy.Durability.Volatile,
                Policy.History.KeepLast(10),
                Policy.DataRepresentation(use_cdrv0_representation=True))
        tq = Qos(Policy.DataRepresentation(use_cdrv0_representation=True))
        writers = [DataWriter(dp, Topic(dp, "rt" + n, WrenchStamped, qos=tq), qos=q)
                   for n in topics]
        refs = [w._ref for w in writers]

        def publish(i, payload, _msg):
            ddspy_write(refs[i], payload)
    else:
        import rclpy
        from geometry_msgs.msg import WrenchStamped
        from rclpy.qos import QoSProfile, ReliabilityPolicy, DurabilityPolicy, HistoryPolicy
        rclpy.init()
        node = rclpy.create_node(a.name)
        q = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE,
                       durability=DurabilityPolicy.VOLATILE, history=HistoryPolicy.KEEP_LAST)
        pubs = [node.create_publisher(WrenchStamped, n, q) for n in topics]
        if a.impl == "rclpy":
            def publish(i, payload, _msg):
                pubs[i].publish(payload)
        else:
            def publish(i, _payload, v):
                m = WrenchStamped()
                m.header.stamp.sec, m.header.stamp.nanosec = v[0], v[1]
                m.header.frame_id = a.name
                f, tq_ = m.wrench.force, m.wrench.torque
                f.x, f.y, f.z, tq_.x, tq_.y, tq_.z = v[2]
                pubs[i].publish(m)
    setup_s = time.monotonic() - t_setup
    time.sleep(2.0)  # discovery
    c0, w0 = time.process_time(), time.monotonic()
    sent, k = 0, 0
    per = a.rate * a.latency
    due = 0.0
    nxt = w0
    while True:
        now = time.monotonic()
        if now - w0 >= a.seconds:
            break
        due += per
        n = int(due)
        due -= n
        ns = time.time_ns()
        for _ in range(n):
            k += 1
            v = (0.1 * (k % 100), 0.2, 9.8, 0.01, 0.02, 0.03)
            for i in (0, 1):
                p = cdr_wrench(ns // 1_000_000_000, ns % 1_000_000_000, a.name, v)
                publish(i, p, (ns // 1_000_000_000, ns % 1_000_000_000, v))
            sent += 1
        nxt += a.latency
        d = nxt - time.monotonic()
        if d > 0:
            time.sleep(d)
    c1, w1 = time.process_time(), time.monotonic()
    print(json.dumps({"impl": a.impl, "rmw": os.environ.get("RMW_IMPLEMENTATION", ""),
                      "samples": sent, "rate_hz": round(sent / (w1 - w0), 1),
                      "cpu_pct_of_core": round(100 * (c1 - c0) / (w1 - w0), 2),
                      "setup_s": round(setup_s, 2), "seconds": round(w1 - w0, 1)}))
    if a.impl.startswith("rclpy"):
        node.destroy_node()
        rclpy.shutdown()


if __name__ == "__main__":
    main()
