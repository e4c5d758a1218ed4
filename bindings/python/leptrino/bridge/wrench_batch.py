"""A session's batches as WrenchStamped CDR messages, serialized in C.

lep_ros_wrench_cdr (include/leptrino/ros_cdr.h) writes the `wrench` and
`wrench_raw` messages of a whole batch into two numpy buffers in one call;
Python only slices the result into the payloads each transport takes. The
same bytes go to Zenoh, DDS, Foxglove and MCAP.
"""

from __future__ import annotations

from typing import Any, List, Sequence, Tuple

import numpy as np

from .. import _constants as K
from ..errors import LeptrinoError
from ..sensor import SampleBuffer

#: Samples per lep_session_read (a 2 ms latency budget brings 2-3 at 1.2 kHz;
#: a stalled reader catches up in batches of this many).
BATCH = 256


class WrenchBatch:
    """Session batch arrays and the CDR buffers of their messages.

    be: the backend (leptrino.get_backend()); rated: the sensor's six rated
    values (Sensor.rated: N, N·m; for wrench_raw); frame_id: header.frame_id. ValueError for a
    frame_id the C side refuses (a NUL, longer than LEP_ROS_FRAME_ID_MAX
    bytes). One per reading thread.
    """

    def __init__(self, be: Any, rated: Sequence[float], frame_id: str, cap: int = BATCH) -> None:
        fid = frame_id.encode("utf-8")
        if b"\x00" in fid or len(fid) > K.LEP_ROS_FRAME_ID_MAX:
            raise ValueError(f"frame_id {frame_id!r}: no NUL, at most "
                             f"{K.LEP_ROS_FRAME_ID_MAX} bytes")
        self._be = be
        self._fn = be.lib.lep_ros_wrench_cdr
        self._rated = be.doubles(6)
        for i, v in enumerate(rated):
            self._rated[i] = float(v)
        self._fid = fid
        self.cap = cap
        self.size = int(be.lib.lep_ros_wrench_size(len(fid)))
        self.arrays = SampleBuffer(be, cap)
        self._w = np.zeros(cap * self.size, np.uint8)
        self._r = np.zeros(cap * self.size, np.uint8)
        self._st = np.zeros(cap, np.int64)
        self._last = np.zeros(1, np.int64)
        self._pw = be.array_ptr(self._w, "uint8_t")
        self._pr = be.array_ptr(self._r, "uint8_t")
        self._pst = be.array_ptr(self._st, "int64_t")
        self._plast = be.array_ptr(self._last, "int64_t")
        # What encode() touches per batch, made once: each batch follows a
        # sleep in the session's read, so the code it runs starts cold
        # (docs/bridge.md, "Where the time goes"): plain memoryviews and
        # slices rather than numpy calls, the byte ranges precomputed.
        a = self.arrays
        self._pt = be.array_ptr(a.t_utc, "double")
        self._psi = be.array_ptr(a.si, "double")
        self._praw = be.array_ptr(a.raw, "int16_t")
        self._nbytes = cap * self.size
        self._mw, self._mr = self._w.data, self._r.data
        self._mst = self._st.data
        self._cuts = [(i * self.size, (i + 1) * self.size) for i in range(cap)]
        #: the arrays' t_mono as a memoryview (the last sample's time, per batch)
        self.t_mono = self.arrays.t_mono.data

    def encode(self, wrench: bool = True, wrench_raw: bool = True
               ) -> Tuple[List[bytes], List[bytes], List[int]]:
        """The arrays' samples [0, n) as (wrench payloads, wrench_raw
        payloads, stamps in ns); a topic not wanted gets an empty list (its
        bytes are written by the C call, not cut into payloads). Stamps never
        go back, across calls too. LeptrinoError for a time the message
        cannot hold."""
        n = self.arrays.n
        if n == 0:
            return [], [], []
        rc = self._fn(n, self._pt, self._psi, self._praw, self._rated, self._fid, self._plast,
                      self._pw, self._pr, self._nbytes, self._pst)
        if rc != 0:
            raise LeptrinoError(f"serializing WrenchStamped: error {int(rc)}", int(rc))
        end = n * self.size
        cuts = self._cuts[:n]
        w = r = b""
        if wrench:
            w = self._mw[:end].tobytes()
        if wrench_raw:
            r = self._mr[:end].tobytes()
        return ([w[i:j] for i, j in cuts] if wrench else [],
                [r[i:j] for i, j in cuts] if wrench_raw else [], self._mst[:n].tolist())
