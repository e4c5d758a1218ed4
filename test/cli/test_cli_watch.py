"""`leptrino watch` (and `stream`'s keys) in a real terminal: tmux runs the
program in a detached session, keys go in with send-keys, the screen comes
back with capture-pane.

Skipped only when tmux is not installed; CI installs it: .ci/checks/40-cli.sh
sets LEPTRINO_REQUIRE_TMUX=1, which turns the skip into a failure."""

from __future__ import annotations

import math
import os
import re
import shlex
import shutil
import signal
import subprocess
import time
import uuid
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from conftest import Csv, cli_path, wait_rows_after

if shutil.which("tmux") is None:
    if os.environ.get("LEPTRINO_REQUIRE_TMUX") == "1":
        pytest.fail("tmux is required here (LEPTRINO_REQUIRE_TMUX=1) but not installed",
                    pytrace=False)
    pytest.skip("tmux is not installed", allow_module_level=True)

AXES = ("Fx", "Fy", "Fz", "Mx", "My", "Mz")


class Tmux:
    """One detached tmux server and session of our own (own socket)."""

    def __init__(self, command: str, cols: int = 100, rows: int = 30) -> None:
        self.socket = f"leptrino-test-{uuid.uuid4().hex[:8]}"
        self.name = "w"
        self._tmux("new-session", "-d", "-s", self.name, "-x", str(cols), "-y", str(rows),
                   command)

    def _tmux(self, *args: str) -> str:
        r = subprocess.run(["tmux", "-L", self.socket, *args], capture_output=True, text=True,
                           timeout=20, check=False)
        assert r.returncode == 0, (args, r.stderr)
        return r.stdout

    def screen(self) -> str:
        return self._tmux("capture-pane", "-p", "-J", "-t", self.name)  # -J: wrapped lines joined

    def keys(self, *keys: str) -> None:
        self._tmux("send-keys", "-t", self.name, *keys)

    def resize(self, cols: int, rows: int) -> None:
        self._tmux("resize-window", "-t", self.name, "-x", str(cols), "-y", str(rows))

    def wait_for(self, pred: Callable[[str], bool], timeout: float = 20.0) -> str:
        deadline = time.monotonic() + timeout
        text = ""
        while time.monotonic() < deadline:
            text = self.screen()
            if pred(text):
                return text
            time.sleep(0.1)
        raise AssertionError(f"screen never matched; last screen:\n{text}")

    def program_pid(self) -> int:
        """The pid of leptrino: the child of the pane's shell."""
        shell = int(self._tmux("display-message", "-p", "-t", self.name, "#{pane_pid}"))
        children = []
        for entry in os.listdir("/proc"):
            if not entry.isdigit():
                continue
            try:
                with open(f"/proc/{entry}/stat") as f:
                    stat = f.read()
            except OSError:
                continue
            # pid (comm) state ppid ...: comm may hold spaces, so split after ')'
            if int(stat.rsplit(")", 1)[1].split()[1]) == shell:
                children.append(int(entry))
        assert len(children) == 1, children
        return children[0]

    def close(self) -> None:
        subprocess.run(["tmux", "-L", self.socket, "kill-server"], capture_output=True,
                       timeout=20, check=False)


def shell_command(args: list[str], marker: str) -> str:
    """Run leptrino in a shell that reports how it ended and whether the
    terminal settings came back, then stays (so the pane can be read)."""
    cmd = " ".join(shlex.quote(a) for a in [cli_path(), *args])
    return ("sh -c " + shlex.quote(
        f"trap : INT; before=$(stty -g); {cmd} 2>/tmp/{marker}.err; code=$?; "
        f"if [ \"$(stty -g)\" = \"$before\" ]; then t=restored; else t=changed; fi; "
        f"echo {marker} exit=$code tty=$t; sleep 60"))


@pytest.fixture
def marker() -> Iterator[str]:
    m = f"END{uuid.uuid4().hex[:6]}"
    yield m
    try:
        os.unlink(f"/tmp/{m}.err")
    except FileNotFoundError:
        pass


