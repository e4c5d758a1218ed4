"""What `leptrino stream` writes to a terminal: the live status line never
lands between data rows (stdout and stderr on one terminal: no status line,
only the summary after the last row), and it is drawn when the data go
elsewhere."""

from __future__ import annotations

import os
import pty
import select
import subprocess
import time
from pathlib import Path

from conftest import cli_path

STATUS_SEQ = b"\x1b[K"  # erase to end of line: the status line redraws itself


def run_on_pty(args: list[str], stdout_to_pty: bool, out_file: Path | None = None,
               timeout: float = 60.0) -> tuple[int, bytes]:
    """Run leptrino with stderr (and stdout, if asked) on a new terminal;
    return the exit code and everything the terminal received."""
    master, slave = pty.openpty()
    stdout = slave if stdout_to_pty else open(out_file or os.devnull, "wb")  # noqa: SIM115
    try:
        proc = subprocess.Popen([cli_path(), *args], stdin=subprocess.DEVNULL, stdout=stdout,
                                stderr=slave, close_fds=True)
    finally:
        os.close(slave)
        if not stdout_to_pty:
            stdout.close()
    data = bytearray()
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        ready, _, _ = select.select([master], [], [], 0.2)
        if ready:
            try:
                chunk = os.read(master, 65536)
            except OSError:  # EIO: every writer closed the terminal
                break
            if not chunk:
                break
            data += chunk
        elif proc.poll() is not None:
            break
    code = proc.wait(timeout=10)
    os.close(master)
    return code, bytes(data)


def test_same_terminal_gets_clean_rows_then_the_summary() -> None:
    code, data = run_on_pty(["stream", "--sim", "--duration", "1.5"], stdout_to_pty=True)
    assert code == 0, data[-500:]
    assert STATUS_SEQ not in data
    lines = data.decode().split("\r\n")  # the terminal turns \n into \r\n
    while lines and lines[-1] == "":
        lines.pop()
    assert lines[0].startswith("# leptrino-metadata: {")
    assert lines[1].startswith("t_s,")
    ncols = len(lines[1].split(","))
    summary = lines[-1]
    assert summary.startswith("leptrino: stream:") and "samples" in summary
    rows = lines[2:-1]
    assert len(rows) > 500
    for row in rows:
        if row.startswith("#"):
            continue
        assert "\r" not in row and "leptrino" not in row, row
        assert len(row.split(",")) == ncols, row


def test_status_line_is_drawn_when_data_go_to_a_file(tmp_path: Path) -> None:
    out = tmp_path / "f.csv"
    code, data = run_on_pty(["stream", "--sim", "--duration", "1.5", "-o", str(out)],
                            stdout_to_pty=False)
    assert code == 0, data[-500:]
    assert STATUS_SEQ in data and b"Hz" in data
    # The status line is erased before the summary, which ends the output.
    assert data.rstrip().split(b"\r\n")[-1].split(STATUS_SEQ)[-1].startswith(b"leptrino: stream:")
    assert out.read_text().count("\n") > 500
