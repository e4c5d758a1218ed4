"""leptrino.identify_payload and Payload: the C identification through both
backends, against numpy's least squares, refusals, and the virtual sensor
carrying a payload (Simulator(payload=..., gravity=...)) identified."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import leptrino

G0 = 9.80665


def _model(mass: float, com: np.ndarray, fb: np.ndarray, mb: np.ndarray,
           g: np.ndarray) -> np.ndarray:
    f = mass * g
    return np.hstack([f + fb, np.cross(com, f) + mb])


def _reference(g: np.ndarray, w: np.ndarray) -> np.ndarray:
    """numpy's least squares of the 10-parameter linear model: m, F_b, m c, M_b."""
    rows, rhs = [], []
    for gi, wi in zip(g, w):
        gx, gy, gz = gi
        skew = np.array([[0, gz, -gy], [-gz, 0, gx], [gy, -gx, 0]])  # (p x g) = skew @ p
        a = np.zeros((6, 10))
        a[:3, 0] = gi
        a[:3, 1:4] = np.eye(3)
        a[3:, 4:7] = skew
        a[3:, 7:10] = np.eye(3)
        rows.append(a)
        rhs.append(wi)
    x, *_ = np.linalg.lstsq(np.vstack(rows), np.hstack(rhs), rcond=None)
    return x


def test_identify_matches_numpy_lstsq(backend: str) -> None:
    rng = np.random.default_rng(5)
    for _ in range(20):
        n = int(rng.integers(4, 12))
        g = rng.normal(size=(n, 3))
        g *= G0 / np.linalg.norm(g, axis=1, keepdims=True)
        mass, com = rng.uniform(0.3, 5.0), rng.normal(scale=0.1, size=3)
        fb, mb = rng.normal(scale=5, size=3), rng.normal(scale=0.3, size=3)
        w = np.array([_model(mass, com, fb, mb, gi) for gi in g])
        w[:, :3] += rng.normal(scale=0.05, size=(n, 3))
        w[:, 3:] += rng.normal(scale=0.001, size=(n, 3))
        p = leptrino.identify_payload(g, w, backend=backend)
        x = _reference(g, w)
        assert p.mass == pytest.approx(x[0], rel=1e-9)
        assert p.force_bias == pytest.approx(x[1:4], abs=1e-9)
        assert p.com == pytest.approx(x[4:7] / x[0], abs=1e-9)
        assert p.torque_bias == pytest.approx(x[7:10], abs=1e-9)
        assert p.poses == n and len(p.residual) == 6 and p.spread > 0
        if p.spread > 0.3:
            assert abs(p.mass - mass) < 0.01 * mass
            assert np.max(np.abs(np.array(p.com) - com)) < 0.002


def test_refusals_are_value_errors(backend: str) -> None:
    g = np.array([[0, 0, -G0]] * 5, dtype=float)
    w = np.zeros((5, 6))
    w[:, 2] = -G0
    with pytest.raises(ValueError, match="too few distinct directions"):
        leptrino.identify_payload(g, w, backend=backend)
    with pytest.raises(ValueError, match="at least 3"):
        leptrino.identify_payload(g[:2], w[:2], backend=backend)
    g = np.array([[0, 0, -G0], [G0, 0, 0], [0, G0, 0]])
    w = np.array([_model(1.0, np.zeros(3), np.zeros(3), np.zeros(3), gi) for gi in g])
    w[1, 4] = math.nan
    with pytest.raises(ValueError, match="pose 2: wrench my is nan"):
        leptrino.identify_payload(g, w, backend=backend)
    with pytest.raises(ValueError, match="N×6"):
        leptrino.identify_payload(g, w[:, :5], backend=backend)
    with pytest.raises(ValueError, match="N×3"):
        leptrino.identify_payload(g[:, :2], w, backend=backend)
    with pytest.raises(ValueError, match="3 poses, wrenches 2"):
        leptrino.identify_payload(g, w[:2], backend=backend)


def test_payload_wrench_and_argument(backend: str) -> None:
    p = leptrino.Payload(mass=2.0, com=(0.1, 0.0, 0.05))
    w = p.wrench((0.0, 0.0, -G0), backend=backend)
    assert w == pytest.approx((0, 0, -2 * G0, 0, 0.2 * G0, 0))
    assert p.argument == "2.0,0.1,0.0,0.05" and list(p) == [2.0, 0.1, 0.0, 0.05]
    with pytest.raises(ValueError):
        leptrino.Payload(mass=-1.0, com=(0, 0, 0)).wrench((0, 0, -G0), backend=backend)