def axis_values(screen: str) -> dict[str, float]:
    values = {}
    for axis in AXES:
        m = re.search(rf"^\S?\s*{axis}\s+(-?\d+\.\d+) ", screen, re.M)
        if m:
            values[axis] = float(m.group(1))
    return values


def bar_width(screen: str) -> int:
    m = re.search(r"^\S?\s*Fx\s+\S+\s+N\s+(\[.*\])", screen, re.M)
    assert m, screen
    return len(m.group(1))


def has_all_axes(screen: str) -> bool:
    return len(axis_values(screen)) == 6


def test_watch_tare_untare_resize_quit(marker: str) -> None:
    t = Tmux(shell_command(["watch", "--sim", "--sim-constant", "--sim-amplitude", "0.3",
                            "--tare", "50"], marker))
    try:
        screen = t.wait_for(has_all_axes)
        assert "PFS055YA501U6" in screen and "keys" in screen
        assert re.search(r"rate\s+\d", screen)
        assert "tare      off" in screen
        # A constant load of 0.3 x rated: Fx = 150 N on a 500 N sensor, bar 30 % full.
        loaded = axis_values(screen)
        assert abs(loaded["Fx"] - 150.0) < 10.0, screen
        assert "30.0 %" in screen or "29.9 %" in screen or "30.1 %" in screen

        t.keys("t")
        screen = t.wait_for(lambda s: "tare      on" in s
                            and all(abs(v) < 1.0 for v in axis_values(s).values())
                            and has_all_axes(s))
        t.keys("u")
        screen = t.wait_for(lambda s: "tare      off" in s and has_all_axes(s)
                            and abs(axis_values(s)["Fx"] - 150.0) < 10.0)

        wide = bar_width(screen)
        t.resize(70, 24)
        screen = t.wait_for(lambda s: has_all_axes(s) and bar_width(s) < wide)
        assert all(len(line) <= 70 for line in screen.splitlines())
        t.resize(30, 10)
        t.wait_for(lambda s: "too small" in s)
        t.resize(100, 30)
        t.wait_for(lambda s: has_all_axes(s) and bar_width(s) == wide)

        t.keys("q")
        screen = t.wait_for(lambda s: marker in s)
        assert f"{marker} exit=0 tty=restored" in screen
        assert "keys" not in screen  # back on the normal screen
        with open(f"/tmp/{marker}.err") as f:
            assert "leptrino: watch:" in f.read()
    finally:
        t.close()


def test_watch_payload_and_gravity(marker: str) -> None:
    """A tool of 1.5 kg on the virtual sensor (its own gravity: z up, no other
    load): with --payload its weight is gone from the view; with --gravity
    tilted 30 degrees about y the view shows w(g_sim) - w(g), computed here."""
    tool = (1.5, 0.02, -0.01, 0.06)
    sim = ["--sim", "--sim-constant", "--sim-amplitude", "0",
           "--sim-payload", ",".join(map(str, tool))]
    g = (9.80665 * math.sin(math.radians(30)), 0.0, -9.80665 * math.cos(math.radians(30)))

    def weight(gv: tuple[float, float, float]) -> list[float]:
        f = [tool[0] * x for x in gv]
        c = tool[1:]
        return f + [c[1] * f[2] - c[2] * f[1], c[2] * f[0] - c[0] * f[2],
                    c[0] * f[1] - c[1] * f[0]]

    want_flat = [0.0] * 6
    want_tilt = [a - b for a, b in zip(weight((0.0, 0.0, -9.80665)), weight(g))]
    for extra, want in (([], want_flat), (["--gravity", ",".join(map(str, g))], want_tilt)):
        t = Tmux(shell_command(["watch", *sim, "--payload", ",".join(map(str, tool)), *extra],
                               marker))
        try:
            screen = t.wait_for(lambda s: has_all_axes(s) and "payload 1.5 kg" in s)
            got = axis_values(screen)
            for axis, w in zip(AXES, want):
                assert abs(got[axis] - w) < 0.08, (axis, got[axis], w, screen)
            assert "payload 1.5 kg at 0.02 -0.01 0.06 m" in screen
            t.keys("q")
            assert f"{marker} exit=0 tty=restored" in t.wait_for(lambda s: marker in s)
        finally:
            t.close()


