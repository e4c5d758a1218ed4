"""Find and open libleptrino.

Lookup order:
  1. the path in the LEPTRINO_LIBRARY environment variable (when set, it is
     the only candidate: an explicit choice that fails is an error, never a
     silent fall-back to another copy);
  2. the copy bundled in this package (leptrino/_lib/, put there by
     ``pip install``);
  3. the installed SONAME (libleptrino.so.0 / libleptrino.0.dylib) through
     the dynamic linker's search path;
  4. ctypes.util.find_library("leptrino").
ImportError lists every attempt and why it failed.
"""

from __future__ import annotations

import ctypes.util
import os
import sys
from pathlib import Path
from typing import Any, Callable, List, Optional, Sequence, Tuple

#: ABI major of the library these bindings are written for.
ABI_MAJOR = 0

BUNDLED_DIR = Path(__file__).resolve().parent / "_lib"


def soname() -> str:
    if sys.platform == "darwin":
        return f"libleptrino.{ABI_MAJOR}.dylib"
    return f"libleptrino.so.{ABI_MAJOR}"


def candidates(
    env: Optional[str] = None,
    bundled_dir: Optional[Path] = None,
    find_library: Callable[[str], Optional[str]] = ctypes.util.find_library,
) -> List[Tuple[str, Optional[str]]]:
    """(description, path or name to open, or None when there is nothing to try)."""
    if env:
        return [("LEPTRINO_LIBRARY", env)]
    bdir = BUNDLED_DIR if bundled_dir is None else bundled_dir
    bundled = bdir / soname()
    found = find_library("leptrino")
    return [
        ("bundled copy", str(bundled) if bundled.is_file() else None),
        ("installed SONAME", soname()),
        ("system search (ctypes.util.find_library)", found),
    ]


def load(
    opener: Callable[[str], Any],
    path: Optional[str] = None,
    *,
    env: Optional[str] = None,
    bundled_dir: Optional[Path] = None,
    find_library: Callable[[str], Optional[str]] = ctypes.util.find_library,
) -> Tuple[Any, str]:
    """Open the first candidate with opener (ctypes.CDLL or ffi.dlopen).

    path, when given, is the only candidate. Returns (library, what was opened)."""
    if path is not None:
        cands: Sequence[Tuple[str, Optional[str]]] = [("path argument", path)]
    else:
        if env is None:
            env = os.environ.get("LEPTRINO_LIBRARY") or None
        cands = candidates(env, bundled_dir, find_library)
    tried: List[str] = []
    for what, target in cands:
        if target is None:
            where = bundled_dir if bundled_dir is not None else BUNDLED_DIR
            if what == "bundled copy":
                tried.append(f"  - {what}: {where / soname()} does not exist")
            else:
                tried.append(f"  - {what}: nothing found")
            continue
        if what in ("LEPTRINO_LIBRARY", "path argument") and not os.path.exists(target):
            tried.append(f"  - {what}: {target} does not exist")
            continue
        try:
            return opener(target), target
        except OSError as exc:
            tried.append(f"  - {what}: {target}: {exc}")
    raise ImportError(
        "leptrino: cannot load the C library libleptrino. Tried, in order:\n"
        + "\n".join(tried)
        + "\nInstall the bindings with `pip install ./bindings/python` (which builds and "
        "bundles it), install libleptrino system-wide, or set LEPTRINO_LIBRARY to the path "
        "of libleptrino.so."
    )
