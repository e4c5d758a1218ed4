#!/usr/bin/env python3
"""CPU of `leptrino stream --sim` into a pipe and into a file: two builds side
by side in one run (runs alternate A, B, A, B, ...), medians printed.

    python3 bench/stream_cpu.py --runs 5 --seconds 5 BEFORE/leptrino AFTER/leptrino

CPU is the child's user + system time (os.wait4), in-process virtual sensor
included; per second of stream. Also the write(2) calls per second from
`strace -c` when strace is installed (one run each)."""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import tempfile
from typing import Dict, List, Optional


def one(exe: str, seconds: float, sink: str, tmp: str) -> float:
    out = os.path.join(tmp, "rec.csv")
    if os.path.exists(out):
        os.unlink(out)
    args = [exe, "stream", "--sim", "--duration", str(seconds)]
    if sink == "file":
        args += ["-o", out]
        p = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        reader = None
    else:
        p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
        reader = subprocess.Popen(["cat"], stdin=p.stdout, stdout=subprocess.DEVNULL)
        assert p.stdout is not None
        p.stdout.close()
    _, status, ru = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    if reader is not None:
        reader.wait()
    if p.returncode != 0:
        raise SystemExit(f"{exe} exited {p.returncode}")
    return (ru.ru_utime + ru.ru_stime) / seconds


def writes_per_s(exe: str, seconds: float, sink: str, tmp: str) -> Optional[float]:
    if shutil.which("strace") is None:
        return None
    out = os.path.join(tmp, "rec.csv")
    if os.path.exists(out):
        os.unlink(out)
    log = os.path.join(tmp, "strace.txt")
    args = ["strace", "-f", "-c", "-e", "trace=write", "-o", log, exe, "stream", "--sim",
            "--duration", str(seconds)] + (["-o", out] if sink == "file" else [])
    subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    for line in open(log):
        f = line.split()
        if f and f[-1] == "write":
            return int(f[3]) / seconds
    return 0.0


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--seconds", type=float, default=5.0)
    ap.add_argument("before")
    ap.add_argument("after")
    a = ap.parse_args()
    res: Dict[str, Dict[str, List[float]]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for sink in ("pipe", "file"):
            for _ in range(a.runs):
                for name, exe in (("before", a.before), ("after", a.after)):
                    res.setdefault(sink, {}).setdefault(name, []).append(
                        one(exe, a.seconds, sink, tmp))
        out = {}
        for sink, by in res.items():
            med = {k: statistics.median(v) for k, v in by.items()}
            out[sink] = {
                "cpu_s_per_s_before": round(med["before"], 4),
                "cpu_s_per_s_after": round(med["after"], 4),
                "ratio_after_before": round(med["after"] / med["before"], 3),
                "writes_per_s_before": writes_per_s(a.before, 2.0, sink, tmp),
                "writes_per_s_after": writes_per_s(a.after, 2.0, sink, tmp),
                "runs": a.runs,
            }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
