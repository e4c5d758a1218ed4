"""python -m leptrino: the bundled `leptrino` tool, plus plot in Python; the
console-script launchers."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import subprocess_env
from leptrino import _tools


def run(backend: str, *args: str, timeout: float = 60, **env: str) -> subprocess.CompletedProcess:
    e = subprocess_env(LEPTRINO_BACKEND=backend, **env)
    return subprocess.run([sys.executable, "-m", "leptrino", *args], capture_output=True,
                          text=True, timeout=timeout, env=e)


def tool(name: str, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(_tools.program_path(name)), *args], capture_output=True,
                          text=True, timeout=60)


def test_commands_are_the_c_tool(backend: str) -> None:
    for args in (("--version",), ("info", "--sim", "--sim-model", "CFS034CA301U"),
                 ("info",), ("info", "--sim", "--sim-amplitude", "9"),
                 ("read", "--sim", "-n", "2")):
        py, c = run(backend, *args), tool("leptrino", *args)
        assert py.returncode == c.returncode, (args, py.stderr, c.stderr)
        if args[0] != "read":  # read prints the host time of each sample
            def same(out: str) -> list:  # each run has a virtual sensor of its own
                return [ln for ln in out.splitlines() if not ln.startswith("port:")]

            assert same(py.stdout) == same(c.stdout), args
    assert "CFS034CA301U" in run(backend, "info", "--sim", "--sim-model",
                                 "CFS034CA301U").stdout
    r = run(backend, "--help")
    assert r.returncode == 0 and "plot" in r.stderr


def test_stream_rows_from_the_c_tool(backend: str) -> None:
    r = run(backend, "stream", "--sim", "-c", "50")
    assert r.returncode == 0, r.stderr
    rows = [ln for ln in r.stdout.splitlines() if ln and not ln.startswith("#")]
    assert len(rows) == 51 and rows[0].startswith("t")


def test_missing_program_says_how_to_get_it(backend: str, tmp_path: Path) -> None:
    r = run(backend, "info", "--sim", LEPTRINO_CLI=str(tmp_path / "nope"))
    assert r.returncode == 1
    assert "the leptrino program is not here" in r.stderr and "LEPTRINO_CLI" in r.stderr
    with pytest.raises(ValueError):
        _tools.program_path("rm")


def test_console_script_launchers(tmp_path: Path) -> None:
    for func, name in ((_tools.leptrino, "leptrino"), (_tools.leptrino_sim, "leptrino-sim")):
        code = (f"import sys; sys.argv = ['{name}', '--help']; "
                f"from leptrino._tools import {func.__name__}; {func.__name__}()")
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           env=subprocess_env(), timeout=60)
        assert r.returncode == 0 and name in (r.stdout + r.stderr), r.stderr


def test_plot(backend: str, tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    png = tmp_path / "forces.png"
    r = run(backend, "plot", "--sim", "--seconds", "1", "--sim-model", "CFS018CA201U",
            "--sim-constant", "--tare", "20", "-o", str(png))
    assert r.returncode == 0, r.stderr
    assert "CFS" not in r.stderr
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10000


def test_plot_sim_options_from_the_table(backend: str, tmp_path: Path) -> None:
    r = run(backend, "plot", "--help")
    assert r.returncode == 0
    import leptrino

    for o in leptrino.Simulator.option_table(backend=backend):
        assert f"--sim-{o.flag}" in r.stdout
    png = str(tmp_path / "x.png")
    r = run(backend, "plot", "--sim", "--sim-amplitude", "5", "-o", png)
    assert r.returncode == 2 and "amplitude '5'" in r.stderr, r.stderr
    r = run(backend, "plot", "/dev/x", "--sim-nak", "0.5", "-o", png)
    assert r.returncode == 2 and "need --sim" in r.stderr
    r = run(backend, "plot", str(tmp_path / "missing"), "-o", png)
    assert r.returncode == 6 and "missing" in r.stderr
    assert not os.path.exists(png)


def test_plot_without_matplotlib_names_the_package(backend: str, tmp_path: Path) -> None:
    blocker = tmp_path / "matplotlib"
    blocker.mkdir()
    (blocker / "__init__.py").write_text("raise ImportError('blocked for the test')\n")
    env = subprocess_env(LEPTRINO_BACKEND=backend)
    env["PYTHONPATH"] = str(tmp_path) + os.pathsep + env["PYTHONPATH"]
    t0 = time.monotonic()
    r = subprocess.run([sys.executable, "-m", "leptrino", "plot", "--sim", "--seconds", "30",
                        "-o", str(tmp_path / "x.png")], capture_output=True, text=True, env=env,
                       timeout=60)
    assert r.returncode == 1 and "pip install matplotlib" in r.stderr
    assert time.monotonic() - t0 < 25  # said before the 30 s recording, not after it
