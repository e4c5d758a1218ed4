#!/usr/bin/env python3
"""CPU of `leptrino stream` next to `cat` reading the same pty, as JSON.

The guard rail of issue 20: at 1.2 kHz, `leptrino stream` uses at most 2x the
CPU of `cat` reading the same port in raw mode with the default latency, and
at most 0.3x with `--latency 100`. Printed, never asserted.

One virtual sensor (leptrino-sim, its own process, on a pty) serves all the
runs. Each round measures, in this order, for SECONDS each:
  - cat: the port put in raw mode (termios), the stream started with the start
    command written to the port, then `cat PORT >/dev/null`;
  - `leptrino stream PORT --duration SECONDS -o /dev/null` (default latency);
  - the same with `--latency 100`.
CPU is the child's user + system time (wait4's rusage), including leptrino's
start-up (recovery, queries: about 0.1 s of wall time, a few ms of CPU).
Medians over the rounds, and the ratios leptrino / cat.

    python3 bench/stream_vs_cat.py --leptrino build/dev/tools/leptrino/leptrino \\
        --sim build/dev/tools/leptrino-sim/leptrino-sim [--seconds 10] [--rounds 3] \\
        [--compare OTHER_LEPTRINO]
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import statistics
import subprocess
import sys
import termios
import time
import tty
from typing import Dict, List

# DLE STX | 04 FF 32 00 (start continuous output) | DLE ETX | BCC
START = bytes([0x10, 0x02, 0x04, 0xFF, 0x32, 0x00, 0x10, 0x03, 0xCA])


def cpu_of(argv: List[str], seconds: float, stop: bool) -> float:
    """Run argv to its end (or SIGTERM after seconds when stop), its CPU in s."""
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    if stop:
        time.sleep(seconds)
        proc.send_signal(signal.SIGTERM)
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    err = proc.stderr.read().decode(errors="replace") if proc.stderr else ""
    if proc.stderr:
        proc.stderr.close()
    if not stop and proc.returncode != 0:
        sys.exit(f"{argv[0]} failed ({proc.returncode}): {err.strip()}")
    return usage.ru_utime + usage.ru_stime


def cat_cpu(port: str, seconds: float) -> float:
    fd = os.open(port, os.O_RDWR | os.O_NOCTTY)
    try:
        tty.setraw(fd)
        termios.tcflush(fd, termios.TCIFLUSH)
        os.write(fd, START)  # (a stream already running refuses it and goes on)
        time.sleep(0.05)
        return cpu_of(["cat", port], seconds, stop=True)
    finally:
        os.close(fd)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--leptrino", required=True)
    ap.add_argument("--sim", required=True)
    ap.add_argument("--seconds", type=float, default=10.0)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--compare", metavar="LEPTRINO",
                    help="another leptrino binary (e.g. an older build), measured in the same rounds")
    a = ap.parse_args()

    sim = subprocess.Popen([a.sim, "--rate", "1200"], stdout=subprocess.PIPE, text=True)
    try:
        port = sim.stdout.readline().strip() if sim.stdout else ""
        if not port:
            sys.exit("leptrino-sim printed no port")
        runs: Dict[str, List[float]] = {"cat": [], "leptrino": [], "leptrino_latency_100": []}
        binaries = {"leptrino": a.leptrino}
        if a.compare:
            binaries["compare"] = a.compare
            runs.update({"compare": [], "compare_latency_100": []})
        for _ in range(a.rounds):
            runs["cat"].append(cat_cpu(port, a.seconds))
            for name, binary in binaries.items():
                stream = [binary, "stream", port, "--duration", str(a.seconds), "-o", "/dev/null"]
                runs[name].append(cpu_of(stream, a.seconds, stop=False))
                runs[name + "_latency_100"].append(
                    cpu_of(stream + ["--latency", "100"], a.seconds, stop=False))
    finally:
        sim.send_signal(signal.SIGTERM)
        sim.wait()
    med = {k: statistics.median(v) for k, v in runs.items()}
    out = {
        "seconds": a.seconds,
        "rounds": a.rounds,
        "rate_hz": 1200,
        "load_average": os.getloadavg()[0],
        "cpu_s": {k: {"median": med[k], "runs": v} for k, v in runs.items()},
        "cpu_share_of_a_core": {k: med[k] / a.seconds for k in med},
        "ratio_to_cat": {k: (med[k] / med["cat"] if med["cat"] > 0 else None)
                         for k in med if k != "cat"},
        "guard_rails": {"leptrino": 2.0, "leptrino_latency_100": 0.3},
    }
    print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
