"""Plain value types returned by the bindings (no references into C memory)."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any, NamedTuple, Optional, Tuple

import numpy as np

from . import _constants as K

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


@dataclass(frozen=True)
class Sample:
    """One sample: host time, SI values (offset by the tare, if any), raw counts, status."""

    t: float  # host arrival time, seconds of the monotonic clock
    force: Vec3  # Fx, Fy, Fz [N]
    torque: Vec3  # Mx, My, Mz [N·m]
    raw: Raw6  # counts: ±10000 = ± rated
    status: int  # status byte (LEP_STATUS_* bits)
    calibration_error: bool  # status bit 0: calibration data in ROM corrupt
    sensor_fault: bool  # status bit 1
    overload: bool  # status bit 2: load beyond rating detected
    seq: int  # the two reserved bytes; leptrino-sim puts a sequence number here

    @property
    def si(self) -> Tuple[float, float, float, float, float, float]:
        f, m = self.force, self.torque
        return (f[0], f[1], f[2], m[0], m[1], m[2])

    @property
    def ok(self) -> bool:
        """No status bit set."""
        return self.status & 0x07 == 0


def make_sample(t: float, si: Any, raw: Any, status: int, seq: int) -> Sample:
    return Sample(
        t=float(t),
        force=(float(si[0]), float(si[1]), float(si[2])),
        torque=(float(si[3]), float(si[4]), float(si[5])),
        raw=tuple(int(v) for v in raw),  # type: ignore[arg-type]
        status=int(status),
        calibration_error=bool(status & K.LEP_STATUS_CALIBRATION),
        sensor_fault=bool(status & K.LEP_STATUS_SENSOR_FAULT),
        overload=bool(status & K.LEP_STATUS_OVERLOAD),
        seq=int(seq),
    )


@dataclass
class Recording:
    """Samples recorded in one batch call, as numpy arrays of equal length n."""

    t: np.ndarray  # (n,) float64, host arrival time [s], monotonic clock
    si: np.ndarray  # (n, 6) float64, Fx Fy Fz [N], Mx My Mz [N·m] (tare applied)
    raw: np.ndarray  # (n, 6) int16 counts
    status: np.ndarray  # (n,) uint8 status bits
    seq: np.ndarray  # (n,) uint16 reserved bytes (leptrino-sim's sequence number)

    def __len__(self) -> int:
        return int(self.t.shape[0])

    @property
    def force(self) -> np.ndarray:
        return self.si[:, :3]

    @property
    def torque(self) -> np.ndarray:
        return self.si[:, 3:]

    @property
    def elapsed(self) -> np.ndarray:
        """Seconds since the first sample."""
        return self.t - self.t[0] if len(self) else self.t.copy()

    @property
    def overload(self) -> np.ndarray:
        return np.asarray((self.status & K.LEP_STATUS_OVERLOAD) != 0, dtype=bool)

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


@dataclass(frozen=True)
class ClientStats:
    """Client counters (lep_client_stats)."""

    messages: int
    bcc_errors: int
    frame_errors: int
    bytes_discarded: int
    naks: int
    retries: int
    unexpected: int
    invalid: int
    timeouts: int
    samples: int


@dataclass(frozen=True)
class SimStats:
    """What the virtual sensor did (lep_sim_stats)."""

    samples_sent: int
    samples_dropped: int
    commands: int
    naks: int
    bytes_corrupted: int
    hangups: int
    streaming: bool
    filter: int
    filter_pending: int
    hung_up: bool
    sequence: int  # sequence number the next stream sample will carry
    responses: int
    faked_naks: int
    samples_skipped: int
    samples_blocked: int
    garbage_bytes: int
    bytes_received: int
    reopens: int
    power_cycles: int
    stalls: int


@dataclass(frozen=True)
class PortInfo:
    """A serial port found on this machine."""

    path: str
    by_id: str  # /dev/serial/by-id/... or ""
    description: str
    vid: int  # USB vendor id, 0 if unknown
    pid: int
    likely_sensor: bool  # STM VCP 0483:5740 or FTDI 0403:6001


def copy_fields(cls: Any, c: Any) -> Any:
    """Build the dataclass cls from the same-named fields of a C struct."""
    return cls(**{f.name: getattr(c, f.name) for f in fields(cls)})
