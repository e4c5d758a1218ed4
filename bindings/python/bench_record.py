#!/usr/bin/env python3
"""Per-sample CPU cost of Sensor.record() and of the sample iterator.

The virtual sensor runs on a C thread of this process (Sensor(sim=...)), so
the figures are the CPU time of the calling thread only (time.thread_time):
the C session's reads and the Python around them. Prints the median of the
runs for each, and the issue's targets (record() <= 2 us per sample
amortised, iterating <= 10 us per sample); asserts nothing.

    python bench_record.py [--backend ctypes|cffi] [--runs 5] [--seconds 2]
                           [--latency 0.05] [--json]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time

# Run as a file from bindings/python, this directory would shadow the installed
# package (whose copy carries the bundled library) with the source tree.
_HERE = os.path.dirname(os.path.abspath(__file__))
if not os.path.isdir(os.path.join(_HERE, "leptrino", "_lib")):
    sys.path[:] = [p for p in sys.path if os.path.abspath(p or ".") != _HERE]
try:
    import leptrino
except ImportError:
    if _HERE in sys.path:
        raise
    sys.path.insert(0, _HERE)  # not installed: the source tree (with LEPTRINO_LIBRARY)
    import leptrino


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--backend", choices=leptrino.BACKENDS, default=None)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--seconds", type=float, default=2.0)
    ap.add_argument("--rate", type=float, default=1200.0, help="virtual sensor rate (Hz)")
    ap.add_argument("--latency", type=float, default=0.05,
                    help="the session's latency budget in s (Sensor's default 0.05)")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args()

    be = leptrino.get_backend(args.backend)
    rec_us, rec_n, it_us, it_n, c_us, lost = [], [], [], [], [], 0
    with leptrino.Sensor(sim={"rate": args.rate}, latency=args.latency,
                         backend=args.backend) as sensor:
        sensor.record(count=100)  # warm up (allocations, first batch)
        # record() in a running stream (as a long recording amortises the
        # start and stop), then the start + stop themselves.
        sensor.start()
        for _ in range(args.runs):
            c0 = time.thread_time()
            rec = sensor.record(seconds=args.seconds)
            c1 = time.thread_time()
            rec_us.append((c1 - c0) / len(rec) * 1e6)
            rec_n.append(len(rec))
            lost += rec.missing()
        sensor.stop()
        ss_ms = []
        for _ in range(args.runs):
            c0 = time.thread_time()
            sensor.start()
            sensor.stop()
            ss_ms.append((time.thread_time() - c0) * 1e3)
        # The session alone: lep_session_read into one big batch, no Python
        # around it but the loop (what record() costs above it is Python's).
        from leptrino.sensor import _Arrays

        arrays = _Arrays(be, int(args.rate * args.seconds * 1.2) + 1000)
        for _ in range(args.runs):
            arrays.n = 0
            sensor.start()
            end = time.monotonic() + args.seconds
            c0 = time.thread_time()
            while time.monotonic() < end:
                arrays.read(sensor._s, 250, arrays.cap - arrays.n, at=arrays.n)
            c1 = time.thread_time()
            sensor.stop()
            c_us.append((c1 - c0) / max(1, arrays.n) * 1e6)
        for _ in range(args.runs):
            n = 0
            c0 = time.thread_time()
            with sensor.stream(seconds=args.seconds) as samples:
                for _s in samples:
                    n += 1
            c1 = time.thread_time()
            it_us.append((c1 - c0) / n * 1e6)
            it_n.append(n)

    rec_med, it_med = statistics.median(rec_us), statistics.median(it_us)
    c_med = statistics.median(c_us)
    result = {
        "backend": be.name,
        "rate_hz": args.rate,
        "latency_s": args.latency,
        "runs": args.runs,
        "seconds": args.seconds,
        "record_us_per_sample": round(rec_med, 3),
        "record_runs_us": [round(x, 3) for x in rec_us],
        "record_samples": statistics.median(rec_n),
        "record_lost": lost,
        "session_read_only_us_per_sample": round(c_med, 3),
        "start_stop_ms_cpu": round(statistics.median(ss_ms), 3),
        "iterate_us_per_sample": round(it_med, 3),
        "iterate_runs_us": [round(x, 3) for x in it_us],
        "iterate_samples": statistics.median(it_n),
        "targets_us": {"record": 2.0, "iterate": 10.0},
    }
    if args.json:
        print(json.dumps(result))
        return
    print(f"backend {be.name}, virtual sensor at {args.rate:g} Hz, latency budget "
          f"{args.latency * 1000:g} ms, {args.runs} runs of {args.seconds:g} s "
          f"({statistics.median(rec_n):g} samples each, {lost} lost)")
    print(f"record():   median {rec_med:.2f} us CPU per sample "
          f"(runs: {', '.join(f'{x:.2f}' for x in rec_us)}) "
          f"= {rec_med * args.rate / 1e4:.2f} % of one core; target <= 2 us")
    print(f"(the session's reads alone: median {c_med:.2f} us CPU per sample; "
          f"Python adds {rec_med - c_med:.2f} us to record(); a start + stop costs "
          f"{statistics.median(ss_ms):.2f} ms CPU)")
    print(f"iterating:  median {it_med:.2f} us CPU per sample "
          f"(runs: {', '.join(f'{x:.2f}' for x in it_us)}) "
          f"= {it_med * args.rate / 1e4:.2f} % of one core; target <= 10 us")


if __name__ == "__main__":
    main()
