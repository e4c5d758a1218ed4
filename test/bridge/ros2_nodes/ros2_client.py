#!/usr/bin/env python3
"""A real ROS 2 node (rclpy, on whatever RMW_IMPLEMENTATION says; the
default middleware is rmw_fastrtps_cpp) checking one leptrino-bridge sensor
as a ROS user would: every topic, the node graph, and both services.

Runs in a ROS 2 Python environment (the PyPI wheels `ros-jazzy-rclpy[fastrtps]`
etc., or a sourced ROS installation); needs nothing from leptrino. Every wait
is bounded. Prints one JSON object on stdout:

    {"distro": ..., "rmw": ..., "checks": {NAME: {"ok": bool, "detail": str}}}

and exits 0 when every check passed, 1 otherwise (2: bad arguments).

Checks (NAME):
  wrench, wrench_raw   geometry_msgs/msg/WrenchStamped arrive at --rate Hz
                       (within --rate-tol), frame_id, finite values, stamps
                       never going back
  diagnostics          diagnostic_msgs/msg/DiagnosticArray arrives, one status
                       "leptrino: NAME" with key/values
  gravity_input        the bridge subscribes to NAME/gravity
                       (geometry_msgs/msg/Vector3Stamped), as the graph shows
  node_listed          NAME in the node list (`ros2 node list`), in NS
  node_info            the node's publishers (wrench, wrench_raw,
                       diagnostics) and services (tare, untare) by node
                       (`ros2 node info`)
  tare                 std_srvs/srv/Trigger on NAME/tare answers success, and
                       the wrench's force goes to about 0
  untare               std_srvs/srv/Trigger on NAME/untare answers success, and
                       the force comes back
"""

