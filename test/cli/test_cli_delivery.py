"""When rows reach their reader (issue 19, item 2; docs/session.md "What a
crash can lose"): into a pipe each batch at once, into a file the metadata
line before the first row and rows at least every 100 ms; kill -9 loses at
most that. The virtual sensor stalls for seconds after a short run: what was
read before the stall must be in the pipe or the file during the stall (a
64 KiB buffer held it until the end before)."""

from __future__ import annotations

import os
import select
import signal
import subprocess
import time
from pathlib import Path

from conftest import METADATA_PREFIX, cli_path

STALL = ["--sim-stall", "4000", "--sim-stall-after", "0.3", "--data-timeout", "20"]


def _rows(text: str) -> list[str]:
    return [ln for ln in text.splitlines() if ln and not ln.startswith("#") and ln[0].isdigit()]


def test_pipe_gets_each_batch_at_once() -> None:
    p = subprocess.Popen([cli_path(), "stream", "--sim", "--duration", "10", *STALL],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    assert p.stdout is not None
    got = b""
    try:
        deadline = time.monotonic() + 3.0  # well inside the 4 s stall
        while time.monotonic() < deadline:
            r, _, _ = select.select([p.stdout], [], [], 0.1)
            if r:
                chunk = os.read(p.stdout.fileno(), 65536)
                if not chunk:
                    break
                got += chunk
        assert p.poll() is None, "the stream ended before the stall did"
    finally:
        p.kill()
        p.wait()
    text = got.decode()
    assert text.startswith(METADATA_PREFIX)
    rows = _rows(text)
    # the 0.3 s before the stall (about 360 rows) came through while it lasted
    assert len(rows) > 200, len(rows)
    assert text.endswith("\n")  # whole rows only


def test_head_ends_the_stream_at_once(tmp_path: Path) -> None:
    """`leptrino stream --sim | head -3` exits as soon as head does."""
    t0 = time.monotonic()
    out = subprocess.run(f"'{cli_path()}' stream --sim --duration 30 | head -3", shell=True,
                         capture_output=True, text=True, timeout=30)
    took = time.monotonic() - t0
    lines = out.stdout.splitlines()
    assert len(lines) == 3 and lines[0].startswith(METADATA_PREFIX)
    assert took < 10.0  # the 30 s --duration did not run out


def test_file_has_rows_during_a_stall_and_after_kill_9(tmp_path: Path) -> None:
    f = tmp_path / "rec.csv"
    p = subprocess.Popen([cli_path(), "stream", "--sim", "--duration", "10", "-o", str(f),
                          *STALL], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        time.sleep(2.0)  # inside the stall, started 0.3 s after the stream
        assert p.poll() is None
        during = f.read_text()
        p.send_signal(signal.SIGKILL)
        p.wait()
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    assert during.startswith(METADATA_PREFIX)
    rows = _rows(during)
    assert len(rows) > 200, len(rows)  # the rows before the stall are on disk
    after = f.read_text()
    assert after.startswith(during)  # kill -9 lost none of them
    assert after.endswith("\n")


def test_kill_9_keeps_the_metadata_line_with_the_tare(tmp_path: Path) -> None:
    """The header is written with the first batch (after a start-up tare, so
    that the metadata holds its offsets) and reaches the disk before it."""
    f = tmp_path / "rec.csv"
    p = subprocess.Popen([cli_path(), "stream", "--sim", "--duration", "10", "-o", str(f),
                          "--tare", "100", "--sim-stall", "4000", "--sim-stall-after", "0.2",
                          "--data-timeout", "20"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        time.sleep(1.5)
        p.send_signal(signal.SIGKILL)
        p.wait()
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    text = f.read_text()
    lines = text.splitlines()
    assert lines[0].startswith(METADATA_PREFIX) and '"tared":true' in lines[0]
    assert lines[1].startswith("t_s,")
    assert len(_rows(text)) > 50
