"""Plain value types returned by the bindings (no references into C memory)."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field, fields
from typing import Any, Dict, List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from . import _constants as K
# The counter structs' dataclasses are generated from the headers (_stats.py).
from ._stats import ClientStats as ClientStats
from ._stats import FrameStats as FrameStats
from ._stats import Health as Health
from ._stats import SimStats as SimStats

Vec3 = Tuple[float, float, float]
Raw6 = Tuple[int, int, int, int, int, int]


class Rated(NamedTuple):
    """Rated (full-scale) values: forces in N, moments in N·m."""

    fx: float
    fy: float
    fz: float
    mx: float
    my: float
    mz: float

    @property
    def force(self) -> Vec3:
        return (self.fx, self.fy, self.fz)

    @property
    def torque(self) -> Vec3:
        return (self.mx, self.my, self.mz)


@dataclass(frozen=True)
class ProductInfo:
    """Answer to the product-information command (0x2A)."""

    model: str
    serial: str
    firmware: str
    output_rate: str  # the ASCII field of the 38-byte form ("" in the 32-byte form)
    output_rate_hz: Optional[int]  # output_rate as a number, None when absent
    has_output_rate: bool  # True: 38-byte form; False: 32-byte v1.13 form

    @property
    def variant(self) -> str:
        return "38-byte with output rate" if self.has_output_rate else "v1.13 (32-byte)"


Six = Tuple[float, float, float, float, float, float]


class Sample:
    """One sample, as the session delivered it.

    t      arrival time, s of the monotonic clock (lep_monotonic_seconds)
    t_utc  the same instant on the wall clock, s since 1970-01-01 UTC
    si     Fx Fy Fz [N], Mx My Mz [N·m]: tare, low-pass, rotation applied
    raw    counts as received (±10000 = ± rated)
    zeroed raw minus the tare offsets, counts
    status the sensor's status bits (LEP_STATUS_*)
    flags  the session's flags (LEP_SF_*: gap before it, overload, taring, settling)
    seq    the two reserved bytes (leptrino-sim's sequence number)
    """

    __slots__ = ("t", "t_utc", "si", "raw", "zeroed", "status", "flags", "seq")

    def __init__(self, t: float, t_utc: float, si: Six, raw: Raw6, zeroed: Six, status: int,
                 flags: int, seq: int) -> None:
        self.t = t
        self.t_utc = t_utc
        self.si = si
        self.raw = raw
        self.zeroed = zeroed
        self.status = status
        self.flags = flags
        self.seq = seq

    @property
    def force(self) -> Vec3:
        return self.si[:3]

    @property
    def torque(self) -> Vec3:
        return self.si[3:]

    @property
    def calibration_error(self) -> bool:
        """Status bit 0: calibration data in ROM corrupt."""
        return bool(self.status & K.LEP_STATUS_CALIBRATION)

    @property
    def sensor_fault(self) -> bool:
        """Status bit 1."""
        return bool(self.status & K.LEP_STATUS_SENSOR_FAULT)

    @property
    def overload(self) -> bool:
        """Overload status bit, or an axis at saturation (the session's flag)."""
        return bool(self.flags & K.LEP_SF_OVERLOAD or self.status & K.LEP_STATUS_OVERLOAD)

    @property
    def gap(self) -> bool:
        """A gap (lost samples, a stall, a reconnect) lies just before this sample."""
        return bool(self.flags & K.LEP_SF_GAP)

    @property
    def taring(self) -> bool:
        """A tare was averaging this sample (its zeroed values use the old offsets)."""
        return bool(self.flags & K.LEP_SF_TARING)

    @property
    def ok(self) -> bool:
        """No status bit set."""
        return self.status & 0x07 == 0

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Sample):
            return NotImplemented
        return all(getattr(self, k) == getattr(other, k) for k in self.__slots__)

    def __repr__(self) -> str:
        return ("Sample(" + ", ".join(f"{k}={getattr(self, k)!r}" for k in self.__slots__)
                + ")")


#: LEP_EV_* value -> event name ("gap", "disconnected", ...): every event type
#: of session.h, its name lower-cased without the prefix.
EVENT_NAMES = {v: k[len("LEP_EV_"):].lower() for k, v in vars(K).items()
               if k.startswith("LEP_EV_")}


@dataclass(frozen=True)
class SessionEvent:
    """Something the session noticed beside the data (lep_session_next_event: the
    fields LEP_EVF_*)."""

    type: str  # gap, disconnected, reconnected, tare, overload_begin, overload_end,
    #            limit_exceeded, limit_cleared
    # index of the sample it applies to: the row of the recording / Stream it came with
    # (the library's LEP_EVF_ROW plus the rows read before), take_events(): the stream's
    # row (LEP_EVF_SAMPLE); 0 for one from before the stream (an untare while stopped)
    sample: int
    t: float  # monotonic s
    t_utc: float
    gap_from: float  # gap/reconnected: arrival of the last sample before (monotonic s)
    gap_to: float  # ... and of the first after
    lost: int  # gap: samples estimated lost
    error: int  # disconnected: LEP_E_DISCONNECTED or LEP_E_TIMEOUT
    axes: int  # overload: bit i = axis i saturated; limit_exceeded: bit i = axis i beyond
    status: int
    tare: Six  # tare: the offsets now in force, counts
    wrench: Six = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # limit_*: the sample's SI values (N, N·m)

    def as_dict(self) -> Dict[str, Any]:
        return {f.name: getattr(self, f.name) for f in fields(self)}


@dataclass
class Recording:
    """Samples of one session, as numpy arrays of equal length n, with the
    events that came with them and the session's metadata."""

    t: np.ndarray  # (n,) float64, arrival time [s], monotonic clock
    si: np.ndarray  # (n, 6) float64, Fx Fy Fz [N], Mx My Mz [N·m] (tare, filter, frame)
    raw: np.ndarray  # (n, 6) int16 counts as received
    status: np.ndarray  # (n,) uint8 status bits
    seq: np.ndarray  # (n,) uint16 reserved bytes (leptrino-sim's sequence number)
    t_utc: np.ndarray = field(default_factory=lambda: np.empty(0))  # (n,) s since 1970 UTC
    zeroed: np.ndarray = field(default_factory=lambda: np.empty((0, 6)))  # (n, 6) counts - tare
    flags: np.ndarray = field(default_factory=lambda: np.empty(0, np.uint8))  # (n,) LEP_SF_*
    events: List[SessionEvent] = field(default_factory=list)
    metadata_json: str = "{}"  # the session's metadata object, as the library wrote it
    start_mono: float = 0.0  # monotonic s when the stream started (origin of t_s in files)

    def __len__(self) -> int:
        return int(self.t.shape[0])

    @property
    def metadata(self) -> Dict[str, Any]:
        """Model, serial, firmware, rated values, filters, tare, frame, start
        time, library version (lep_session_info, LEP_INFO_METADATA_JSON)."""
        return dict(json.loads(self.metadata_json or "{}"))

    @property
    def force(self) -> np.ndarray:
        return self.si[:, :3]

    @property
    def torque(self) -> np.ndarray:
        return self.si[:, 3:]

    @property
    def elapsed(self) -> np.ndarray:
        """Seconds since the first sample."""
        return np.asarray(self.t - self.t[0] if len(self) else self.t.copy())

    @property
    def overload(self) -> np.ndarray:
        """Overload status bit, or an axis at saturation."""
        over = (self.status & K.LEP_STATUS_OVERLOAD) != 0
        if self.flags.shape == self.status.shape:
            over |= (self.flags & K.LEP_SF_OVERLOAD) != 0
        return np.asarray(over, dtype=bool)

    @property
    def gap(self) -> np.ndarray:
        """True where a gap lies just before the sample."""
        return np.asarray((self.flags & K.LEP_SF_GAP) != 0, dtype=bool)

    def missing(self) -> int:
        """Samples lost between the first and the last, counted from the
        sequence numbers (meaningful with leptrino-sim, which numbers them)."""
        if len(self) < 2:
            return 0
        steps = np.mod(np.diff(self.seq.astype(np.int64)), 65536)
        return int(np.sum(steps - 1))

    @property
    def rate_hz(self) -> float:
        """Mean sample rate over the recording (0 with fewer than 2 samples)."""
        n = len(self)
        if n < 2 or self.t[-1] <= self.t[0]:
            return 0.0
        return float((n - 1) / (self.t[-1] - self.t[0]))

    def cut(self, n: int) -> Recording:
        """The first n samples (and the events before them)."""
        return Recording(self.t[:n], self.si[:n], self.raw[:n], self.status[:n], self.seq[:n],
                         self.t_utc[:n], self.zeroed[:n], self.flags[:n],
                         [e for e in self.events if e.sample <= n], self.metadata_json,
                         self.start_mono)

    def save(self, path: Any, *, format: Optional[str] = None,
             columns: Sequence[str] = ("si", "status"), time: str = "rel",
             overwrite: bool = False, backend: Optional[str] = None) -> None:
        """Write the recording to path.

        .csv / .jsonl (or format="csv"/"jsonl"): the `leptrino` tool's format,
        written by the library's one writer (leptrino/output.h): the metadata
        line, the header, the rows and the events, byte for byte as the tool
        writes them. columns: any of "raw", "zeroed", "si", "status",
        "flags", "seq" (the file keeps the library's column order); time:
        "rel" (s since the stream started), "mono" or "utc". An existing file
        is refused unless overwrite.
        .npz (or format="npz"): every array, the events and the metadata
        (Recording.load reads it back)."""
        p = str(path)
        fmt = format or ("npz" if p.endswith(".npz") else "jsonl" if p.endswith(".jsonl")
                         else "csv" if p.endswith(".csv") else None)
        if fmt == "npz":
            if os.path.exists(p) and not overwrite:
                raise FileExistsError(f"{p}: already exists; not overwritten (choose another "
                                      "name, or overwrite=True)")
            save_npz(self, p)
            return
        if fmt not in ("csv", "jsonl"):
            raise ValueError(f"{p}: give a name ending in .csv, .jsonl or .npz, or format=")
        from .output import write_recording

        write_recording(self, p, format=fmt, columns=columns, time=time, overwrite=overwrite,
                        backend=backend)

    @classmethod
    def load(cls, path: Any) -> Recording:
        """Read a recording back: the .npz of save(), or the CSV / JSON lines
        of save() and `leptrino stream -o` (leptrino.read_recording reads
        them; columns the file lacks are zeros, or NaN for SI values)."""
        with open(str(path), "rb") as f:
            if not f.read(2) == b"PK":
                from .recording_file import recording_from_file

                return recording_from_file(str(path))
        with np.load(str(path), allow_pickle=False) as z:
            meta = str(z["metadata"])
            events = [SessionEvent(**{**e, "tare": tuple(e["tare"]),
                                      "wrench": tuple(e.get("wrench", (0.0,) * 6))})
                      for e in json.loads(str(z["events"]))]
            return cls(t=z["t"], si=z["si"], raw=z["raw"], status=z["status"], seq=z["seq"],
                       t_utc=z["t_utc"], zeroed=z["zeroed"], flags=z["flags"], events=events,
                       metadata_json=meta, start_mono=float(z["start_mono"]))


def save_npz(rec: Recording, path: str) -> None:
    with open(path, "wb") as f:
        np.savez(f, t=rec.t, t_utc=rec.t_utc, si=rec.si, raw=rec.raw, zeroed=rec.zeroed,
                 status=rec.status, flags=rec.flags, seq=rec.seq,
                 events=np.array(json.dumps([e.as_dict() for e in rec.events])),
                 metadata=np.array(rec.metadata_json), start_mono=np.array(rec.start_mono))


@dataclass(frozen=True)
class PortInfo:
    """A serial port found on this machine."""

    path: str
    by_id: str  # /dev/serial/by-id/... or ""
    description: str
    vid: int  # USB vendor id, 0 if unknown
    pid: int
    likely_sensor: bool  # STM VCP 0483:5740 or FTDI 0403:6001