import argparse
import json
import math
import os
import sys
import threading
import time


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--name", default="a", help="the bridge's sensor (node) name")
    ap.add_argument("--namespace", default="/", help="the bridge's --namespace")
    ap.add_argument("--frame-id", default=None, help="expected header.frame_id (default NAME)")
    ap.add_argument("--rate", type=float, default=1200.0, help="expected wrench rate, Hz")
    ap.add_argument("--rate-tol", type=float, default=0.10, help="relative rate tolerance")
    ap.add_argument("--window", type=float, default=3.0, help="rate measurement window, s")
    ap.add_argument("--discovery-timeout", type=float, default=10.0,
                    help="how long to wait for the first message / the node, s")
    ap.add_argument("--service-timeout", type=float, default=5.0,
                    help="wait for a service, then for its answer, s (each)")
    ap.add_argument("--skip-services", action="store_true")
    a = ap.parse_args()

    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.serialization import deserialize_message
    from rclpy.qos import QoSProfile, ReliabilityPolicy, HistoryPolicy, DurabilityPolicy
    from rclpy.utilities import get_rmw_implementation_identifier
    from geometry_msgs.msg import WrenchStamped
    from diagnostic_msgs.msg import DiagnosticArray
    from std_srvs.srv import Trigger

    ns = "/" + a.namespace.strip("/") if a.namespace.strip("/") else ""
    base = f"{ns}/{a.name}"
    frame = a.frame_id or a.name
    checks = {}

    def put(name, ok, detail):
        checks[name] = {"ok": bool(ok), "detail": detail}

    rclpy.init()
    node = rclpy.create_node("leptrino_ros2_check", namespace="/")
    ex = SingleThreadedExecutor()
    ex.add_node(node)
    spin = threading.Thread(target=ex.spin, daemon=True)
    spin.start()

    lock = threading.Lock()
    stats = {}

    def make_cb(topic):
        # raw (serialized) messages: counting 1,200 Hz in Python keeps up only
        # without deserializing each one; every 8th is decoded and checked
        st = stats[topic] = {"n": 0, "t": [], "bad_frame": 0, "nonfinite": 0, "back": 0,
                             "last": None, "fz": [], "decoded": 0, "ns": []}

        def cb(raw):
            now = time.monotonic()
            with lock:
                st["n"] += 1
                n = st["n"]
            if n % 8 and not st["want_all"]:
                return
            msg = deserialize_message(raw, WrenchStamped)
            s = msg.header.stamp.sec * 1_000_000_000 + msg.header.stamp.nanosec
            f = msg.wrench.force
            vals = (f.x, f.y, f.z, msg.wrench.torque.x, msg.wrench.torque.y, msg.wrench.torque.z)
            with lock:
                st["decoded"] += 1
                if msg.header.frame_id != frame:
                    st["bad_frame"] += 1
                if not all(math.isfinite(v) for v in vals):
                    st["nonfinite"] += 1
                if st["last"] is not None and s < st["last"]:
                    st["back"] += 1
                st["last"] = s
                st["ns"].append((n, s))
                st["fz"].append((now, math.sqrt(f.x * f.x + f.y * f.y + f.z * f.z)))
        st["want_all"] = False
        return cb

    # the bridge's writers are reliable/volatile/keep-last 10: a reliable reader matches
    qos = QoSProfile(depth=5000, reliability=ReliabilityPolicy.RELIABLE,
                     history=HistoryPolicy.KEEP_LAST, durability=DurabilityPolicy.VOLATILE)
    subs = [node.create_subscription(WrenchStamped, f"{base}/{t}", make_cb(t), qos, raw=True)
            for t in ("wrench", "wrench_raw")]
    diags = []

    def on_diag(msg):
        with lock:
            diags.append(msg)
    subs.append(node.create_subscription(DiagnosticArray, f"{base}/diagnostics", on_diag, 10))

    t0 = time.monotonic()
    # wait for the first wrench, then measure over the window
    while time.monotonic() - t0 < a.discovery_timeout:
        with lock:
            if stats["wrench"]["n"] and stats["wrench_raw"]["n"]:
                break
        time.sleep(0.05)
    first = time.monotonic()
    time.sleep(0.5)  # settle
    with lock:
        start = {k: v["n"] for k, v in stats.items()}
    w0 = time.monotonic()
    time.sleep(a.window)
    w1 = time.monotonic()
    with lock:
        end = {k: v["n"] for k, v in stats.items()}
    time.sleep(0.5)  # let a client that fell behind drain its reader
    with lock:
        for topic, st in stats.items():
            n = end[topic] - start[topic]
            arrival = n / (w1 - w0)
            # the publisher's rate: messages received per second of header
            # stamps (the reader keeps a deep history, so a client slowed by
            # a loaded machine still counts every message, only later)
            pts = [(k, s_) for (k, s_) in st["ns"] if k > start[topic]]
            rate = ((pts[-1][0] - pts[0][0]) / ((pts[-1][1] - pts[0][1]) / 1e9)
                    if len(pts) > 2 and pts[-1][1] > pts[0][1] else 0.0)
            ok = (st["n"] > 0 and abs(rate - a.rate) <= a.rate_tol * a.rate
                  and arrival >= 0.5 * a.rate
                  and not st["bad_frame"] and not st["nonfinite"] and not st["back"])
            put(topic, ok, f"{st['n']} messages; {rate:.1f} Hz by their stamps, {arrival:.1f} Hz "
                f"arriving over {w1 - w0:.1f} s (expected {a.rate:.0f} +- {a.rate_tol:.0%}); "
                f"frame_id mismatches {st['bad_frame']}, non-finite {st['nonfinite']}, "
                f"stamps back {st['back']} ({st['decoded']} decoded)"
                + ("" if st["n"] else f"; nothing within {first - t0:.1f} s"))

    # diagnostics: 1 Hz; allow up to discovery_timeout since the start
    while time.monotonic() - t0 < a.discovery_timeout:
        with lock:
            if diags:
                break
        time.sleep(0.05)
    with lock:
        d = list(diags)
    want = f"leptrino: {a.name}"
    if d:
        names = [s.name for s in d[-1].status]
        keys = {kv.key for s in d[-1].status for kv in s.values}
        ok = want in names and {"tared", "received"} <= keys
        put("diagnostics", ok, f"{len(d)} messages; statuses {names}; {len(keys)} keys"
            + ("" if ok else f"; expected a status {want!r} with keys tared, received"))
    else:
        put("diagnostics", False, f"no DiagnosticArray on {base}/diagnostics within "
            f"{time.monotonic() - t0:.1f} s")

    # the graph: the node, its endpoints, the gravity input
    listed = False
    names_ns = []
    while time.monotonic() - t0 < a.discovery_timeout + a.window + 1:
        names_ns = node.get_node_names_and_namespaces()
        if (a.name, ns or "/") in names_ns:
            listed = True
            break
        time.sleep(0.1)
    put("node_listed", listed, f"nodes: {sorted(f'{n_} in {s_}' for n_, s_ in names_ns)}")
    if listed:
        pubs = dict(node.get_publisher_names_and_types_by_node(a.name, ns or "/"))
        srvs = dict(node.get_service_names_and_types_by_node(a.name, ns or "/"))
        want_p = {f"{base}/wrench": "geometry_msgs/msg/WrenchStamped",
                  f"{base}/wrench_raw": "geometry_msgs/msg/WrenchStamped",
                  f"{base}/diagnostics": "diagnostic_msgs/msg/DiagnosticArray"}
        want_s = {f"{base}/tare": "std_srvs/srv/Trigger", f"{base}/untare": "std_srvs/srv/Trigger"}
        miss = [k for k, v in want_p.items() if v not in pubs.get(k, [])]
        miss += [k for k, v in want_s.items() if v not in srvs.get(k, [])]
        put("node_info", not miss, f"publishers {sorted(pubs)}; services {sorted(srvs)}"
            + (f"; missing {miss}" if miss else ""))
    else:
        put("node_info", False, "the node is not listed")
    grav = node.get_subscriptions_info_by_topic(f"{base}/gravity")
    gtypes = sorted({i.topic_type for i in grav})
    put("gravity_input", bool(grav) and gtypes == ["geometry_msgs/msg/Vector3Stamped"],
        f"{len(grav)} subscriber(s) of {base}/gravity, types {gtypes}")

    # the services
    def force_mean(after, n=20, timeout=2.0):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            with lock:
                v = [m for (t, m) in stats["wrench"]["fz"] if t > after]
            if len(v) >= n:
                return sum(v[:n]) / n
            time.sleep(0.02)
        return None

    if not a.skip_services:
        before = force_mean(0.0)
        for svc in ("tare", "untare"):
            cli = node.create_client(Trigger, f"{base}/{svc}")
            ts = time.monotonic()
            if not cli.wait_for_service(timeout_sec=a.service_timeout):
                put(svc, False, f"{base}/{svc} not available within {a.service_timeout} s")
                continue
            avail = time.monotonic() - ts
            fut = cli.call_async(Trigger.Request())
            tc = time.monotonic()
            done = threading.Event()
            fut.add_done_callback(lambda _f: done.set())
            done.wait(a.service_timeout)
            if not fut.done():
                fut.cancel()
                put(svc, False, f"available after {avail:.2f} s; no answer within "
                    f"{a.service_timeout} s")
                continue
            rtt = time.monotonic() - tc
            r = fut.result()
            after = force_mean(time.monotonic() + 0.05)
            if svc == "tare":
                moved = before is not None and after is not None and after < 0.05 * max(before, 1e-9)
                what = "force goes to about 0"
            else:
                moved = before is not None and after is not None and after > 0.5 * before
                what = "force comes back"
            put(svc, r.success and moved,
                f"answered in {rtt * 1000:.0f} ms: success={r.success} message={r.message[:120]!r}; "
                f"|F| before {before}, after {after} ({what}: {moved})")
    out = {"distro": os.environ.get("ROS_DISTRO", ""),
           "rmw": get_rmw_implementation_identifier(), "checks": checks}
    print(json.dumps(out), flush=True)
    rc = 0 if all(c["ok"] for c in checks.values()) else 1
    # the result is out: a teardown that trips over the executor thread
    # (rclpy aborts on some) must not change the exit status
    try:
        ex.shutdown(timeout_sec=1)
        spin.join(2)
        node.destroy_node()
        rclpy.shutdown()
    finally:
        sys.stderr.flush()
        os._exit(rc)


if __name__ == "__main__":
    sys.exit(main())
