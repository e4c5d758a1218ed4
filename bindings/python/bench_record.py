#!/usr/bin/env python3
"""Per-sample CPU cost of Sensor.record() against the virtual sensor.

The virtual sensor runs on a C thread of this process, so the figure is the
CPU time of the recording thread only (time.thread_time), which is where
record() and the C batch fill run. For comparison it also measures the
per-sample Python iterator (Sensor.stream()). Prints the median of the runs.

    python bench_record.py [--backend ctypes|cffi] [--runs 5] [--seconds 2]
"""

from __future__ import annotations

import argparse
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
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--backend", choices=leptrino.BACKENDS, default=None)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--seconds", type=float, default=2.0)
    ap.add_argument("--rate", type=float, default=1200.0, help="virtual sensor rate (Hz)")
    args = ap.parse_args()

    be = leptrino.get_backend(args.backend)
    rec_us, rec_n, it_us = [], [], []
    with leptrino.Simulator(rate_hz=args.rate, backend=args.backend) as port:
        with leptrino.Sensor(port, backend=args.backend) as sensor:
            sensor.record(count=100)  # warm up (rated values, allocations)
            for _ in range(args.runs):
                c0 = time.thread_time()
                rec = sensor.record(seconds=args.seconds)
                c1 = time.thread_time()
                rec_us.append((c1 - c0) / len(rec) * 1e6)
                rec_n.append(len(rec))
                assert rec.missing() == 0
            for _ in range(args.runs):
                n = 0
                c0 = time.thread_time()
                with sensor.stream(seconds=args.seconds) as samples:
                    for _s in samples:
                        n += 1
                c1 = time.thread_time()
                it_us.append((c1 - c0) / n * 1e6)

    med = statistics.median(rec_us)
    print(f"backend {be.name}, virtual sensor at {args.rate:g} Hz, {args.runs} runs of "
          f"{args.seconds:g} s ({statistics.median(rec_n)} samples each)")
    print(f"record():  median {med:.2f} us CPU per sample "
          f"(runs: {', '.join(f'{x:.2f}' for x in rec_us)}) "
          f"= {med * args.rate / 1e4:.2f} % of one core at {args.rate:g} Hz")
    mi = statistics.median(it_us)
    print(f"stream():  median {mi:.2f} us CPU per sample (per-sample Python iterator) "
          f"= {mi * args.rate / 1e4:.2f} % of one core")


if __name__ == "__main__":
    main()
