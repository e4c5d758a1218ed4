"""Shared fixtures: both backends, the repository paths, a virtual sensor."""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any, Iterator, Optional

import pytest

HERE = Path(__file__).resolve().parent


def repo_root() -> Optional[Path]:
    """The leptrino checkout these tests belong to (for headers and vectors)."""
    env = os.environ.get("LEPTRINO_SOURCE_DIR")
    for cand in ([Path(env)] if env else []) + [HERE.parent.parent.parent]:
        if (cand / "include" / "leptrino" / "leptrino.h").is_file():
            return cand.resolve()
    return None


ROOT = repo_root()


def _backends() -> list:
    out = [pytest.param("ctypes", id="ctypes")]
    try:
        import cffi  # noqa: F401

        out.append(pytest.param("cffi", id="cffi"))
    except ImportError:
        out.append(pytest.param("cffi", id="cffi",
                                marks=pytest.mark.skip(reason="cffi is not installed")))
    return out


@pytest.fixture(params=_backends())
def backend(request: Any) -> str:
    """Each test that uses it runs once per backend."""
    import leptrino

    leptrino.get_backend(request.param)  # load now: a failure is the test's failure
    return str(request.param)


@pytest.fixture
def root() -> Path:
    if ROOT is None:
        pytest.skip("not run from a leptrino checkout (set LEPTRINO_SOURCE_DIR)")
    assert ROOT is not None
    return ROOT


@pytest.fixture
def sim(backend: str) -> Iterator[Any]:
    """A default virtual sensor for the backend under test."""
    import leptrino

    s = leptrino.Simulator(backend=backend)
    try:
        yield s
    finally:
        s.stop()


@pytest.fixture
def python() -> str:
    return sys.executable


def subprocess_env(**extra: str) -> dict:
    """Environment for a child Python that must import the same leptrino."""
    import leptrino

    pkg_parent = str(Path(leptrino.__file__).resolve().parent.parent)
    env = dict(os.environ, **extra)
    env["PYTHONPATH"] = os.pathsep.join(
        [pkg_parent] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
    return env


#: Rows of the replayed ramp (the bridge tests' virtual sensor input).
RAMP_ROWS = 6000


@pytest.fixture
def ramp(tmp_path: Path) -> str:
    """A replay file: row k has fx = k - 3000, fy = -fx, fz = 3 (k mod 100),
    mx = 100 (k mod 7), my = 1234, mz = -1234 (raw counts)."""
    p = tmp_path / "ramp.csv"
    lines = ["fx,fy,fz,mx,my,mz"]
    for k in range(RAMP_ROWS):
        fx = k - 3000
        lines.append(f"{fx},{-fx},{3 * (k % 100)},{100 * (k % 7)},1234,-1234")
    p.write_text("\n".join(lines) + "\n")
    return str(p)
