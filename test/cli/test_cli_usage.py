"""Command line of `leptrino`: help, version, and every bad-argument path
(exit code 2 with one clear line on stderr, nothing on stdout)."""

from __future__ import annotations

import re

import pytest

from conftest import run

COMMANDS = ["list", "info", "read", "stream", "filter", "watch", "check", "payload"]


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
    for code in range(10):
        assert re.search(rf"^  {code}  \S", r.stdout, re.M), code
    assert re.search(r"^  10\.\.15  check", r.stdout, re.M)


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
    for word in ("fx_N", "mx_Nm", "fx_counts", "fx_zeroed_counts", "t_utc_s", "# gap",
                 "leptrino-metadata", "SIGUSR1", "SIGUSR2", "--split", "leptrino help sim",
                 "--data-timeout"):
        assert word in out, word


@pytest.mark.parametrize("cmd", COMMANDS)
def test_help_shows_the_command_not_the_virtual_sensor(cmd: str) -> None:
    """One line points to the virtual sensor's options; `help sim` lists them."""
    out = run([cmd, "--help"]).stdout
    assert "--sim-model" not in out and "--sim-stall" not in out
    sim = run(["help", "sim"])
    assert sim.returncode == 0 and sim.stderr == ""
    for word in ("--sim-model", "--sim-hangup-after", "--sim-replay", "--sim-rate",
                 "--sim-usb-packets", "--sim-ftdi-latency", "--sim-ppm"):
        assert word in sim.stdout, word


BAD = [
    [],
    ["bogus"],
    ["--bogus"],
    ["--version", "extra"],
    ["--help", "extra"],
    ["stream", "--help", "extra"],
    ["read", "-h", "--sim"],
    ["help", "sim", "extra"],
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
    ["stream", "/dev/ttyUSB9", "/dev/ttyUSB9"],
    ["stream", "--sim", "--sim-amplitude", "5"],
    ["stream", "--sim", "--sim-bogus", "1"],
    ["stream", "--sim", "--columns", "bogus"],
    ["stream", "--sim", "--columns", ""],
    ["stream", "--sim", "--columns", "si,si"],
    ["stream", "--sim", "--columns", "si,"],
    ["stream", "--sim", "--columns", "si", "--units", "raw"],
    ["stream", "--sim", "--time", "local"],
    ["stream", "--sim", "--lowpass", "0"],
    ["stream", "--sim", "--lowpass", "-5"],
    ["stream", "--sim", "--lowpass", "x"],
    ["stream", "--sim", "--lowpass", "1000"],
    ["stream", "--sim", "--decimate", "0"],
    ["stream", "--sim", "--decimate", "1.5"],
    ["stream", "--sim", "--rotate", "1,2"],
    ["stream", "--sim", "--rotate", "a,b,c"],
    ["stream", "--sim", "--rotate", "1,2,3,4"],
    ["stream", "--sim", "--rotate", "0,0,inf"],
    ["stream", "--sim", "--matrix", "1,0,0,0,1,0,0,0"],
    ["stream", "--sim", "--rotate", "0,0,90", "--matrix", "1,0,0,0,1,0,0,0,1"],
    ["stream", "--sim", "--shift", "0,0"],
    ["stream", "--sim", "--latency", "-1"],
    ["stream", "--sim", "--retare", "0"],
    ["stream", "--sim", "--split", "out.csv"],
    ["stream", "--sim", "--split", "{n}.csv", "-o", "x.csv"],
    ["stream", "--sim", "--overwrite=1"],
    ["stream", *["--sim"] * 9],
    ["watch"],
    ["watch", "--sim", "--sim"],
    ["watch", "--sim", "--tare", "0"],
    ["watch", "--sim", "--lowpass", "abc"],
    ["watch", "--sim", "--payload", "-1,0,0,0"],
    ["watch", "--sim", "--payload", "1,0,0"],
    ["watch", "--sim", "--gravity", "0,nan,-9.8"],
    ["watch", "--sim", "--limit", "fz=5"],  # stream's option only
    ["watch", "--sim"],
    ["info", "--sim", "--sim"],
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


@pytest.mark.parametrize("args,words", [
    (["check", "--sim", "--sim"], "--sim given twice"),
    (["check", "/dev/ttyUSB9", "--sim"], "either PORT or --sim"),
    (["check", "--sim", "/dev/ttyUSB9"], "either PORT or --sim"),
    (["check", "/dev/ttyUSB9", "/dev/ttyUSB8"], "unexpected argument '/dev/ttyUSB8'"),
])
def test_one_sensor_commands_say_what_was_given_twice(args: list[str], words: str) -> None:
    r = run(args, timeout=20)
    assert r.returncode == 2 and words in r.stderr, r.stderr
