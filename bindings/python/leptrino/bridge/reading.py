"""One reading thread for all the sensors of a bridge.

Each wake-up of a Python thread costs more than the work it does (the code
runs cold after a sleep: docs/bridge.md, "Figures"), so the bridge's sensors
share one: it sleeps out the latency budget once, then takes from each
sensor's session what it has without waiting (SensorNode.read_pass with a
0 ms timeout: the session neither sleeps nor polls then) and publishes it.

A sensor whose stream is down, failing or silent (SensorNode.in_trouble) is
handed to a thread of its own until its data flows again: the session
reconnects inside its reads, and a reconnection attempt (open, re-sync,
restart) blocks for as long as the sensor takes to answer, which must not
delay the others. The session's driving calls are for one thread at a time:
a node is read by the shared reader or by its own thread, never both.
"""

from __future__ import annotations

import logging
import threading
import time
from typing import List

from .node import READ_ENDED, SensorNode

log = logging.getLogger("leptrino.bridge")


class SharedReader:
    """The reading thread of the nodes add()ed (before or after start());
    stop() it before the nodes' own stop()."""

    def __init__(self, latency_s: float) -> None:
        if not latency_s > 0:
            raise ValueError(f"latency {latency_s}: a shared reader needs a latency budget > 0")
        self.period = float(latency_s)
        self._nodes: List[SensorNode] = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="bridge-reader", daemon=True)

    def add(self, node: SensorNode) -> None:
        """Read node from now on (its stream started)."""
        self._nodes = [*self._nodes, node]  # a new list: the thread iterates the old one

    def start(self) -> None:
        self._thread.start()

    @property
    def alive(self) -> bool:
        return self._thread.is_alive()

    def stop(self, timeout: float = 5.0) -> None:
        """End the thread and wait for it (the nodes' own threads are theirs)."""
        self._stop.set()
        if self._thread.ident is not None:
            self._thread.join(timeout)

    def _run(self) -> None:
        stop, period = self._stop, self.period
        wake = time.monotonic()
        while not stop.is_set():
            wake += period
            now = time.monotonic()
            if wake > now + 0.05:
                stop.wait(wake - now)  # a long budget: see stop() at once
            elif wake > now:
                time.sleep(wake - now)
            else:
                wake = now  # behind (a stall): no burst of passes to catch up
            for node in self._nodes:
                if node._solo or node._ended or node._stop.is_set():
                    continue
                try:
                    n = node.read_pass(0)
                    if n == READ_ENDED:
                        node._ended = True
                    elif n == 0 and node.in_trouble:
                        node.read_alone()
                except Exception:  # one sensor's failure ends its reading, not the others'
                    node._ended = True
                    log.exception("%s: reading stopped", node.spec.name)
