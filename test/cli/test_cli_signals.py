"""Ending a stream: Ctrl-C / SIGTERM stop the sensor's stream; a vanished
port is an error, or with --reconnect a marked gap."""

from __future__ import annotations

import json
import signal
import subprocess
import time
from pathlib import Path

import pytest

from conftest import Csv, SimProcess, cli_path, parse_csv, parse_jsonl, run, wait_rows_after


def wait_streaming(sim: SimProcess, want: int, timeout: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if sim.stats()["streaming"] == want:
            return True
        time.sleep(0.05)
    return False


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_signal_stops_the_sensor_stream_and_exits_0(sig: signal.Signals, tmp_path: Path) -> None:
    sim = SimProcess()
    out = tmp_path / "out.csv"
    try:
        proc = subprocess.Popen([cli_path(), "stream", sim.port, "-o", str(out)],
                                stdin=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        assert wait_streaming(sim, 1), "the stream never started"
        wait_rows_after(out, 0, 101, proc)
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=20)
        assert proc.returncode == 0, err
        assert "stopped by signal" in err
        # The sensor is left quiet: not streaming, and the line is usable at once.
        assert sim.stats()["streaming"] == 0
        rows, _ = parse_csv(out.read_text())  # flushed and complete
        assert len(rows) > 100
        r = run(["read", sim.port, "-n", "2"])
        assert r.returncode == 0, r.stderr
    finally:
        sim.close()


def test_sigint_with_in_process_sim_exits_0() -> None:
    proc = subprocess.Popen([cli_path(), "stream", "--sim", "-f", "jsonl"],
                            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    assert proc.stdout is not None
    first = [proc.stdout.readline() for _ in range(101)]  # the metadata and 100 rows
    proc.send_signal(signal.SIGINT)
    # (the rest through the same buffered reader: communicate() would miss
    # what it has read ahead)
    out = proc.stdout.read()
    assert proc.stderr is not None
    err = proc.stderr.read()
    assert proc.wait(timeout=20) == 0, err
    lines = "".join(first).splitlines() + out.splitlines()
    assert len(lines) > 100
    for line in lines:
        json.loads(line)  # every line complete, the last one included
    assert "metadata" in json.loads(lines[0])


def test_closed_output_pipe_stops_cleanly() -> None:
    proc = subprocess.Popen([cli_path(), "stream", "--sim"], stdin=subprocess.DEVNULL,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert proc.stdout is not None
    proc.stdout.readline()
    proc.stdout.close()
    _, err = proc.communicate(timeout=20)
    assert proc.returncode == 0, err


def test_disconnect_without_reconnect_exits_4(tmp_path: Path) -> None:
    out = tmp_path / "out.csv"
    r = run(["stream", "--sim", "--sim-hangup-after", "0.5", "-o", str(out)])
    assert r.returncode == 4, r.stderr
    assert "disconnected" in r.stderr
    rows, _ = parse_csv(out.read_text())
    assert len(rows) > 100  # what came before the hang-up is kept


@pytest.mark.parametrize("fmt", ["csv", "jsonl"])
def test_reconnect_resumes_after_hangup_and_marks_the_gap(fmt: str, tmp_path: Path) -> None:
    out = tmp_path / f"out.{fmt}"
    r = run(["stream", "--sim", "--sim-hangup-after", "1", "--sim-reopen-after", "400",
             "--reconnect", "--duration", "3.5", "-f", fmt, "-o", str(out)], timeout=60)
    assert r.returncode == 0, r.stderr
    assert "disconnected" in r.stderr and "resumed" in r.stderr
    text = out.read_text()
    if fmt == "csv":
        csv = Csv(text)
        gaps = csv.events("gap")
        assert len(gaps) == 1, csv.comments
        gap_from, gap_to = float(gaps[0]["from"]), float(gaps[0]["to"])
        assert gaps[0]["reason"] == "disconnected"
        ts = csv.column("t_s")
    else:
        _, rows, events = parse_jsonl(text)
        gaps = [e for e in events if e["event"] == "gap"]
        assert len(gaps) == 1 and gaps[0]["reason"] == "disconnected", events
        gap_from, gap_to = gaps[0]["from"], gaps[0]["to"]
        ts = [rec["t_s"] for rec in rows]
    assert 0.5 < gap_from < gap_to
    assert gap_to - gap_from >= 0.3  # the port was away for 400 ms
    before = [t for t in ts if t <= gap_from]
    after = [t for t in ts if t >= gap_to]
    assert len(before) > 500 and len(after) > 300
    assert len(before) + len(after) == len(ts)
