"""One thread drives a Sensor at a time; close() is safe from any thread.

The rule (docs: README "Threads", session.h "Threads"): a call that reads
the stream or changes its state (record, stream, read, start, stop, tare
with wait) made while another thread is inside one on the same Sensor, or
holds an open stream() iterator, raises StateError at once. The other calls
(tare offsets, untare, low-pass, frame, health, metadata) may come from any
thread. close() from another thread makes a call in progress raise
StateError at its next read (within one read's wait) and waits for it to
leave before the C session is freed.
"""

from __future__ import annotations

import threading
from contextlib import contextmanager
from typing import Callable, Dict, Iterator, Optional

from . import _constants as K
from .errors import StateError


class Guard:
    def __init__(self) -> None:
        self._cv = threading.Condition()
        self._owner: Optional[int] = None  # thread that drives
        self._depth = 0  # its nested driving calls (and open iterators)
        self._inside: Dict[int, int] = {}  # calls in progress, per thread
        self.closing = False

    def closed_error(self, port: str) -> StateError:
        return StateError(f"{port}: the sensor was closed (by close() or another thread)",
                          K.LEP_E_STATE)

    def _busy_error(self, port: str) -> StateError:
        return StateError(
            f"{port}: the sensor is busy in another thread (recording, streaming or "
            "reading); one thread at a time drives a Sensor, see 'Threads' in the README",
            K.LEP_E_STATE)

    def hold(self, port: str) -> None:
        """Become (or stay) the driving thread; StateError when another is."""
        me = threading.get_ident()
        with self._cv:
            self._hold(me, port)

    def _hold(self, me: int, port: str) -> None:
        if self.closing:
            raise self.closed_error(port)
        if self._owner is not None and self._owner != me:
            raise self._busy_error(port)
        self._owner = me
        self._depth += 1

    def release(self) -> None:
        with self._cv:
            self._release()

    def _release(self) -> None:
        if self._depth > 0:
            self._depth -= 1
        if self._depth == 0:
            self._owner = None
        if self.closing:  # close() waits on the condition; nobody else does
            self._cv.notify_all()

    # The enter/leave pairs below are what every Sensor call runs (a stream
    # reader calls read_batch hundreds of times a second): one lock section
    # each, no generator; call() and drive() are the same as context managers.
    def enter_call(self, port: str) -> None:
        """An any-thread call begins: counted so that close() waits for it."""
        me = threading.get_ident()
        with self._cv:
            if self.closing:
                raise self.closed_error(port)
            self._inside[me] = self._inside.get(me, 0) + 1

    def leave_call(self) -> None:
        """The call entered by enter_call() (in this thread) is over."""
        me = threading.get_ident()
        with self._cv:
            self._leave(me)

    def _leave(self, me: int) -> None:
        n = self._inside[me] - 1
        if n:
            self._inside[me] = n
        else:
            del self._inside[me]
        if self.closing:
            self._cv.notify_all()

    def enter_drive(self, port: str) -> None:
        """A driving call begins: hold(), and counted as enter_call() does."""
        me = threading.get_ident()
        with self._cv:
            self._hold(me, port)
            self._inside[me] = self._inside.get(me, 0) + 1

    def leave_drive(self) -> None:
        """The call entered by enter_drive() (in this thread) is over."""
        me = threading.get_ident()
        with self._cv:
            self._leave(me)
            self._release()

    @contextmanager
    def call(self, port: str) -> Iterator[None]:
        """Any-thread call: counted so that close() waits for it."""
        self.enter_call(port)
        try:
            yield
        finally:
            self.leave_call()

    @contextmanager
    def drive(self, port: str) -> Iterator[None]:
        self.enter_drive(port)
        try:
            yield
        finally:
            self.leave_drive()

    def check(self, port: str) -> None:
        """Between two reads: StateError when close() has begun."""
        if self.closing:
            raise self.closed_error(port)

    def close(self, free: Callable[[], None]) -> None:
        """Mark closing, wait for the calls inside to leave (each sees the
        mark at its next read), then free. A call in this same thread (close
        from inside a loop body) is not waited for."""
        me = threading.get_ident()
        with self._cv:
            self.closing = True
            while any(t != me for t in self._inside):
                self._cv.wait()
        free()