def test_virtual_sensor_carrying_a_payload(backend: str, tmp_path: Path) -> None:
    """Four orientations of the virtual sensor with a tool, recorded and
    identified; the option takes a tuple or a Payload, and the table's text."""
    truth = leptrino.Payload(mass=0.8, com=(-0.01, 0.02, 0.06))
    r = G0 / math.sqrt(2)
    poses = np.array([[0, 0, -G0], [r, 0, -r], [0, -r, -r], [-0.6 * r, 0.5 * r, -0.9 * r]])
    means = []
    for i, g in enumerate(poses):
        payload = truth if i % 2 == 0 else tuple(truth)
        opts = dict(amplitude=0.0, noise=0.002, payload=payload, gravity=tuple(g))
        with leptrino.Sensor(sim=opts, backend=backend) as s:
            rec = s.record(count=600)
        if i == 3:  # through a recording made the tool's way, read back by the C reader
            path = tmp_path / "pose.csv"
            rec.save(str(path))
            mean, n = leptrino.read_pose(str(path), backend=backend)
            assert n == 600
            assert mean == pytest.approx(rec.si.mean(axis=0), abs=1e-5)
        means.append(rec.si.mean(axis=0))
    fit = leptrino.identify_payload(poses, np.array(means), backend=backend)
    assert abs(fit.mass - truth.mass) < 0.01 * truth.mass
    assert np.max(np.abs(np.array(fit.com) - np.array(truth.com))) < 0.002


def test_sensor_compensates_and_limits(backend: str) -> None:
    """Sensor.set_payload / set_gravity / set_limits: the C session's
    compensation (raw counts keep the tool) and limit events in Python."""
    g = (0.0, 0.0, -G0)
    tool = leptrino.Payload(mass=1.5, com=(0.0, 0.02, 0.05))
    sim = dict(amplitude=0.0, noise=0.0, payload=tool, gravity=g,
               overload_every=0.3, overload_duration=0.05)
    with leptrino.Sensor(sim=sim, backend=backend) as s:
        rec = s.record(count=200)
        assert rec.si[:, 2].mean() == pytest.approx(-1.5 * G0, abs=0.03)
        s.set_payload(tool)
        s.set_gravity(g)
        s.set_limits(fx=100, fy=100)
        rec = s.record(count=1200)
        calm = (rec.flags & 2) == 0  # not in an overload episode
        assert np.abs(rec.si[calm, :3]).max() < 0.03 and np.abs(rec.si[calm, 3:]).max() < 0.001
        assert rec.raw[calm, 2].mean() == pytest.approx(-1.5 * G0 / 500 * 10000, abs=1)
        meta = rec.metadata
        assert meta["payload"]["mass_kg"] == 1.5 and meta["gravity"] == [0, 0, -G0]
        assert meta["limit"] == [100, 100, 0, 0, 0, 0]
        kinds = [e.type for e in rec.events]
        assert "limit_exceeded" in kinds and "limit_cleared" in kinds
        ev = next(e for e in rec.events if e.type == "limit_exceeded")
        assert ev.axes in (1, 2) and max(abs(v) for v in ev.wrench[:2]) > 100
        assert rec.flags[ev.sample] & 16
        # refusals
        with pytest.raises(ValueError):
            s.set_payload((-1.0, 0, 0, 0))
        with pytest.raises(ValueError):
            s.set_gravity((0, math.nan, 0))
        with pytest.raises(ValueError):
            s.set_limits(fq=1)
        with pytest.raises(ValueError):
            s.set_limits(fz=-1)
        s.set_payload(None)
        s.set_limits(None)
        assert s.metadata["payload"] is None and s.metadata["limit"] == [0] * 6


def test_tare_with_payload_keeps_the_tool(backend: str) -> None:
    g1, g2 = np.array([0.0, 0.0, -G0]), np.array([G0, 0.0, 0.0])
    tool = leptrino.Payload(mass=0.7, com=(0.01, 0.0, 0.04))
    sim = dict(amplitude=0.005, constant=True, payload=tool, gravity=tuple(g1))
    with leptrino.Sensor(sim=sim, backend=backend) as s:
        s.set_payload(tool)
        s.set_gravity(g1)
        s.tare(100)
        assert s.tare_offsets == pytest.approx((50,) * 6, abs=0.5)  # the bias alone
        s.set_gravity(g2)  # the robot turned
        rec = s.record(count=100)
        want = np.array(tool.wrench(g1, backend=backend)) - np.array(tool.wrench(g2, backend=backend))
        assert rec.si[-1] == pytest.approx(want, abs=1e-9)
