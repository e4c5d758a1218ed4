"""Finding libleptrino: lookup order and the error when it is missing."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import List

import pytest

from conftest import subprocess_env
from leptrino import _loader


def test_missing_library_names_every_attempt(tmp_path: Path) -> None:
    tried: List[str] = []

    def opener(name: str) -> object:
        tried.append(name)
        raise OSError(f"{name}: cannot open shared object file")

    with pytest.raises(ImportError) as info:
        _loader.load(opener, env="", bundled_dir=tmp_path, find_library=lambda n: None)
    text = str(info.value)
    assert "cannot load the C library libleptrino" in text
    assert str(tmp_path / _loader.soname()) in text and "does not exist" in text
    assert "installed SONAME" in text and _loader.soname() in text
    assert "find_library" in text and "nothing found" in text
    assert "LEPTRINO_LIBRARY" in text and "pip install" in text
    assert tried == [_loader.soname()]  # only what exists is opened


def test_lookup_order(tmp_path: Path) -> None:
    (tmp_path / _loader.soname()).write_bytes(b"")
    opened: List[str] = []

    def opener(name: str) -> str:
        opened.append(name)
        if name.startswith("/sys-lib"):
            return "lib:" + name
        raise OSError("no")

    lib, what = _loader.load(opener, env="", bundled_dir=tmp_path,
                             find_library=lambda n: "/sys-lib/libleptrino.so")
    assert opened == [str(tmp_path / _loader.soname()), _loader.soname(),
                      "/sys-lib/libleptrino.so"]
    assert what == "/sys-lib/libleptrino.so"


def test_explicit_path_is_the_only_candidate(tmp_path: Path) -> None:
    with pytest.raises(ImportError) as info:
        _loader.load(lambda n: n, env=str(tmp_path / "nope.so"), bundled_dir=tmp_path,
                     find_library=lambda n: "/should/not/be/tried")
    assert "LEPTRINO_LIBRARY" in str(info.value) and "nope.so" in str(info.value)
    assert "/should/not" not in str(info.value)


@pytest.mark.parametrize("backend_name", ["ctypes", "cffi"])
def test_import_error_in_a_fresh_interpreter(tmp_path: Path, backend_name: str) -> None:
    if backend_name == "cffi":
        pytest.importorskip("cffi")
    env = subprocess_env(LEPTRINO_LIBRARY=str(tmp_path / "libleptrino.so.0"),
                         LEPTRINO_BACKEND=backend_name)
    r = subprocess.run([sys.executable, "-c", "import leptrino"], capture_output=True,
                       text=True, env=env, timeout=60)
    assert r.returncode != 0
    assert "ImportError" in r.stderr and "cannot load the C library libleptrino" in r.stderr
    assert str(tmp_path / "libleptrino.so.0") in r.stderr


def test_bad_backend_name() -> None:
    import leptrino

    with pytest.raises(ValueError):
        leptrino.get_backend("rust")
    env = subprocess_env(LEPTRINO_BACKEND="rust")
    r = subprocess.run([sys.executable, "-c", "import leptrino"], capture_output=True,
                       text=True, env=env, timeout=60)
    assert r.returncode != 0 and "LEPTRINO_BACKEND" in r.stderr


def test_loaded_library_reports_its_version(backend: str) -> None:
    import leptrino

    assert leptrino.library_version(backend).count(".") == 2
    assert leptrino.get_backend(backend).path
