"""Backend selection: ctypes (default) or cffi, by argument or LEPTRINO_BACKEND."""

from __future__ import annotations

import os
import threading
from typing import Any, Dict, Optional

BACKENDS = ("ctypes", "cffi")

_cache: Dict[str, Any] = {}
_lock = threading.Lock()


def default_backend_name() -> str:
    name = os.environ.get("LEPTRINO_BACKEND", "").strip().lower() or "ctypes"
    if name not in BACKENDS:
        raise ImportError(
            f"leptrino: LEPTRINO_BACKEND={name!r} is not one of {', '.join(BACKENDS)}"
        )
    return name


def get_backend(name: Optional[str] = None) -> Any:
    """The loaded backend called name ("ctypes" or "cffi"; None: LEPTRINO_BACKEND,
    else ctypes). Loaded once per process and shared. Raises ImportError when the
    library or the cffi package cannot be loaded, ValueError for another name."""
    if name is None:
        name = default_backend_name()
    elif not isinstance(name, str):
        return name  # already a backend object
    key = name.strip().lower()
    if key not in BACKENDS:
        raise ValueError(f"backend must be one of {', '.join(BACKENDS)}, not {name!r}")
    with _lock:
        be = _cache.get(key)
        if be is None:
            if key == "ctypes":
                from ._ctypes_backend import CtypesBackend

                be = CtypesBackend()
            else:
                from ._cffi_backend import CffiBackend

                be = CffiBackend()
            _cache[key] = be
        return be
