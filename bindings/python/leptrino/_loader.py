"""Find and open libleptrino, and check that it is this package's version.

Lookup order:
  1. the path in the LEPTRINO_LIBRARY environment variable (when set, it is
     the only candidate: an explicit choice that fails is an error, never a
     silent fall-back to another copy);
  2. the copy bundled in this package (leptrino/_lib/libleptrino.so, put
     there by ``pip install``);
  3. the installed SONAME (libleptrino.so.<major>.<minor>, then
     libleptrino.so.<major>) through the dynamic linker's search path;
  4. ctypes.util.find_library("leptrino").
A library whose lep_version() differs from the package's version is refused
(the bindings declare the structures of their own version; while 0.x, any
release may change them) and the search goes on. ImportError lists every
attempt and why it failed.

The package's version comes from leptrino/_version.py, written by the build
from project(VERSION) in the top CMakeLists.txt; a source-tree run (no
build) reads that CMakeLists.txt itself.
"""

from __future__ import annotations

import ctypes.util
import os
import re
import sys
from pathlib import Path
from typing import Any, Callable, List, Optional, Sequence, Tuple

BUNDLED_DIR = Path(__file__).resolve().parent / "_lib"
_SOURCE_TREE_CMAKE = Path(__file__).resolve().parent.parent.parent.parent / "CMakeLists.txt"


def package_version() -> str:
    """This package's version ("0.1.0"): the build's _version.py, else the
    checkout's CMakeLists.txt. ImportError when neither exists."""
    try:
        # written by setup.py at build time: absent from a checkout (then CMakeLists.txt)
        from ._version import VERSION  # type: ignore[import-not-found,unused-ignore]

        return str(VERSION)
    except ImportError:
        pass
    try:
        text = _SOURCE_TREE_CMAKE.read_text(encoding="utf-8")
    except OSError:
        text = ""
    m = re.search(r"project\s*\(\s*leptrino\s+VERSION\s+([0-9]+(?:\.[0-9]+)*)", text)
    if not m:
        raise ImportError(
            "leptrino: this copy of the package has no leptrino/_version.py (its build writes "
            f"it) and is not inside a leptrino checkout ({_SOURCE_TREE_CMAKE} has no "
            "project(leptrino VERSION ...)). Install it with pip from the sdist or a checkout "
            "(pip install ./bindings/python)."
        )
    return m.group(1)


def bundled_name() -> str:
    return "libleptrino.dylib" if sys.platform == "darwin" else "libleptrino.so"


def sonames(version: str) -> List[str]:
    """Installed names to try: major.minor (the SONAME while 0.x), then major."""
    parts = version.split(".")
    major, minor = parts[0], parts[1] if len(parts) > 1 else "0"
    if sys.platform == "darwin":
        return [f"libleptrino.{major}.{minor}.dylib", f"libleptrino.{major}.dylib"]
    return [f"libleptrino.so.{major}.{minor}", f"libleptrino.so.{major}"]


def candidates(
    version: str,
    env: Optional[str] = None,
    bundled_dir: Optional[Path] = None,
    find_library: Callable[[str], Optional[str]] = ctypes.util.find_library,
) -> List[Tuple[str, Optional[str]]]:
    """(description, path or name to open, or None when there is nothing to try)."""
    if env:
        return [("LEPTRINO_LIBRARY", env)]
    bdir = BUNDLED_DIR if bundled_dir is None else bundled_dir
    bundled = bdir / bundled_name()
    return ([("bundled copy", str(bundled) if bundled.is_file() else None)]
            + [("installed SONAME", name) for name in sonames(version)]
            + [("system search (ctypes.util.find_library)", find_library("leptrino"))])


def load(
    opener: Callable[[str], Any],
    version_of: Callable[[Any], str],
    path: Optional[str] = None,
    *,
    expected: Optional[str] = None,
    env: Optional[str] = None,
    bundled_dir: Optional[Path] = None,
    find_library: Callable[[str], Optional[str]] = ctypes.util.find_library,
) -> Tuple[Any, str]:
    """Open the first candidate with opener (ctypes.CDLL or ffi.dlopen) whose
    version_of(library) equals expected (default: package_version()).

    path, when given, is the only candidate. Returns (library, what was opened)."""
    if expected is None:
        expected = package_version()
    if path is not None:
        cands: Sequence[Tuple[str, Optional[str]]] = [("path argument", path)]
    else:
        if env is None:
            env = os.environ.get("LEPTRINO_LIBRARY") or None
        cands = candidates(expected, env, bundled_dir, find_library)
    tried: List[str] = []
    mismatch = False
    for what, target in cands:
        if target is None:
            where = bundled_dir if bundled_dir is not None else BUNDLED_DIR
            if what == "bundled copy":
                tried.append(f"  - {what}: {where / bundled_name()} does not exist")
            else:
                tried.append(f"  - {what}: nothing found")
            continue
        if what in ("LEPTRINO_LIBRARY", "path argument") and not os.path.exists(target):
            tried.append(f"  - {what}: {target} does not exist")
            continue
        try:
            lib = opener(target)
        except OSError as exc:
            tried.append(f"  - {what}: {target}: {exc}")
            continue
        try:
            got = version_of(lib)
        except AttributeError:
            tried.append(f"  - {what}: {target} has no lep_version(): not a libleptrino")
            continue
        if got != expected:
            mismatch = True
            tried.append(f"  - {what}: {target} is libleptrino {got}, refused: this package "
                         f"is version {expected}")
            continue
        return lib, target
    if mismatch:
        head = (f"leptrino: no libleptrino of version {expected} found. The Python package "
                f"and the C library must be the same version (the bindings declare the "
                f"library's structures as of {expected}). Tried, in order:\n")
    else:
        head = "leptrino: cannot load the C library libleptrino. Tried, in order:\n"
    raise ImportError(
        head
        + "\n".join(tried)
        + "\nReinstall the bindings with pip (the wheel and the sdist bundle a matching "
        "library), install libleptrino " + expected + " system-wide, or set "
        "LEPTRINO_LIBRARY to the path of a matching libleptrino.so."
    )
