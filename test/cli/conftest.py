"""Shared helpers for the `leptrino` CLI tests.

The executable under test comes from LEPTRINO_CLI and the stand-alone
virtual sensor from LEPTRINO_CLI_SIM (both set by ctest)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO, Any, Sequence

import pytest

CSV_HEADER = "t_s,fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm,status"
AXES = ("fx_N", "fy_N", "fz_N", "mx_Nm", "my_Nm", "mz_Nm")
RAW = ("fx_counts", "fy_counts", "fz_counts", "mx_counts", "my_counts", "mz_counts")
ZEROED = tuple(a.replace("_counts", "_zeroed_counts") for a in RAW)
METADATA_PREFIX = "# leptrino-metadata: "


def cli_path() -> str:
    path = os.environ.get("LEPTRINO_CLI")
    if not path:
        pytest.fail("LEPTRINO_CLI is not set (run the tests through ctest)")
    return path


def run(args: Sequence[str], timeout: float = 60.0) -> subprocess.CompletedProcess[str]:
    """Run leptrino with args; stdin closed, output captured as text."""
    return subprocess.run(
        [cli_path(), *args],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


def wait_until(cond: Callable[[], bool], what: str,
               proc: subprocess.Popen[Any] | None = None, timeout: float = 60.0) -> None:
    """Poll cond until it holds: the tests wait for what they need to have
    happened, never for a time. The timeout is a failure bound only (a loaded
    machine is slow, never wrong); a proc that exits meanwhile fails at once."""
    deadline = time.monotonic() + timeout
    while not cond():
        if proc is not None and proc.poll() is not None:
            pytest.fail(f"waiting for {what}: the process exited ({proc.returncode})")
        if time.monotonic() > deadline:
            pytest.fail(f"waiting for {what}: not within {timeout:g} s")
        time.sleep(0.02)


def data_rows(text: str) -> list[str]:
    """The data rows of a CSV the CLI wrote (no '#' line, not the header).
    A row starts with its time, and t_s may be a little below 0 for the
    first samples: stamped on the sensor's clock, they left it before the
    host noted the start (its answer read late on a loaded machine)."""
    return [ln for ln in text.splitlines() if ln[:1].isdigit() or ln[:1] == "-"]


def rows_between(path: Path, word: str = "tare") -> list[int]:
    """The rows a running `stream -o path` has written so far (whole lines),
    counted between its '# WORD ...' event lines: [before the first, after
    the first, ...]; [0] while nothing is written."""
    counts = [0]
    header = False
    text = path.read_text() if path.exists() else ""
    for line in text.split("\n")[:-1]:  # (a last line cut in its middle is not counted)
        if line.startswith("#"):
            parts = line[1:].split()
            if parts and parts[0] == word:
                counts.append(0)
        elif header:
            counts[-1] += 1
        else:
            header = True
    return counts


def wait_rows_after(path: Path, events: int, rows: int, proc: subprocess.Popen[Any] | None,
                    word: str = "tare") -> None:
    """Wait until path holds `events` '# WORD' event lines and `rows` rows
    after the last of them (rows in all when events is 0)."""
    def done() -> bool:
        c = rows_between(path, word)
        return len(c) > events and c[events] >= rows
    wait_until(done, f"{rows} rows after {events} '# {word}' lines in {path.name}", proc)


def wait_catching(proc: subprocess.Popen[Any], sig: signal.Signals) -> None:
    """Wait until proc has a handler for sig (Linux: SigCgt in /proc/PID/status):
    a signal sent before that would kill it instead of being handled."""
    def catching() -> bool:
        with open(f"/proc/{proc.pid}/status") as f:
            for line in f:
                if line.startswith("SigCgt:"):
                    return bool(int(line.split()[1], 16) >> (int(sig) - 1) & 1)
        return False
    wait_until(catching, f"a handler for {sig.name}", proc)


class Csv:
    """A CSV recording of the tool, read without pandas: the metadata
    objects, the header, the rows (as dicts of floats, or str for the sensor
    column) and the other '#' comment lines (events), in order."""

    def __init__(self, text: str, header: str | None = None) -> None:
        lines = text.splitlines()
        assert lines, "no output"
        self.metadata: list[dict[str, Any]] = []
        i = 0
        while i < len(lines) and lines[i].startswith(METADATA_PREFIX):
            self.metadata.append(json.loads(lines[i][len(METADATA_PREFIX):]))
            i += 1
        assert self.metadata, "no metadata header"
        assert i < len(lines), "no header line"
        self.header = lines[i].split(",")
        if header is not None:
            assert lines[i] == header
        self.rows: list[dict[str, Any]] = []
        self.comments: list[str] = []
        self.lines_after_header = lines[i + 1:]
        for line in lines[i + 1:]:
            if line.startswith("#"):
                self.comments.append(line)
                continue
            fields = line.split(",")
            assert len(fields) == len(self.header), line
            row: dict[str, Any] = {}
            for name, value in zip(self.header, fields):
                row[name] = value if name == "sensor" else float(value)
            self.rows.append(row)

    def column(self, name: str) -> list[Any]:
        return [r[name] for r in self.rows]

    def events(self, word: str) -> list[dict[str, str]]:
        """'# WORD k=v k=v' comment lines as dicts."""
        out = []
        for c in self.comments:
            parts = c[1:].split()
            if parts and parts[0] == word:
                out.append(dict(p.split("=", 1) for p in parts[1:] if "=" in p))
        return out


def parse_csv(text: str) -> tuple[list[list[float]], list[str]]:
    """Rows of a default-columns CSV output (header checked) as lists, and
    its '#' comment lines other than the metadata."""
    csv = Csv(text, CSV_HEADER)
    return [[r[k] for k in csv.header] for r in csv.rows], csv.comments


def parse_jsonl(text: str) -> tuple[list[dict[str, Any]], list[dict[str, Any]],
                                    list[dict[str, Any]]]:
    """(metadata objects, sample objects, event objects) of a JSON-lines output."""
    meta, rows, events = [], [], []
    for line in text.splitlines():
        obj = json.loads(line)
        if "metadata" in obj:
            assert not rows, "metadata after samples"
            meta.append(obj["metadata"])
        elif "event" in obj:
            events.append(obj)
        else:
            rows.append(obj)
    return meta, rows, events


class SimProcess:
    """A virtual sensor in a process of its own (lep_cli_sim)."""

    def __init__(self, *args: str) -> None:
        helper = os.environ.get("LEPTRINO_CLI_SIM")
        if not helper:
            pytest.fail("LEPTRINO_CLI_SIM is not set (run the tests through ctest)")
        self.proc = subprocess.Popen(
            [helper, *args],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )
        out = self._stdout().readline().strip()
        assert out, "lep_cli_sim printed no port"
        self.port = out

    def _stdout(self) -> IO[str]:
        assert self.proc.stdout is not None
        return self.proc.stdout

    def ask(self, command: str) -> str:
        assert self.proc.stdin is not None
        self.proc.stdin.write(command + "\n")
        self.proc.stdin.flush()
        return self._stdout().readline().strip()

    def stats(self) -> dict[str, int]:
        line = self.ask("stats")
        return {k: int(v) for k, v in (item.split("=") for item in line.split())}

    def close(self) -> None:
        if self.proc.poll() is None:
            try:
                self.ask("quit")
            except (BrokenPipeError, OSError):
                pass
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()


@pytest.fixture
def sim() -> Iterator[SimProcess]:
    s = SimProcess()
    yield s
    s.close()
