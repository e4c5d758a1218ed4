#!/usr/bin/env python3
"""Check that a leptrino-bench output parses and holds every key (CI smoke).

Asserts the shape, never the speed: a figure may be any number, or null where
the JSON gives the reason next to it.

    python3 bench/check_bench_json.py build/dev/bench-smoke.json
"""

from __future__ import annotations

import json
import sys
from typing import Any

CHUNK_KEYS = [
    "leptrino", "plain", "ratio_plain_over_leptrino", "plain_loop", "ratio_plain_loop_over_leptrino",
    "leptrino_feed", "ratio_plain_over_leptrino_feed", "leptrino_messages", "leptrino_feed_messages",
    "plain_messages", "plain_loop_messages", "leptrino_msgs_per_s", "leptrino_feed_msgs_per_s",
    "plain_msgs_per_s", "plain_loop_msgs_per_s", "leptrino_ns_per_byte", "plain_ns_per_byte",
    "plain_loop_ns_per_byte",
]
MODE_KEYS = [
    "path", "latency_budget_ms", "rc", "samples", "lost", "latency_us", "latency_from_write_end_us",
    "latency_from_deadline_us",
    "sim_lateness_us", "wall_s", "cpu_s", "cpu_percent_of_one_core", "cpu_us_per_sample", "sim_cpu_us_per_sample",
    "sim_over_client_cpu", "read_write_syscalls_per_sample_proc", "syscalls_per_s", "syscalls_per_sample",
    "syscalls_method",
]
FIELD_KEYS = ["idle_sleeps_per_sample", "syscalls_per_sample_proc", "syscalls_proc_method"]
COMPARISON_KEYS = [
    "field_sleep_over_low_latency_latency_p50", "field_sleep_over_low_latency_cpu_per_sample",
    "field_sleep_over_recording_cpu_per_sample", "field_sleep_over_recording_syscalls_per_sample",
    "field_sleep_over_recording_read_write_per_sample_proc", "field_busy_over_low_latency_latency_p50",
    "field_busy_cpu_percent_of_one_core", "method",
]
SPREAD_KEYS = ["p50", "p99", "max", "min", "reference"]


def need(obj: Any, path: str, keys: list[str]) -> list[str]:
    if not isinstance(obj, dict):
        return [f"{path}: not an object"]
    return [f"{path}.{k}: missing" for k in keys if k not in obj]


def main() -> int:
    with open(sys.argv[1], encoding="utf-8") as f:
        d = json.load(f)
    errs = need(d, "", ["tool", "leptrino_version", "smoke", "machine", "limits", "decoder",
                        "client_step", "encoder", "end_to_end", "python"])
    errs += need(d.get("limits"), "limits", ["line_bytes_per_s", "data_frame_bytes", "period_us",
                                             "frame_wire_time_us"])
    dec = d.get("decoder", {})
    errs += need(dec, "decoder", ["method", "unit", "streams"])
    for stream in ("realistic", "all_0x10", "corrupt_1pct"):
        s = dec.get("streams", {}).get(stream)
        errs += need(s, f"decoder.streams.{stream}", ["bytes", "payload_0x10_share", "chunks"])
        for chunk in ("1", "32", "4096"):
            c = (s or {}).get("chunks", {}).get(chunk)
            errs += need(c, f"decoder.streams.{stream}.chunks.{chunk}", CHUNK_KEYS)
            if isinstance(c, dict) and c.get("leptrino_messages") != c.get(
                    "leptrino_feed_messages"):
                errs.append(f"{stream}/{chunk}: feed and feed_all disagree")
    errs += need(d.get("client_step"), "client_step", ["leptrino", "plain_same_input", "samples", "step_call", "step_call_samples"])
    errs += need(d.get("encoder"), "encoder", ["frame_encode_msgs_per_s", "sample_to_frame_msgs_per_s"])
    e2e = d.get("end_to_end", {})
    errs += need(e2e, "end_to_end", ["sim", "low_latency", "recording", "client", "field_sleep", "field_busy",
                                     "field_comparison", "session_latency_budget_ms", "rates",
                                     "max_rate_without_loss_hz"])
    errs += need(e2e.get("field_comparison"), "end_to_end.field_comparison", COMPARISON_KEYS)
    errs += need(e2e.get("sender_floor"), "end_to_end.sender_floor",
                 ["sleep_us_cpu_per_period", "sleep_and_pty_write_us_cpu_per_period", "method"])
    for mode in ("low_latency", "recording", "client", "field_sleep", "field_busy"):
        m = e2e.get(mode)
        errs += need(m, f"end_to_end.{mode}", MODE_KEYS + (FIELD_KEYS if mode.startswith("field_") else []))
        for lat in ("latency_us", "latency_from_write_end_us", "latency_from_deadline_us", "sim_lateness_us"):
            errs += need((m or {}).get(lat), f"end_to_end.{mode}.{lat}", SPREAD_KEYS)
        for lat in ("latency_us", "latency_from_write_end_us"):
            errs += need((m or {}).get(lat), f"end_to_end.{mode}.{lat}", ["matched"])
    py_keys = ["record_us_cpu_per_sample", "stream_iter_us_cpu_per_sample", "session_read_only_us_cpu_per_sample",
               "reason"]
    errs += need(d.get("python"), "python", py_keys + ["backend", "latency_budget_s", "latency_budget_0"])
    errs += need((d.get("python") or {}).get("latency_budget_0"), "python.latency_budget_0", py_keys)
    for e in errs:
        print("bench smoke:", e, file=sys.stderr)
    if not errs:
        print(f"bench smoke: ok ({len(json.dumps(d))} bytes of JSON, every key present)")
    return 1 if errs else 0


if __name__ == "__main__":
    sys.exit(main())
