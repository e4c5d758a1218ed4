"""One argument policy (leptrino/_args.py), checked before any C call, in the
CLI's words: a value of the wrong kind is TypeError, out of range ValueError
(README: "Bad arguments and options are ValueError/TypeError"). Every public
method's bad values; the issue's cases first. Angles: degrees everywhere,
as `leptrino --rotate` and `leptrino-bridge --rotate` (degrees=False: radians)."""

from __future__ import annotations

import math
from typing import Any, Callable

import numpy as np
import pytest

import leptrino


@pytest.fixture
def sensor(sim: Any, backend: str) -> Any:
    with leptrino.Sensor(sim, backend=backend) as s:
        yield s


def _raises(exc: type, words: str, fn: Callable[[], Any]) -> None:
    with pytest.raises(exc) as e:
        fn()
    assert words in str(e.value), str(e.value)


def test_issue_cases(sensor: Any) -> None:
    sensor.tare_offsets = (1, 2, 3, 4, 5, 6)
    _raises(ValueError, "tare: n: 0 is out of range (1 .. 1000000)", lambda: sensor.tare(0))
    _raises(ValueError, "tare: n: -1 is out of range", lambda: sensor.tare(-1))
    assert sensor.tared  # nothing was un-tared by the bad calls
    _raises(TypeError, "tare: n: 1.5 is not a whole number", lambda: sensor.tare(1.5))
    _raises(ValueError, "tare: seconds: -1 is out of range", lambda: sensor.tare(seconds=-1))
    _raises(TypeError, "tare: wait: 0.3 is not True or False", lambda: sensor.tare(wait=0.3))
    _raises(ValueError, "rotation is not a rotation matrix",
            lambda: sensor.set_frame(np.diag([1, 1, 2])))
    assert sensor.tare_offsets == (1, 2, 3, 4, 5, 6)


def test_every_method(sensor: Any) -> None:
    cases = [
        (TypeError, "not a whole number", lambda: sensor.record(count=2.5)),
        (ValueError, "out of range", lambda: sensor.record(count=0)),
        (ValueError, "out of range", lambda: sensor.record(seconds=-1)),
        (ValueError, "not a number", lambda: sensor.record(seconds=math.nan)),
        (TypeError, "not a number", lambda: sensor.record(seconds="1")),
        (ValueError, "exactly one", lambda: sensor.record()),
        (TypeError, "not a whole number", lambda: sensor.stream(count="3")),
        (ValueError, "out of range", lambda: sensor.stream(count=-1)),
        (ValueError, "out of range", lambda: sensor.stream(seconds=0)),
        (ValueError, "out of range", lambda: setattr(sensor, "filter", 9)),
        (TypeError, "not a whole number", lambda: setattr(sensor, "filter", "1")),
        (TypeError, "not a whole number", lambda: sensor.filter_label(1.0)),
        (ValueError, "out of range", lambda: setattr(sensor, "lowpass", -1)),
        (ValueError, "out of range", lambda: setattr(sensor, "lowpass", 1000)),
        (TypeError, "not a number", lambda: setattr(sensor, "lowpass", None)),
        (ValueError, "six numbers", lambda: setattr(sensor, "tare_offsets", (1, 2))),
        (TypeError, "six numbers", lambda: setattr(sensor, "tare_offsets", "abcdef")),
        (ValueError, "not finite", lambda: setattr(sensor, "tare_offsets", [math.inf] * 6)),
        (ValueError, "rotation", lambda: sensor.set_frame((1.0, 2.0))),
        (TypeError, "rotation", lambda: sensor.set_frame("x")),
        (ValueError, "shift", lambda: sensor.set_frame(shift=(1, 2))),
        (TypeError, "degrees", lambda: sensor.set_frame((0, 0, 90), degrees=1)),
    ]
    before = sensor.metadata
    for exc, words, fn in cases:
        _raises(exc, words, fn)
    after = sensor.metadata
    for k in ("tared", "tare_counts", "rotation", "shift_m", "host_lowpass_hz"):
        assert before[k] == after[k], k  # nothing reached the session


