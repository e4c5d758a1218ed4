"""`leptrino payload`: the virtual sensor carrying a tool at four
orientations, recorded with `leptrino stream` the way a user would, then
identified; refusals and bad arguments."""

from __future__ import annotations

import json
import math
from pathlib import Path

from conftest import run

G0 = 9.80665
R = G0 / math.sqrt(2.0)
POSES = ((0.0, 0.0, -G0), (R, 0.0, -R), (0.0, -R, -R), (-0.6 * R, 0.5 * R, -0.9 * R))
TOOL = (0.9, -0.015, 0.025, 0.11)


def _g(g: tuple[float, float, float]) -> str:
    return ",".join(repr(v) for v in g)


def _record(tmp: Path, i: int, g: tuple[float, float, float], *extra: str) -> str:
    path = tmp / f"pose{i}.csv"
    r = run(["stream", "--sim", "--sim-amplitude", "0", "--sim-noise", "0.003",
             "--sim-payload", ",".join(map(str, TOOL)), "--sim-gravity", _g(g),
             "--count", "600", "-o", str(path), *extra])
    assert r.returncode == 0, r.stderr
    return f"{path}@{_g(g)}"


def test_identified_from_four_recorded_poses(tmp_path: Path) -> None:
    # a tare, a rotated output and raw columns: all brought back to the sensor frame
    args = [_record(tmp_path, 1, POSES[0], "--tare", "100"),
            _record(tmp_path, 2, POSES[1], "--rotate", "10,-20,30", "--shift", "0,0,0.1"),
            _record(tmp_path, 3, POSES[2], "--units", "raw"),
            _record(tmp_path, 4, POSES[3], "--lowpass", "50")]
    r = run(["payload", *args, "--json"])
    assert r.returncode == 0, r.stderr
    fit = json.loads(r.stdout)
    assert abs(fit["mass_kg"] - TOOL[0]) < 0.01 * TOOL[0]
    assert all(abs(c - t) < 0.002 for c, t in zip(fit["com_m"], TOOL[1:]))
    assert fit["poses"] == 4 and fit["samples"] == [600] * 4
    assert max(fit["residual"][:3]) < 0.1 and max(fit["residual"][3:]) < 0.005
    # the text form, with the argument for --payload that reproduces the numbers
    t = run(["payload", *args])
    assert t.returncode == 0, t.stderr
    lines = dict(line.split(":", 1) for line in t.stdout.splitlines())
    assert lines["use"].strip() == f"--payload {fit['payload_argument']}"
    assert lines["mass"].strip().endswith("kg") and "sensor frame" in lines["com"]
    m, cx, cy, cz = map(float, fit["payload_argument"].split(","))
    assert abs(m - fit["mass_kg"]) < 1e-6 * m and abs(cz - fit["com_m"][2]) < 1e-9


def test_degenerate_poses_refused(tmp_path: Path) -> None:
    up = _record(tmp_path, 1, POSES[0])
    path = up.split("@")[0]
    down = f"{path}@0,0,{G0}"
    r = run(["payload", up, up, down])
    assert r.returncode == 1 and r.stdout == ""
    assert "too few distinct directions" in r.stderr and r.stderr.count("\n") == 1


def test_bad_arguments(tmp_path: Path) -> None:
    r = run(["payload", "a.csv@0,0,-9.8", "b.csv@0,0"])
    assert r.returncode == 2 and "'b.csv@0,0' is not POSE.csv@GX,GY,GZ" in r.stderr
    r = run(["payload", "a.csv@0,0,-9.8", "b.csv@0,0,nan", "c.csv@1,2,3"])
    assert r.returncode == 2 and "b.csv@0,0,nan" in r.stderr
    r = run(["payload", "a.csv@0,0,-9.8"])
    assert r.returncode == 2 and "at least 3" in r.stderr
    r = run(["payload", "--bogus"])
    assert r.returncode == 2
    missing = tmp_path / "missing.csv"
    r = run(["payload", f"{missing}@0,0,-9.8", f"{missing}@0,9.8,0", f"{missing}@9.8,0,0"])
    assert r.returncode == 1 and "missing.csv" in r.stderr
    notrec = tmp_path / "plain.csv"
    notrec.write_text("fx,fy\n1,2\n")
    r = run(["payload", f"{notrec}@0,0,-9.8", f"{notrec}@0,9.8,0", f"{notrec}@9.8,0,0"])
    assert r.returncode == 1 and "plain.csv:1: no '# leptrino-metadata:'" in r.stderr
    r = run(["payload", "--help"])
    assert r.returncode == 0 and "Kubus" in r.stdout and "Exit codes" in r.stdout
