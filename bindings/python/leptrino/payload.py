"""A tool on the sensor: leptrino.Payload and leptrino.identify_payload.

The model and the identification are the library's (leptrino/payload.h):
with g the gravity vector in the sensor frame (m/s², (0, 0, -9.80665) when the
sensor's z axis points up), the sensor reads F = m·g + F_b and
M = c × (m·g) + M_b. Nothing is computed here; this module converts arrays.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterator, Optional, Sequence, Tuple, cast

import numpy as np

from . import _args as A
from . import _constants as K
from ._backend import get_backend

Vec3 = Tuple[float, float, float]
Vec6 = Tuple[float, float, float, float, float, float]


@dataclass(frozen=True)
class Payload:
    """A payload: mass (kg) and centre of mass (m, sensor frame); from an
    identification also the sensor's biases (N, N·m), the residual (per axis,
    RMS over the poses of measured - model, N and N·m), the spread of the
    poses' gravity vectors (payload.h) and the number of poses.

    Iterating gives (mass, cx, cy, cz): Simulator(payload=p) takes it, and
    str(p.argument) is the --payload / --sim-payload argument."""

    mass: float
    com: Vec3
    force_bias: Vec3 = (0.0, 0.0, 0.0)
    torque_bias: Vec3 = (0.0, 0.0, 0.0)
    residual: Vec6 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    spread: float = 0.0
    poses: int = 0

    def __iter__(self) -> Iterator[float]:
        yield float(self.mass)
        yield from (float(c) for c in self.com)

    @property
    def argument(self) -> str:
        """"M,CX,CY,CZ", as `leptrino stream --payload` and `--sim-payload` take it."""
        return ",".join(repr(v) for v in self)

    def wrench(self, gravity: Sequence[float], backend: Optional[str] = None) -> Vec6:
        """The gravity wrench (fx, fy, fz, mx, my, mz) of this payload at
        gravity (sensor frame), N and N·m: lep_payload_wrench. ValueError for
        a negative mass or non-finite values."""
        be = get_backend(backend)
        p = be.doubles(4)
        for i, v in enumerate(_payload4(self)):
            p[i] = v
        g = be.doubles(3)
        gv = _vector(gravity, 3, "gravity")
        for i in range(3):
            g[i] = float(gv[i])
        w = be.doubles(6)
        rc = be.lib.lep_payload_wrench(p, g, w)
        if rc < 0:
            raise ValueError(f"payload {self.argument} at gravity {tuple(gv)}: "
                             "not finite, or a negative mass")
        return cast(Vec6, tuple(float(w[i]) for i in range(6)))


def _vector(v: Any, n: int, what: str) -> Any:
    a = A.array_of("Payload", what, v, f"{n} numbers")
    if a.shape != (n,):
        raise ValueError(f"{what}: expected {n} numbers, got shape {a.shape}")
    return a


def _payload4(p: Payload) -> Tuple[float, float, float, float]:
    """(mass, cx, cy, cz): the four doubles of a payload (payload.h)."""
    com = _vector(p.com, 3, "com")
    return (float(p.mass), float(com[0]), float(com[1]), float(com[2]))


def identify_payload(gravity: Any, wrenches: Any, backend: Optional[str] = None) -> Payload:
    """Identify a payload and the sensor's biases from N >= 3 static poses.

    gravity: N×3 (m/s², sensor frame, one row per pose); wrenches: N×6, the
    mean wrench measured at each pose (fx, fy, fz in N, mx, my, mz in N·m, not
    tared). Linear least squares in C (lep_payload_identify; Kubus, Kröger and
    Wahl, 2008). TypeError for values that are not numbers (strings, bools,
    None); ValueError with the library's message for arrays of the wrong
    shape, NaN or infinite values, or poses that do not determine the
    payload (fewer than 3, gravity in too few distinct directions, a mass
    found not positive): a degenerate set is refused, never answered."""
    be = get_backend(backend)
    # the kind first (leptrino/_args.py: strings, bools, None are TypeError), then the shape
    g = np.ascontiguousarray(A.array_of("identify_payload", "gravity", gravity,
                                        "an N×3 array of numbers (m/s²)"))
    w = np.ascontiguousarray(A.array_of("identify_payload", "wrenches", wrenches,
                                        "an N×6 array of numbers (N, N·m)"))
    if g.ndim != 2 or g.shape[1] != 3:
        raise ValueError(f"gravity: expected an N×3 array, got shape {g.shape}")
    if w.ndim != 2 or w.shape[1] != 6:
        raise ValueError(f"wrenches: expected an N×6 array, got shape {w.shape}")
    if g.shape[0] != w.shape[0]:
        raise ValueError(f"gravity has {g.shape[0]} poses, wrenches {w.shape[0]}")
    fit = be.doubles(K.LEP_FIT_COUNT)
    err = be.new_text(256)
    rc = be.lib.lep_payload_identify(be.array_ptr(g, "double"), be.array_ptr(w, "double"),
                                     g.shape[0], fit, K.LEP_FIT_COUNT, err, 256)
    if rc < 0:
        what = "bad input" if rc == K.LEP_E_ARG else "degenerate poses"
        raise ValueError(be.text(err) or what)
    f = [float(fit[i]) for i in range(K.LEP_FIT_COUNT)]

    def at(i: int, n: int) -> Any:
        return tuple(f[i:i + n])

    return Payload(
        mass=f[K.LEP_FIT_PAYLOAD],
        com=at(K.LEP_FIT_PAYLOAD + 1, 3),
        force_bias=at(K.LEP_FIT_FORCE_BIAS_N, 3),
        torque_bias=at(K.LEP_FIT_TORQUE_BIAS_NM, 3),
        residual=at(K.LEP_FIT_RESIDUAL, 6),
        spread=f[K.LEP_FIT_SPREAD],
        poses=int(f[K.LEP_FIT_POSES]),
    )


def read_pose(path: str, backend: Optional[str] = None) -> Tuple[Vec6, int]:
    """The mean wrench of a pose recorded with `leptrino stream` (CSV), in the
    sensor frame and untared, and how many samples it averages
    (lep_payload_pose_read). ValueError / FileNotFoundError / OSError with the
    library's message naming the file."""
    be = get_backend(backend)
    mean = be.doubles(6)
    n = be.new_scalar("uint64_t")
    err = be.new_text(512)
    rc = be.lib.lep_payload_pose_read(str(path).encode(), mean, n, err, 512)
    if rc < 0:
        msg = be.text(err) or str(path)
        if rc == K.LEP_E_NOT_FOUND:
            raise FileNotFoundError(msg)
        if rc == K.LEP_E_IO:
            raise OSError(msg)
        raise ValueError(msg)
    return cast(Vec6, tuple(float(mean[i]) for i in range(6))), int(be.value(n))


def parse_limits(text: str, *more: str, backend: Optional[str] = None) -> Vec6:
    """Limits from `--limit` texts ("fz=50,mz=2": AXIS=VALUE pairs, AXIS one
    of fx fy fz mx my mz, VALUE > 0 in N or N·m) as six numbers (fx..mz, 0 =
    none) for Sensor.set_limits. Several texts (a repeated --limit) merge by
    the library's one rule (lep_limits_add, as `leptrino stream --limit`):
    the axes add up, and an axis limited twice is refused. ValueError when a
    text is malformed or an axis is limited twice."""
    texts = (text, *more)
    for t in texts:
        if not isinstance(t, str):
            raise TypeError(f"limits: {t!r} is not text")
    be = get_backend(backend)
    out = be.doubles(K.LEP_AXES)
    for t in texts:
        if "\x00" in t or be.lib.lep_limits_add(t.encode(), out) < 0:
            raise ValueError(f"limits {t!r}: expected AXIS=VALUE,... with AXIS one of fx, fy, "
                             "fz, mx, my, mz, each limited once over every text, and VALUE > 0 "
                             "(N, N·m)")
    return cast(Vec6, tuple(float(out[i]) for i in range(K.LEP_AXES)))