def test_payload_gravity_limits(sensor: Any) -> None:
    # the methods of payload compensation and limits follow the same policy and words
    cases = [
        (ValueError, "set_payload: payload: 3 is not (mass kg, cx, cy, cz m)",
         lambda: sensor.set_payload(3)),
        (TypeError, "set_payload: payload", lambda: sensor.set_payload("1,0,0,0")),
        (TypeError, "set_payload: payload", lambda: sensor.set_payload((1, 0, 0, "a"))),
        (ValueError, "set_payload: payload", lambda: sensor.set_payload((1, 0, 0))),
        (ValueError, "not finite", lambda: sensor.set_payload((1, 0, 0, math.nan))),
        (ValueError, "set_payload: payload: the mass -1 kg is negative",
         lambda: sensor.set_payload((-1, 0, 0, 0))),
        (ValueError, "set_payload: payload: the mass -2 kg is negative",
         lambda: sensor.set_payload(leptrino.Payload(-2.0, (0.0, 0.0, 0.0)))),
        (ValueError, "set_gravity: gravity: (0, 0) is not (gx, gy, gz) in m/s²",
         lambda: sensor.set_gravity((0, 0))),
        (TypeError, "set_gravity: gravity", lambda: sensor.set_gravity("down")),
        (TypeError, "set_gravity: gravity", lambda: sensor.set_gravity((0, 0, None))),
        (ValueError, "not finite", lambda: sensor.set_gravity((0, 0, math.inf))),
        (TypeError, "set_limits: fz: 'a' is not a number", lambda: sensor.set_limits(fz="a")),
        (TypeError, "set_limits: fz: True is not a number", lambda: sensor.set_limits(fz=True)),
        (ValueError, "set_limits: fz: -1 is out of range", lambda: sensor.set_limits(fz=-1)),
        (ValueError, "set_limits: mz: nan is not a number",
         lambda: sensor.set_limits({"mz": math.nan})),
        (ValueError, "set_limits: unknown axis 'q'", lambda: sensor.set_limits(q=1)),
        (ValueError, "set_limits: limits", lambda: sensor.set_limits((1, 2))),
        (TypeError, "set_limits: limits", lambda: sensor.set_limits("fz=50")),
        (ValueError, "set_limits: fx: -5.0 is out of range",
         lambda: sensor.set_limits((-5, 0, 0, 0, 0, 0))),
    ]
    sensor.set_payload((0.5, 0.0, 0.0, 0.1))
    sensor.set_gravity((0.0, 9.80665, 0.0))
    sensor.set_limits(fz=50)
    before = sensor.metadata
    for exc, words, fn in cases:
        _raises(exc, words, fn)
    after = sensor.metadata
    for k in ("payload", "gravity", "limit"):
        assert before[k] == after[k], k  # nothing reached the session
    sensor.set_payload(leptrino.Payload(0.25, (0.0, 0.01, 0.0)))  # good values still go in
    sensor.set_limits((0, 0, 20, 0, 0, 1))
    assert sensor.metadata["payload"] == {"mass_kg": 0.25, "com_m": [0, 0.01, 0]}
    assert sensor.metadata["limit"] == [0, 0, 20, 0, 0, 1]


def test_identify_payload_kinds(backend: str) -> None:
    g = np.array([[0, 0, -9.8], [4.9, 0, -8.5], [0, 4.9, -8.5]])
    w = np.zeros((3, 6))
    cases = [
        (TypeError, "identify_payload: gravity: 'abc' is not an N×3 array of numbers",
         lambda: leptrino.identify_payload("abc", w, backend=backend)),
        (TypeError, "identify_payload: gravity", lambda: leptrino.identify_payload(
            [[None, 0, -9.8]] * 3, w, backend=backend)),
        (TypeError, "identify_payload: gravity", lambda: leptrino.identify_payload(
            True, w, backend=backend)),
        (TypeError, "identify_payload: wrenches", lambda: leptrino.identify_payload(
            g, [["x"] * 6] * 3, backend=backend)),
        (ValueError, "gravity: expected an N×3 array", lambda: leptrino.identify_payload(
            g[:, :2], w, backend=backend)),
        (TypeError, "Payload: gravity: 'down' is not 3 numbers",
         lambda: leptrino.Payload(1.0, (0.0, 0.0, 0.0)).wrench("down", backend=backend)),
    ]
    for exc, words, fn in cases:
        _raises(exc, words, fn)


