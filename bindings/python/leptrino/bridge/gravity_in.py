"""The gravity input of a sensor: `NAME/gravity` messages
(geometry_msgs/msg/Vector3Stamped, the vector in m/s² in the sensor frame)
from any transport, checked, then handed to the session
(Sensor.set_gravity: the compensation itself is the library's).

Every message is checked before it can change anything: a payload that is
not a Vector3Stamped in CDR (bad header, wrong length, bad string), a
vector with a NaN or an infinity, or a zero vector is refused: gravity
stays as it was, a counter goes up, and one log line says why (at most one
every ratelog.PERIOD_S per sensor, with how many were refused in between).
Thread-safe: the transports call receive() from their own threads.
"""

from __future__ import annotations

import math
import threading
from typing import Any, Dict, List, Tuple

from . import cdr
from .ratelog import RateLimitedLog

VECTOR3_STAMPED = "geometry_msgs/msg/Vector3Stamped"


def check_gravity(payload: bytes) -> Tuple[float, float, float]:
    """The vector of a Vector3Stamped gravity message; ValueError saying why
    it cannot be used (not a Vector3Stamped in CDR, not finite, zero)."""
    _sec, _nsec, _frame, v = cdr.decode_vector3_stamped(payload)
    if not all(math.isfinite(x) for x in v):
        raise ValueError(f"vector {v} is not finite")
    if v == (0.0, 0.0, 0.0):
        raise ValueError("vector is zero")
    return v


class GravityInput:
    """One sensor's gravity input; set(g) is Sensor.set_gravity."""

    def __init__(self, name: str, set_gravity: Any,
                 initial: Tuple[float, float, float]) -> None:
        self.name = name
        self._set = set_gravity
        self._lock = threading.Lock()
        self.gravity = initial
        self.accepted = 0
        self.refused = 0
        self.by_transport: Dict[str, int] = {}
        self.last_refusal = ""
        self._log = RateLimitedLog()

    def receive(self, payload: bytes, transport: str, refuse: str = "") -> bool:
        """One message from transport ("zenoh", "dds", "foxglove"): True when
        it set gravity, False when refused (never raises). refuse: a reason
        the transport already has to refuse it (a channel of another type)."""
        if refuse:
            self._refuse(f"{transport}: {refuse}")
            return False
        try:
            g = check_gravity(bytes(payload))
            with self._lock:
                self._set(g)  # ValueError when the library refuses it
                self.gravity = g
                self.accepted += 1
                self.by_transport[transport] = self.by_transport.get(transport, 0) + 1
            return True
        except Exception as e:  # whatever a message holds, the bridge goes on
            self._refuse(f"{transport}: {e}")
            return False

    def _refuse(self, why: str) -> None:
        with self._lock:
            self.refused += 1
            self.last_refusal = why
        self._log.warning("%s/gravity: message refused, gravity unchanged: %s", self.name, why)

    def values(self) -> List[Tuple[str, str]]:
        """Its diagnostics key/values."""
        with self._lock:
            g, acc, ref, last = self.gravity, self.accepted, self.refused, self.last_refusal
        return [("gravity", " ".join(f"{x:.6g}" for x in g)),
                ("gravity_updates", str(acc)),
                ("gravity_refused", str(ref)),
                ("gravity_last_refusal", last)]

