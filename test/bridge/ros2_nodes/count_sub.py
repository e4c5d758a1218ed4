#!/usr/bin/env python3
"""An rclpy subscriber of NAME/wrench and NAME/wrench_raw (raw: counted, not
deserialized) for --seconds; prints the counts as JSON. For pub_bench.py's
"one subscriber" figures."""
import argparse
import json
import time

import rclpy
from geometry_msgs.msg import WrenchStamped
from rclpy.qos import QoSProfile, ReliabilityPolicy

ap = argparse.ArgumentParser()
ap.add_argument("--name", default="a")
ap.add_argument("--seconds", type=float, default=20.0)
a = ap.parse_args()
rclpy.init()
node = rclpy.create_node("count_sub")
counts = {"wrench": 0, "wrench_raw": 0}


def cb_for(t):
    def cb(_raw):
        counts[t] += 1
    return cb


q = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)
subs = [node.create_subscription(WrenchStamped, f"/{a.name}/{t}", cb_for(t), q, raw=True)
        for t in counts]
end = time.monotonic() + a.seconds
while time.monotonic() < end:
    rclpy.spin_once(node, timeout_sec=0.1)
print(json.dumps(counts))
node.destroy_node()
rclpy.shutdown()
