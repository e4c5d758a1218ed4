"""What the tool says (issue 19): a lost stream names --data-timeout and
announces the stop's wait with -t/--timeout; the overwrite refusal names
--overwrite; the summary's tare words."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

from conftest import cli_path, data_rows, rows_between, run, wait_until


def test_lost_stream_names_the_options() -> None:
    t0 = time.monotonic()
    out = run(["stream", "--sim", "--sim-stall", "20000", "--sim-stall-after", "0.3",
               "--data-timeout", "0.5", "-t", "100", "-o", os.devnull], timeout=60)
    took = time.monotonic() - t0
    assert out.returncode == 3, out.stderr
    lines = out.stderr.splitlines()
    lost = [ln for ln in lines if "the stream is lost" in ln]
    assert lost and "--data-timeout 0.5" in lost[0] and "--reconnect" in lost[0], out.stderr
    # the wait for the stop is said before it happens, with the option that bounds it
    i = next(k for k, ln in enumerate(lines) if "stopping the sensor's stream" in ln)
    assert "-t/--timeout 100 ms" in lines[i] and "up to 0.4 s" in lines[i]  # one transaction
    j = next(k for k, ln in enumerate(lines) if "could not stop" in ln)
    assert j > i and "-t/--timeout" in lines[j]
    assert took < 10.0  # the 20 s stall was not waited out
    assert "sensor timed out" not in out.stderr


def test_overwrite_refusal_names_the_flag(tmp_path: Path) -> None:
    f = tmp_path / "x.csv"
    f.write_text("keep")
    out = run(["stream", "--sim", "--count", "5", "-o", str(f)])
    assert out.returncode != 0
    assert "--overwrite" in out.stderr, out.stderr
    assert f.read_text() == "keep"


def _summary(out: Path, args: list, signals: list) -> str:
    """The summary line of a stream sent `signals` in turn, each once the
    recording shows the one before it done (its '# tare' line written), the
    first once rows are written (after any start-up tare): never on a
    clock, which a loaded machine outruns."""
    p = subprocess.Popen([cli_path(), "stream", "--sim", "-o", str(out), *args],
                         stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, text=True)
    wait_until(lambda: sum(rows_between(out)) > 0, "rows", p)
    for sig in signals:
        done = len(rows_between(out))
        p.send_signal(sig)
        wait_until(lambda: len(rows_between(out)) > done, f"the tare line of {sig.name}", p)
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=30)
    return [ln for ln in err.splitlines() if " samples in " in ln][0]


def test_summary_says_what_the_tare_is(tmp_path: Path) -> None:
    # a tare, then an un-tare: every tare finished; the summary says untared
    s = _summary(tmp_path / "a.csv", ["--tare", "50"], [signal.SIGUSR2])
    assert "tare incomplete" not in s and "untared" in s, s
    # a tare during a run without --tare is reported
    s = _summary(tmp_path / "b.csv", [], [signal.SIGUSR1])
    assert "tared" in s and "untared" not in s, s
    # no tare at all: nothing said
    s = _summary(tmp_path / "c.csv", [], [])
    assert "tare" not in s, s


def test_replay_of_a_file_cut_by_a_crash(tmp_path: Path) -> None:
    """Replayed up to its last whole row, with a warning (it was refused whole)."""
    f = tmp_path / "raw.csv"
    out = run(["stream", "--sim", "--count", "100", "--columns", "raw", "-o", str(f)])
    assert out.returncode == 0, out.stderr
    text = f.read_text()
    f.write_text(text[:-4])  # the last row cut in its middle, no end of line
    got = tmp_path / "again.csv"
    out = run(["stream", "--sim", "--sim-replay", str(f), "--count", "99", "--columns", "raw",
               "-o", str(got)])
    assert out.returncode == 0, out.stderr
    assert "warning" in out.stderr and "the last line is cut" in out.stderr, out.stderr
    assert "99 whole rows" in out.stderr
    rows = data_rows(text)[:99]
    again = data_rows(got.read_text())
    assert [r.split(",")[1:7] for r in rows] == [r.split(",")[1:7] for r in again]


def test_read_metadata_says_when() -> None:
    """`leptrino read` (no stream) stamps its metadata with the open time,
    not 0 (the start of a stream replaces it)."""
    import json
    import time as _t

    out = run(["read", "--sim", "-n", "2"])
    assert out.returncode == 0, out.stderr
    meta = json.loads(out.stdout.splitlines()[0].split(": ", 1)[1])
    assert abs(meta["start_utc"] - _t.time()) < 60 and meta["start_utc_iso"].endswith("Z")
