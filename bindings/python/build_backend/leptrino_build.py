"""PEP 517 backend: setuptools' own, asking for the PyPI cmake/ninja packages
only when the machine lacks a usable cmake (>= 3.20) or a build tool."""

from __future__ import annotations

import re
import shutil
import subprocess
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


def get_requires_for_build_wheel(config_settings: Optional[Dict[str, Any]] = None) -> List[str]:
    return list(_st.get_requires_for_build_wheel(config_settings)) + _native_requires()


def get_requires_for_build_editable(
    config_settings: Optional[Dict[str, Any]] = None,
) -> List[str]:
    return list(_st.get_requires_for_build_editable(config_settings)) + _native_requires()
