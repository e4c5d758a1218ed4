"""Finding libleptrino: lookup order and the error when it is missing."""

from __future__ import annotations

import os
import shutil
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
        _loader.load(opener, _version, expected="1.2.3", env="", bundled_dir=tmp_path,
                     find_library=lambda n: None)
    text = str(info.value)
    assert "cannot load the C library libleptrino" in text
    assert str(tmp_path / _loader.bundled_name()) in text and "does not exist" in text
    assert "installed SONAME" in text
    assert "libleptrino.so.1.2" in text and "libleptrino.so.1:" in text
    assert "find_library" in text and "nothing found" in text
    assert "LEPTRINO_LIBRARY" in text and "pip" in text
    assert tried == ["libleptrino.so.1.2", "libleptrino.so.1"]  # only what exists is opened


def _version(lib: object) -> str:
    return "1.2.3"


def test_lookup_order(tmp_path: Path) -> None:
    (tmp_path / _loader.bundled_name()).write_bytes(b"")
    opened: List[str] = []

    def opener(name: str) -> str:
        opened.append(name)
        if name.startswith("/sys-lib"):
            return "lib:" + name
        raise OSError("no")

    lib, what = _loader.load(opener, _version, expected="1.2.3", env="", bundled_dir=tmp_path,
                             find_library=lambda n: "/sys-lib/libleptrino.so")
    assert opened == [str(tmp_path / _loader.bundled_name()), "libleptrino.so.1.2",
                      "libleptrino.so.1", "/sys-lib/libleptrino.so"]
    assert what == "/sys-lib/libleptrino.so"


def test_a_library_of_another_version_is_refused(tmp_path: Path) -> None:
    """Each candidate's lep_version() must equal the package's version: the
    bundled copy of another version is skipped for an installed one that matches."""
    (tmp_path / _loader.bundled_name()).write_bytes(b"")
    versions = {str(tmp_path / _loader.bundled_name()): "0.0.9", "libleptrino.so.0.1": "0.1.0"}
    lib, what = _loader.load(lambda n: n, lambda lib: versions[lib], expected="0.1.0", env="",
                             bundled_dir=tmp_path, find_library=lambda n: None)
    assert what == "libleptrino.so.0.1"
    with pytest.raises(ImportError) as info:
        _loader.load(lambda n: n, lambda lib: "0.2.0", expected="0.1.0", env="",
                     bundled_dir=tmp_path, find_library=lambda n: "/x/libleptrino.so")
    text = str(info.value)
    assert "no libleptrino of version 0.1.0 found" in text
    assert "must be the same version" in text
    assert text.count("is libleptrino 0.2.0, refused: this package is version 0.1.0") == 4


def test_not_a_libleptrino(tmp_path: Path) -> None:
    def no_version(lib: object) -> str:
        raise AttributeError("lep_version")

    lib = tmp_path / "libother.so"
    lib.write_bytes(b"")
    with pytest.raises(ImportError, match="has no lep_version\\(\\): not a libleptrino"):
        _loader.load(lambda n: n, no_version, expected="0.1.0", env=str(lib))


def _fake_library(tmp_path: Path, version: str) -> Path:
    """A real shared library whose lep_version() returns version."""
    cc = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    assert cc, "a C compiler is needed to build the fake library (the suite builds C anyway)"
    src = tmp_path / "fake.c"
    src.write_text(f'const char *lep_version(void) {{ return "{version}"; }}\n')
    out = tmp_path / "libleptrino-fake.so"
    subprocess.run([cc, "-shared", "-fPIC", "-o", str(out), str(src)], check=True,
                   capture_output=True, timeout=120)
    return out


@pytest.mark.parametrize("backend_name", ["ctypes", "cffi"])
def test_mismatched_real_library_is_refused_at_import(tmp_path: Path, backend_name: str) -> None:
    if backend_name == "cffi":
        pytest.importorskip("cffi")
    import leptrino

    fake = _fake_library(tmp_path, "9.8.7")
    env = subprocess_env(LEPTRINO_LIBRARY=str(fake), LEPTRINO_BACKEND=backend_name)
    r = subprocess.run([sys.executable, "-c", "import leptrino"], capture_output=True,
                       text=True, env=env, timeout=60)
    assert r.returncode != 0
    assert "ImportError" in r.stderr
    assert f"no libleptrino of version {leptrino.__version__} found" in r.stderr
    assert f"{fake} is libleptrino 9.8.7, refused: this package is version " \
           f"{leptrino.__version__}" in r.stderr
    # the same library with the package's version passes the check (and then
    # fails only for the functions it lacks)
    ok = _fake_library(tmp_path, leptrino.__version__)
    env = subprocess_env(LEPTRINO_LIBRARY=str(ok), LEPTRINO_BACKEND=backend_name)
    r = subprocess.run([sys.executable, "-c", "import leptrino"], capture_output=True,
                       text=True, env=env, timeout=60)
    assert r.returncode != 0 and "refused" not in r.stderr
    assert "not a matching libleptrino" in r.stderr


def test_package_version_is_cmake_project_version(root: Path) -> None:
    import re

    import leptrino

    m = re.search(r"project\s*\(\s*leptrino\s+VERSION\s+([0-9.]+)",
                  (root / "CMakeLists.txt").read_text())
    assert m and leptrino.__version__ == m.group(1)
    assert leptrino.library_version() == leptrino.__version__


def test_explicit_path_is_the_only_candidate(tmp_path: Path) -> None:
    with pytest.raises(ImportError) as info:
        _loader.load(lambda n: n, _version, expected="1.2.3", env=str(tmp_path / "nope.so"),
                     bundled_dir=tmp_path, find_library=lambda n: "/should/not/be/tried")
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
