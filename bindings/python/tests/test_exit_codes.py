"""Exit statuses: `python -m leptrino plot` ends with the C tool's status for
every error, because both take it from the library's one table
(lep_exit_code, leptrino/process.h)."""

from __future__ import annotations

import fcntl
import os
import subprocess
import sys
from typing import Iterator, Tuple

import pytest

import leptrino
from conftest import subprocess_env
from leptrino import _constants as K
from leptrino import _tools, cli, errors

#: The statuses docs/cli.md gives, written out apart from the C table.
DOCUMENTED = {
    "OK": 0, "END": 0,
    "TIMEOUT": 3, "NO_SYNC": 3, "STALLED": 3, "LOST": 3,
    "DISCONNECTED": 4,
    "SENSOR": 5, "NAK": 5,
    "NOT_FOUND": 6, "NOT_TTY": 6,
    "BUSY": 7,
    "PERMISSION": 8,
}


def test_every_error_code_gets_the_c_tools_status(backend: str) -> None:
    """For each Error, the exception the bindings raise for it exits python -m
    leptrino with lep_exit_code of its code, on this backend."""
    be = leptrino.get_backend(backend)
    seen = set()
    for code in leptrino.Error:
        exc = errors.error_for(be, int(code), "x")
        assert exc.code is code
        want = int(be.lib.lep_exit_code(int(code)))
        assert want == DOCUMENTED.get(code.name, K.LEP_EXIT_FAIL), code
        got = cli.exit_code(exc, backend)
        if code == leptrino.Error.OK:  # an exception without a library code is a failure
            assert got == K.LEP_EXIT_FAIL
        else:
            assert got == want, code
        seen.add(code.name)
    assert seen >= set(DOCUMENTED)
    # a SensorError (built with the sensor's result code) and a non-leptrino error
    se = errors.error_for(be, K.LEP_E_SENSOR, result=K.LEP_RESULT_STATE)
    assert isinstance(se, leptrino.SensorError) and se.code is leptrino.Error.SENSOR
    assert cli.exit_code(se, backend) == K.LEP_EXIT_SENSOR
    assert cli.exit_code(OSError("disk full"), backend) == K.LEP_EXIT_FAIL


def test_exceptions_keep_their_classes_and_carry_an_error(backend: str) -> None:
    be = leptrino.get_backend(backend)
    for code, cls in ((K.LEP_E_TIMEOUT, leptrino.TimeoutError),
                      (K.LEP_E_STALLED, leptrino.TimeoutError),
                      (K.LEP_E_LOST, leptrino.TimeoutError),
                      (K.LEP_E_NO_SYNC, leptrino.NoSyncError),
                      (K.LEP_E_NOT_FOUND, leptrino.PortNotFoundError),
                      (K.LEP_E_BUSY, leptrino.BusyError),
                      (K.LEP_E_IO, leptrino.LeptrinoError)):
        exc = errors.error_for(be, code)
        assert type(exc) is cls and isinstance(exc.code, leptrino.Error)
        assert exc.code == code and exc.error == code  # .error stays the int
    assert leptrino.LeptrinoError("plain").code is leptrino.Error.OK


def _plot(backend: str, *args: str) -> subprocess.CompletedProcess:
    env = subprocess_env(LEPTRINO_BACKEND=backend, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, "-m", "leptrino", "plot", *args, "-t", "100",
                           "-s", "0.2"], capture_output=True, text=True, timeout=60, env=env)


def _tool(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(_tools.program_path("leptrino")), "info", *args, "-t", "100"],
                          capture_output=True, text=True, timeout=60)


@pytest.fixture
def silent_port() -> Iterator[Tuple[str, int]]:
    """A terminal nobody answers on: the pty's far end, kept open and silent."""
    master, slave = os.openpty()
    try:
        yield os.ttyname(slave), master
    finally:
        os.close(slave)
        os.close(master)


def test_real_failures_exit_alike(backend: str, silent_port: Tuple[str, int]) -> None:
    """The same failure, met for real by the C tool and by python -m leptrino
    plot, ends both with the same status."""
    pytest.importorskip("matplotlib")
    path, _master = silent_port
    cases = {
        "no such port": ("/dev/leptrino-no-such-port", K.LEP_EXIT_NOT_FOUND),
        "not a terminal": ("/dev/null", K.LEP_EXIT_NOT_FOUND),
        "nobody answers": (path, K.LEP_EXIT_TIMEOUT),
    }
    for what, (port, status) in cases.items():
        c, py = _tool(port), _plot(backend, port)
        assert c.returncode == status, (what, c.stderr)
        assert py.returncode == status, (what, py.stderr)
    # the port held by another program (flock, as lep_serial_open takes it)
    fd = os.open(path, os.O_RDWR | os.O_NOCTTY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        c, py = _tool(path), _plot(backend, path)
        assert (c.returncode, py.returncode) == (K.LEP_EXIT_BUSY, K.LEP_EXIT_BUSY), \
            (c.stderr, py.stderr)
    finally:
        os.close(fd)
