"""Warnings about what peers send, at most one per period: a peer that
floods an input with garbage must not flood the log too. The lines held
back are counted and said with the next one."""

from __future__ import annotations

import logging
import threading
import time
from typing import Any

log = logging.getLogger("leptrino.bridge")

#: At most one line per RateLimitedLog this often, seconds.
PERIOD_S = 5.0


class RateLimitedLog:
    """One warning per period at most (thread-safe)."""

    def __init__(self, period_s: float = PERIOD_S) -> None:
        self.period_s = period_s
        self._next = 0.0
        self._suppressed = 0
        self._lock = threading.Lock()

    def warning(self, fmt: str, *args: Any) -> None:
        now = time.monotonic()
        with self._lock:
            if now < self._next:
                self._suppressed += 1
                return
            suppressed, self._suppressed = self._suppressed, 0
            self._next = now + self.period_s
        more = f" ({suppressed} more since the last such line)" if suppressed else ""
        log.warning(fmt + more, *args)
