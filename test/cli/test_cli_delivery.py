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

from conftest import METADATA_PREFIX, cli_path, data_rows, wait_until

STALL = ["--sim-stall", "4000", "--sim-stall-after", "0.3", "--data-timeout", "20"]
# Rows stamped after this came after the stall (t_s <= 0.3 before it, >= 4.3
# after): the tests tell the two apart on the sensor's clock, never on theirs.
AFTER_STALL_S = 2.0


def _before_stall(text: str) -> list[str]:
    """The whole rows of text stamped before the stall."""
    return [r for r in data_rows(text[:text.rfind("\n") + 1])
            if float(r.split(",")[0]) < AFTER_STALL_S]


def _after_stall(text: str) -> bool:
    return len(_before_stall(text)) < len(data_rows(text[:text.rfind("\n") + 1]))


def test_pipe_gets_each_batch_at_once() -> None:
    p = subprocess.Popen([cli_path(), "stream", "--sim", "--duration", "10", *STALL],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    assert p.stdout is not None
    got = b""  # what came before the first row after the stall
    try:
        # read until a row after the stall comes (a failure bound, not a measure)
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline:
            r, _, _ = select.select([p.stdout], [], [], 0.1)
            if r:
                chunk = os.read(p.stdout.fileno(), 65536)
                assert chunk, "the stream ended before the stall did"
                if _after_stall((got + chunk).decode()):
                    before = _before_stall((got + chunk).decode())
                    break
                got += chunk
        else:
            raise AssertionError("no row after the stall within 60 s")
    finally:
        p.kill()
        p.wait()
    text = got.decode()
    assert text.startswith(METADATA_PREFIX)
    # every row before the stall (0.3 s of them less the start-up) came
    # through while it lasted, whole, not with the rows after it
    assert before and data_rows(text) == before, (len(data_rows(text)), len(before))
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
    snaps: list[str] = []  # the file as read every 20 ms

    def stall_over() -> bool:
        snaps.append(f.read_text() if f.exists() else "")
        return _after_stall(snaps[-1])

    try:
        wait_until(stall_over, "a row after the stall", p)
        p.send_signal(signal.SIGKILL)
        p.wait()
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    # the file as it was last seen during the stall (at most 20 ms before its
    # first row after it was written) held every row of before the stall
    during = [s for s in snaps if not _after_stall(s)][-1]
    after = f.read_text()
    before = _before_stall(after)
    assert during.startswith(METADATA_PREFIX)
    assert before and _before_stall(during) == before, (len(_before_stall(during)), len(before))
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
        wait_until(lambda: len(data_rows(f.read_text() if f.exists() else "")) > 50, "rows", p)
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
    assert len(data_rows(text)) > 50
