#!/usr/bin/env python3
"""Run leptrino-bench several times and print the median of every figure.

The one command behind `make bench` (BENCHMARKS.md): each run prints one JSON
object; this prints one object of the same shape where every number is the
median over the runs (strings, booleans and nulls are taken from the first
run), plus "runs" with the count and the per-run values of a few headline
figures, so the spread can be seen.

    python3 bench/bench_runs.py [--runs 3] [--out FILE] BENCH [ARGS...]
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
from typing import Any

HEADLINES = [
    ("decoder", "streams", "realistic", "chunks", "32", "leptrino"),
    ("decoder", "streams", "realistic", "chunks", "4096", "leptrino"),
    ("client_step", "leptrino"),
    ("client_step", "step_call"),
    ("end_to_end", "low_latency", "latency_us", "p50"),
    ("end_to_end", "low_latency", "latency_us", "p99"),
    ("end_to_end", "low_latency", "latency_from_write_end_us", "p50"),
    ("end_to_end", "low_latency", "latency_from_deadline_us", "p50"),
    ("end_to_end", "low_latency", "sim_lateness_us", "p50"),
    ("end_to_end", "low_latency", "sim_over_client_cpu"),
    ("end_to_end", "low_latency", "cpu_us_per_sample"),
    ("end_to_end", "low_latency", "syscalls_per_sample"),
    ("end_to_end", "low_latency", "sim_cpu_us_per_sample"),
    ("end_to_end", "sender_floor", "sleep_and_pty_write_us_cpu_per_period"),
    ("machine", "load_1min_at_start"),
    ("end_to_end", "client", "latency_us", "p50"),
    ("python", "record_us_cpu_per_sample"),
    ("python", "stream_iter_us_cpu_per_sample"),
    ("end_to_end", "low_latency", "cpu_percent_of_one_core"),
    ("end_to_end", "recording", "cpu_percent_of_one_core"),
    ("end_to_end", "field_sleep", "latency_us", "p50"),
    ("end_to_end", "field_sleep", "cpu_percent_of_one_core"),
    ("end_to_end", "field_sleep", "syscalls_per_sample"),
    ("end_to_end", "field_busy", "cpu_percent_of_one_core"),
    ("end_to_end", "field_comparison", "field_sleep_over_low_latency_latency_p50"),
    ("end_to_end", "field_comparison", "field_sleep_over_low_latency_cpu_per_sample"),
    ("end_to_end", "field_comparison", "field_sleep_over_recording_cpu_per_sample"),
    ("end_to_end", "field_comparison", "field_sleep_over_recording_syscalls_per_sample"),
]


def merge(objs: list[Any]) -> Any:
    first = objs[0]
    if isinstance(first, dict):
        return {k: merge([o.get(k) if isinstance(o, dict) else None for o in objs]) for k in first}
    if isinstance(first, list):
        n = min(len(o) if isinstance(o, list) else 0 for o in objs)
        return [merge([o[i] for o in objs]) for i in range(n)] + first[n:]
    if isinstance(first, bool) or first is None or isinstance(first, str):
        return first
    nums = [o for o in objs if isinstance(o, (int, float)) and not isinstance(o, bool)]
    return statistics.median(nums) if nums else None


def dig(obj: Any, path: tuple[str, ...]) -> Any:
    for key in path:
        obj = obj.get(key) if isinstance(obj, dict) else None
    return obj


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--out", help="also write the medians here")
    ap.add_argument("bench", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    if not a.bench:
        ap.error("give the leptrino-bench command")
    results = []
    for i in range(a.runs):
        print(f"bench_runs: run {i + 1} of {a.runs}: {' '.join(a.bench)}", file=sys.stderr)
        out = subprocess.run(a.bench, check=True, capture_output=True, text=True).stdout
        results.append(json.loads(out))
    med = merge(results)
    med["runs"] = {"count": a.runs,
                   "headlines": {"/".join(p): [dig(r, p) for r in results] for p in HEADLINES}}
    text = json.dumps(med, indent=1)
    if a.out:
        with open(a.out, "w", encoding="utf-8") as f:
            f.write(text + "\n")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