def test_constructor(sim: Any, backend: str) -> None:
    bad = [
        (ValueError, "timeout", dict(timeout=0)),
        (TypeError, "retries", dict(retries=1.5)),
        (ValueError, "retries", dict(retries=300)),
        (ValueError, "decimate", dict(decimate=0)),
        (ValueError, "tare", dict(tare=-1)),
        (ValueError, "lowpass", dict(lowpass=-5)),
        (TypeError, "reconnect", dict(reconnect="yes")),
        (ValueError, "latency", dict(latency=-1)),
        (ValueError, "data_timeout", dict(data_timeout=math.inf)),
        (ValueError, "data_timeout: 0 is out of range (above 0", dict(data_timeout=0)),
        (ValueError, "gap_periods", dict(gap_periods=0.5)),
        (ValueError, "rotation is not a rotation matrix", dict(rotation=np.diag([1, 1, 2]))),
        (ValueError, "shift", dict(shift=(0, 0))),
    ]
    for exc, words, kw in bad:
        _raises(exc, words, lambda: leptrino.Sensor(sim, backend=backend, **kw))


def test_angles_are_degrees_like_the_cli(sensor: Any) -> None:
    sensor.set_frame((0, 0, 90))
    assert np.allclose(sensor.rotation, [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-12)
    sensor.set_frame((0, 0, math.pi / 2), degrees=False)
    assert np.allclose(sensor.rotation, [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-12)
    sensor.set_frame()
    assert np.allclose(sensor.rotation, np.eye(3))


def test_bridge_rotate_is_degrees_to_the_sensor() -> None:
    from leptrino.bridge import cli

    assert cli._parse_rpy("0,0,90") == pytest.approx([0, 0, math.pi / 2])


def test_bridge_limits_add_up_and_an_axis_twice_is_refused(capsys: Any) -> None:
    from leptrino.bridge import cli

    p = cli.build_parser()
    assert cli._limits(p, []) is None
    assert cli._limits(p, ["fz=50", "mz=1"]) == (0, 0, 50, 0, 0, 1)  # neither lost
    for texts in (["fz=50", "fz=60"], ["fz=50,fz=60"], ["fz=0"]):
        with pytest.raises(SystemExit) as e:
            cli._limits(p, texts)
        assert e.value.code == 2
        assert "--limit" in capsys.readouterr().err


def test_parse_limits_merges_texts_by_the_librarys_rule() -> None:
    from leptrino.payload import parse_limits

    assert parse_limits("fz=50,mz=2") == (0, 0, 50, 0, 0, 2)
    assert parse_limits("fz=50", "mz=2", "fx=1") == (1, 0, 50, 0, 0, 2)
    for texts in (("fz=50", "fz=60"), ("fz=50", "mz=1,fz=60"), ("fz=50", "mz=x")):
        with pytest.raises(ValueError, match="limited once"):
            parse_limits(*texts)
    with pytest.raises(TypeError):
        parse_limits("fz=1", 5)  # type: ignore[arg-type]


def test_recordings_and_simulator(sensor: Any, sim: Any, tmp_path: Any) -> None:
    rec = sensor.record(count=5)
    cases = [
        (ValueError, "unknown column", lambda: rec.save(tmp_path / "a.csv", columns=["volts"])),
        (TypeError, "not a list of names", lambda: rec.save(tmp_path / "a.csv", columns="si")),
        (ValueError, "format", lambda: rec.save(tmp_path / "a.csv", format="xml")),
        (ValueError, "time", lambda: rec.save(tmp_path / "a.csv", time="tai")),
        (TypeError, "overwrite", lambda: rec.save(tmp_path / "a.csv", overwrite="yes")),
        (ValueError, ".csv, .jsonl or .npz", lambda: rec.save(tmp_path / "a.txt")),
        (ValueError, "out of range", lambda: sim.stall(-1)),
        (TypeError, "not a number", lambda: sim.stall("1")),
    ]
    for exc, words, fn in cases:
        _raises(exc, words, fn)
    assert not (tmp_path / "a.csv").exists()
    (tmp_path / "x.csv").write_text("hello\n")
    _raises(ValueError, "not a leptrino recording",
            lambda: leptrino.read_recording(tmp_path / "x.csv"))
