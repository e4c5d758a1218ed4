"""python -m leptrino: info, stream, plot, and its exit codes."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any, Dict, List

import pytest

from conftest import subprocess_env


def run(backend: str, *args: str, timeout: float = 60) -> subprocess.CompletedProcess:
    env = subprocess_env(LEPTRINO_BACKEND=backend)
    return subprocess.run([sys.executable, "-m", "leptrino", *args], capture_output=True,
                          text=True, timeout=timeout, env=env)


def test_info(backend: str) -> None:
    r = run(backend, "info", "--sim", "--sim-model", "CFS034CA301U", "--sim-output-rate-field")
    assert r.returncode == 0, r.stderr
    lines = dict(line.split(":", 1) for line in r.stdout.splitlines())
    assert lines["model"].strip() == "CFS034CA301U"
    assert lines["output rate"].strip() == "1200 Hz"
    assert "Fz 300 N" in lines["rated"] and "Mz 4 N m" in lines["rated"]
    assert lines["filter"].strip() == "0 (off)"


def test_stream_csv_and_jsonl(backend: str, tmp_path: Path) -> None:
    r = run(backend, "stream", "--sim", "--duration", "1")
    assert r.returncode == 0, r.stderr
    rows = r.stdout.splitlines()
    assert rows[0] == "t,fx,fy,fz,mx,my,mz,status"
    assert 1200 * 0.98 <= len(rows) - 1 <= 1200 * 1.02
    assert all(len(row.split(",")) == 8 for row in rows[1:])
    t = [float(row.split(",")[0]) for row in rows[1:]]
    assert t == sorted(t) and t[-1] < 1.05
    assert "samples" in r.stderr

    out = tmp_path / "s.jsonl"
    r = run(backend, "stream", "--sim", "-c", "250", "-f", "jsonl", "-u", "raw", "-o", str(out))
    assert r.returncode == 0, r.stderr
    objs: List[Dict[str, Any]] = [json.loads(x) for x in out.read_text().splitlines()]
    assert len(objs) == 250
    assert set(objs[0]) == {"t", "fx", "fy", "fz", "mx", "my", "mz", "status"}
    assert all(isinstance(o["fx"], int) for o in objs)


def test_stream_tare(backend: str) -> None:
    r = run(backend, "stream", "--sim", "--sim-constant", "--sim-amplitude", "0.4",
            "--tare", "50", "-c", "100")
    assert r.returncode == 0, r.stderr
    vals = [[float(v) for v in row.split(",")[1:7]] for row in r.stdout.splitlines()[1:]]
    assert len(vals) == 100
    assert max(abs(v) for row in vals for v in row) < 1e-6


def test_stream_sigint_exits_0(backend: str) -> None:
    env = subprocess_env(LEPTRINO_BACKEND=backend)
    p = subprocess.Popen([sys.executable, "-m", "leptrino", "stream", "--sim"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        assert p.stdout is not None
        assert p.stdout.readline().startswith("t,fx")
        time.sleep(0.5)
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=20)
    finally:
        p.kill() if p.poll() is None else None
    assert p.returncode == 0, err
    assert "samples" in err


def test_stream_sigterm_writes_every_sample_received(backend: str) -> None:
    # The batch in flight when the signal comes is written, not dropped: every
    # sample received is a row. Only the few data messages still on the line
    # before the stop's answer are discarded (lep_client_stop's contract).
    import leptrino

    env = subprocess_env(LEPTRINO_BACKEND=backend)
    sim = leptrino.Simulator(backend=backend)
    with sim as port:
        p = subprocess.Popen([sys.executable, "-m", "leptrino", "stream", port],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             env=env)
        try:
            assert p.stdout is not None
            assert p.stdout.readline().startswith("t,fx")
            time.sleep(0.45)
            p.send_signal(signal.SIGTERM)
            out, err = p.communicate(timeout=20)
        finally:
            p.kill() if p.poll() is None else None
        sent = sim.stats.samples_sent  # the stream was stopped before the exit
    assert p.returncode == 0, err
    rows = out.splitlines()
    assert len(rows) >= 100
    assert sent - 10 <= len(rows) <= sent, (len(rows), sent, err)
    assert f"{len(rows)} samples" in err


def test_exit_codes(backend: str, tmp_path: Path) -> None:
    assert run(backend, "info").returncode == 2
    assert run(backend, "stream", "--sim", "--count", "0").returncode == 2
    assert run(backend, "info", "--sim", "--bogus").returncode == 2
    assert run(backend, "info", "/dev/x", "--sim-nak", "0.5").returncode == 2
    r = run(backend, "info", str(tmp_path / "missing"))
    assert r.returncode == 6 and "missing" in r.stderr
    r = run(backend, "info", "--sim", "--sim-nak", "1")
    assert r.returncode == 5, r.stderr
    r = run(backend, "stream", "--sim", "--sim-hangup-after", "0.3")
    assert r.returncode == 4, r.stderr
    r = run(backend, "--version")
    assert r.returncode == 0 and backend in r.stdout


def test_plot(backend: str, tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    png = tmp_path / "forces.png"
    r = run(backend, "plot", "--sim", "--seconds", "1", "-o", str(png))
    assert r.returncode == 0, r.stderr
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10000
