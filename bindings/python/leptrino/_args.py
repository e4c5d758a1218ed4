"""The one argument policy of the Python API, in the `leptrino` tool's words.

Checked before any call into the library. A value of the wrong kind (a
string, a bool where a number goes, 1.5 where a whole number goes, 0.3 where
True/False goes) is TypeError; a value of the right kind out of its range
(or not finite) is ValueError. Messages name the argument and the value as
the CLI does: "tare: n: 0 is out of range (1 .. 1000000)"."""

from __future__ import annotations

import math
import numbers
from typing import Any, List, Optional, Sequence

import numpy as np


def whole(where: str, name: str, v: Any, lo: int, hi: int) -> int:
    if isinstance(v, bool) or not isinstance(v, numbers.Integral):
        raise TypeError(f"{where}: {name}: {v!r} is not a whole number")
    if not lo <= int(v) <= hi:
        raise ValueError(f"{where}: {name}: {v!r} is out of range ({lo} .. {hi})")
    return int(v)


def number(where: str, name: str, v: Any, lo: float, hi: float,
           lo_exclusive: bool = False) -> float:
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise TypeError(f"{where}: {name}: {v!r} is not a number")
    f = float(v)
    if not math.isfinite(f):
        raise ValueError(f"{where}: {name}: {v!r} is not a number")
    if (f <= lo if lo_exclusive else f < lo) or f > hi:
        raise ValueError(f"{where}: {name}: {v!r} is out of range "
                         f"({'above' if lo_exclusive else 'from'} {lo:g} .. {hi:g})")
    return f


def flag(where: str, name: str, v: Any) -> bool:
    if not isinstance(v, (bool, np.bool_)):
        raise TypeError(f"{where}: {name}: {v!r} is not True or False")
    return bool(v)


def optional_flag(where: str, name: str, v: Any) -> Optional[bool]:
    return None if v is None else flag(where, name, v)


def array_of(where: str, name: str, v: Any, what: str) -> Any:
    """An array of numbers, any shape, as float64 (TypeError for strings,
    bools, None or anything else that is not numbers)."""
    if isinstance(v, (str, bytes)):
        raise TypeError(f"{where}: {name}: {v!r} is not {what}")
    try:
        a = np.asarray(v)
    except Exception:
        raise TypeError(f"{where}: {name}: {v!r} is not {what}") from None
    if a.dtype == np.bool_ or not np.issubdtype(a.dtype, np.number):
        raise TypeError(f"{where}: {name}: {v!r} is not {what}")
    return a.astype(np.float64)


def numbers_of(where: str, name: str, v: Any, shape: Sequence[int], what: str) -> List[float]:
    """An array of finite numbers of this shape, flattened (row-major)."""
    a = array_of(where, name, v, what)
    if a.shape != tuple(shape):
        raise ValueError(f"{where}: {name}: {v!r} is not {what}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{where}: {name}: {v!r} is not {what} (not finite)")
    return [float(x) for x in a.reshape(-1)]


def is_rotation(m: Sequence[float]) -> bool:
    """R R^T = I to 1e-6, as the session checks it (lep_session_set_rotation)."""
    r = np.asarray(m, dtype=np.float64).reshape(3, 3)
    return bool(np.all(np.abs(r @ r.T - np.eye(3)) <= 1e-6))
