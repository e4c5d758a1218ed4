"""Command line of `leptrino`: help, version, and every bad-argument path
(exit code 2 with one clear line on stderr, nothing on stdout)."""

from __future__ import annotations

import re

import pytest

from conftest import run

COMMANDS = ["list", "info", "read", "stream", "filter"]


def test_version() -> None:
    r = run(["--version"])
    assert r.returncode == 0
    assert re.fullmatch(r"leptrino \d+\.\d+\.\d+\S*\n", r.stdout)


def test_top_level_help_documents_commands_and_exit_codes() -> None:
    r = run(["--help"])
    assert r.returncode == 0
    for cmd in COMMANDS:
        assert f"  {cmd} " in r.stdout
    assert "Exit codes:" in r.stdout
    for code in range(9):
        assert re.search(rf"^  {code}  \S", r.stdout, re.M), code


@pytest.mark.parametrize("cmd", COMMANDS)
def test_help_of_every_command(cmd: str) -> None:
    for args in ([cmd, "--help"], [cmd, "-h"], ["help", cmd]):
        r = run(args)
        assert r.returncode == 0, args
        assert r.stdout.startswith(f"Usage: leptrino {cmd}")
        assert "Exit codes:" in r.stdout
        assert r.stderr == ""


def test_stream_help_documents_units_and_gap() -> None:
    out = run(["stream", "--help"]).stdout
    assert "t,fx,fy,fz,mx,my,mz,status" in out
    assert "N m" in out and "# gap" in out and "--sim-hangup-after" in out


BAD = [
    [],
    ["bogus"],
    ["--bogus"],
    ["--version", "extra"],
    ["--help", "extra"],
    ["help", "bogus"],
    ["list", "extra"],
    ["list", "--bogus"],
    ["info"],
    ["info", ""],
    ["info", "/dev/a", "/dev/b"],
    ["info", "/dev/ttyUSB9", "--sim"],
    ["info", "--sim", "--timeout", "0"],
    ["info", "--sim", "--timeout", "x"],
    ["info", "--sim=1"],
    ["read", "--sim", "-n"],
    ["read", "--sim", "-n", "0"],
    ["read", "--sim", "-n", "-3"],
    ["read", "--sim", "-n", "2.5"],
    ["read", "--sim", "--format", "xml"],
    ["stream"],
    ["stream", "/dev/ttyUSB9", "--sim"],
    ["stream", "--sim", "/dev/ttyUSB9"],
    ["stream", "--sim", "--bogus"],
    ["stream", "--sim", "-x"],
    ["stream", "--sim", "--duration"],
    ["stream", "--sim", "--duration", "abc"],
    ["stream", "--sim", "--duration", "-1"],
    ["stream", "--sim", "--duration", "0"],
    ["stream", "--sim", "--duration", "nan"],
    ["stream", "--sim", "--duration="],
    ["stream", "--sim", "--count", "0"],
    ["stream", "--sim", "--count", "-5"],
    ["stream", "--sim", "--count", "1e3"],
    ["stream", "--sim", "--format", "xml"],
    ["stream", "--sim", "--format"],
    ["stream", "--sim", "--units", "kg"],
    ["stream", "--sim", "--tare", "x"],
    ["stream", "--sim", "--tare", "0"],
    ["stream", "--sim", "-o"],
    ["stream", "--sim", "--reconnect=yes"],
    ["stream", "--sim", "--data-timeout", "-2"],
    ["stream", "/dev/ttyUSB9", "--sim-rate", "100"],
    ["stream", "--sim", "--sim-rate", "0"],
    ["stream", "--sim", "--sim-rate", "fast"],
    ["stream", "--sim", "--sim-model", "NOPE"],
    ["stream", "--sim", "--sim-nak", "1.5"],
    ["stream", "--sim", "--sim-seed", "-1"],
    ["stream", "--sim", "--sim-filter", "4"],
    ["stream", "--sim", "--sim-serial", "123456789"],
    ["stream", "--sim", "--sim-serial", "12a"],
    ["stream", "--sim", "--sim-firmware", "1.13b"],
    ["stream", "--sim", "--sim-rate", "20000"],
    ["stream", "--sim", "--sim-constant=1"],
    ["filter"],
    ["filter", "--sim", "4"],
    ["filter", "--sim", "abc"],
    ["filter", "--sim", "-1"],
    ["filter", "--sim", "2", "3"],
    ["filter", "/dev/ttyUSB9", "2", "3"],
    ["filter", "/dev/ttyUSB9", "on"],
]


@pytest.mark.parametrize("args", BAD, ids=lambda a: " ".join(a) or "(none)")
def test_bad_arguments_exit_2_with_one_line(args: list[str]) -> None:
    r = run(args, timeout=20)
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert r.stdout == ""
    lines = r.stderr.splitlines()
    assert len(lines) == 1, r.stderr
    assert lines[0].startswith("leptrino: ")
