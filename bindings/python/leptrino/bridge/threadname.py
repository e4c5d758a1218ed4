"""The operating system's name of the calling thread.

Python sets it only from 3.14 on; before, every thread of the bridge shows as
"python" in `top -H`, `ps -L` and /proc/PID/task/TID/comm, and its CPU by
thread (bench/bridge_bench.py) cannot tell the reading thread from the
diagnostics thread. Linux only (prctl PR_SET_NAME, 15 bytes); elsewhere,
nothing.
"""

from __future__ import annotations

import ctypes
import sys

_PR_SET_NAME = 15
#: the longest name Linux keeps (16 bytes with the NUL)
NAME_MAX = 15


def name_this_thread(name: str) -> None:
    """Name the calling thread (cut to NAME_MAX bytes); never raises."""
    if not sys.platform.startswith("linux"):
        return
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_NAME, ctypes.c_char_p(name.encode("utf-8")[:NAME_MAX]),
                   ctypes.c_ulong(0), ctypes.c_ulong(0), ctypes.c_ulong(0))
    except (OSError, AttributeError):  # no C library to ask: the name stays
        pass
