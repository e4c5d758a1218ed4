"""Shared helpers for the `leptrino` CLI tests.

The executable under test comes from LEPTRINO_CLI and the stand-alone
virtual sensor from LEPTRINO_CLI_SIM (both set by ctest)."""

from __future__ import annotations

import os
import subprocess
from collections.abc import Iterator
from typing import IO, Sequence

import pytest

CSV_HEADER = "t,fx,fy,fz,mx,my,mz,status"
AXES = ("fx", "fy", "fz", "mx", "my", "mz")


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


def parse_csv(text: str) -> tuple[list[list[float]], list[str]]:
    """Rows of a CSV output (header checked) and its '#' comment lines."""
    lines = text.splitlines()
    assert lines, "no output"
    assert lines[0] == CSV_HEADER
    rows: list[list[float]] = []
    comments: list[str] = []
    for line in lines[1:]:
        if line.startswith("#"):
            comments.append(line)
            continue
        fields = line.split(",")
        assert len(fields) == 8, line
        values = [float(f) for f in fields]
        assert int(fields[7]) == values[7]
        rows.append(values)
    return rows, comments


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
