"""Tare and untare requests from the network, run one at a time off the
transport's own thread (a tare waits for its samples, and a transport's
callback thread must not wait with it), with a bounded queue: what arrives
while it is full is refused at once, so that a flood of requests is cut and
answered, not queued for minutes."""

from __future__ import annotations

import logging
import threading
from typing import Any, Callable, List, Tuple

from .threadname import name_this_thread

log = logging.getLogger("leptrino.bridge")


class CommandRunner:
    """A thread running submitted actions in order, at most `limit` waiting."""

    def __init__(self, name: str, limit: int) -> None:
        self.limit = limit
        self._cv = threading.Condition()
        self._queue: List[Tuple[str, Callable[[], Any]]] = []
        self._stop = False
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)
        self._thread.start()

    def submit(self, name: str, action: Callable[[], Any]) -> bool:
        """Queue action (name for the log); False, and nothing queued, when
        `limit` are waiting already or the runner is stopped."""
        with self._cv:
            if self._stop or len(self._queue) >= self.limit:
                return False
            self._queue.append((name, action))
            self._cv.notify()
            return True

    def _run(self) -> None:
        name_this_thread("requests")
        while True:
            with self._cv:
                while not self._queue and not self._stop:
                    self._cv.wait()
                if self._stop:
                    return
                name, action = self._queue.pop(0)
            try:
                result = action()
                if result is not None:
                    log.info("%s: %s", name, result)
            except Exception as e:  # an action must not end the thread
                log.warning("%s: %s", name, e)
            del action  # what it holds (a Zenoh query) is released now, not at the next one

    def stop(self, timeout: float = 2.0) -> None:
        """No more actions; the one running may finish (up to timeout s)."""
        with self._cv:
            self._stop = True
            self._cv.notify()
        self._thread.join(timeout)
