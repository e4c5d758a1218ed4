#!/usr/bin/env python3
"""A real rclpy client that sends two std_srvs/srv/Trigger calls to
NAME/tare at once and reports, as one JSON object, the two answers and when
each came: the bridge serves one tare at a time and must answer the other
"busy" at once, not queue it (issue 30's rule, on every transport). Exit 0
when exactly one succeeded and the other was answered busy before it."""
import argparse
import json
import sys
import time

import rclpy
from std_srvs.srv import Trigger

ap = argparse.ArgumentParser()
ap.add_argument("--name", default="a")
a = ap.parse_args()
rclpy.init()
node = rclpy.create_node("leptrino_busy_check")
cli = node.create_client(Trigger, f"/{a.name}/tare")
out = {"available": cli.wait_for_service(timeout_sec=5.0), "answers": []}
if out["available"]:
    t0 = time.monotonic()
    futures = [cli.call_async(Trigger.Request()) for _ in range(2)]
    done_at = {}
    end = t0 + 10.0
    while time.monotonic() < end and not all(f.done() for f in futures):
        rclpy.spin_once(node, timeout_sec=0.05)
        for i, f in enumerate(futures):
            if f.done() and i not in done_at:
                done_at[i] = time.monotonic() - t0
    for i, f in enumerate(futures):
        r = f.result() if f.done() else None
        out["answers"].append(None if r is None else
                              {"success": bool(r.success), "message": r.message,
                               "ms": round(done_at[i] * 1000, 1)})
ans = [x for x in out["answers"] if x is not None]
ok_ = [x for x in ans if x["success"]]
busy = [x for x in ans if not x["success"] and x["message"].startswith("busy")]
out["ok"] = len(ans) == 2 and len(ok_) == 1 and len(busy) == 1 and busy[0]["ms"] <= ok_[0]["ms"]
print(json.dumps(out))
node.destroy_node()
rclpy.shutdown()
sys.exit(0 if out["ok"] else 1)