def test_watch_sigterm_restores_the_terminal(marker: str) -> None:
    t = Tmux(shell_command(["watch", "--sim"], marker))
    try:
        t.wait_for(has_all_axes)
        os.kill(t.program_pid(), signal.SIGTERM)
        screen = t.wait_for(lambda s: marker in s)
        assert f"{marker} exit=0 tty=restored" in screen
    finally:
        t.close()


def test_watch_sigusr1_tares(marker: str) -> None:
    t = Tmux(shell_command(["watch", "--sim", "--sim-constant", "--sim-seed", "7"], marker))
    try:
        t.wait_for(has_all_axes)
        os.kill(t.program_pid(), signal.SIGUSR1)
        t.wait_for(lambda s: "tare      on" in s)
        t.keys("q")
        assert f"{marker} exit=0 tty=restored" in t.wait_for(lambda s: marker in s)
    finally:
        t.close()


def test_watch_lost_port_ends_with_exit_4_and_a_restored_terminal(marker: str) -> None:
    t = Tmux(shell_command(["watch", "--sim", "--sim-hangup-after", "1"], marker))
    try:
        screen = t.wait_for(lambda s: marker in s)
        assert f"{marker} exit=4 tty=restored" in screen
        with open(f"/tmp/{marker}.err") as f:
            assert "disconnected" in f.read()
    finally:
        t.close()


def test_stream_keys_tare_and_untare_in_a_terminal(marker: str, tmp_path: Path) -> None:
    out = tmp_path / "keys.csv"
    t = Tmux(shell_command(["stream", "--sim", "--sim-constant", "--retare", "50",
                            "-o", str(out)], marker))
    try:
        # each key once the recording shows what came before it
        wait_rows_after(out, 0, 100, None)  # loaded rows
        t.keys("t")
        wait_rows_after(out, 1, 500, None)  # zeroed rows after the tare
        t.keys("u")
        wait_rows_after(out, 2, 100, None)  # loaded again after the untare
        t.keys("C-c")
        screen = t.wait_for(lambda s: marker in s)
        assert f"{marker} exit=0 tty=restored" in screen
    finally:
        t.close()
    csv = Csv(out.read_text())
    assert len(csv.events("tare")) == 2, csv.comments
    fx = csv.column("fx_N")
    assert abs(fx[0] - 100.0) < 1.0 and abs(fx[-1] - 100.0) < 1.0
    assert len([v for v in fx if abs(v) < 0.05]) > 400


def test_stream_as_a_background_job_is_not_stopped(tmp_path: Path) -> None:
    # An interactive shell with job control: a background job that touched
    # the terminal would be stopped (SIGTTOU) instead of finishing.
    out = tmp_path / "bg.csv"
    t = Tmux("bash --norc --noprofile -i")
    try:
        t.keys(" ".join(shlex.quote(a) for a in [cli_path(), "stream", "--sim", "--duration",
                                                 "1", "-o", str(out)]) + " &", "Enter")
        # until the job has finished or stopped (jobs -r: the running ones)
        t.keys("while [ -n \"$(jobs -r)\" ]; do sleep 0.1; done; jobs; echo BG-DONE", "Enter")
        screen = t.wait_for(lambda s: re.search(r"^BG-DONE\s*$", s, re.M) is not None)
        assert "Stopped" not in screen, screen
        assert "samples in" in screen  # the summary, on the terminal
    finally:
        t.close()
    assert len(Csv(out.read_text()).rows) > 500
