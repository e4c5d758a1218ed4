"""`leptrino check` (commissioning) and `leptrino stream` with --payload,
--gravity, --limit and --stop-on-limit, tried as a user would."""

from __future__ import annotations

import json
import signal
import subprocess
from pathlib import Path

import pytest
from conftest import Csv, cli_path, run, wait_catching

CHECK_CODES = {"status": 10, "errors": 11, "loss": 12, "rate": 13, "overload": 14, "noise": 15}


def _check(*args: str) -> tuple[int, dict, str]:
    # a loaded machine may deliver late: the rate is judged loosely unless it is the point
    rate = [] if "--min-rate" in args else ["--min-rate", "90"]
    r = run(["check", "--sim", "--duration", "1.5", "--json", *rate, *args])
    return r.returncode, json.loads(r.stdout), r.stderr


def test_check_passes_a_healthy_virtual_sensor() -> None:
    r = run(["check", "--sim"])  # the defaults: 3 s
    assert r.returncode == 0, r.stdout + r.stderr
    assert "result:       PASS" in r.stdout and r.stderr == ""
    for name in CHECK_CODES:
        assert f"PASS {name}" in r.stdout
    assert "model:        PFS055YA501U6" in r.stdout and "filter:       0 (off)" in r.stdout
    code, j, _ = _check()
    assert code == 0 and j["pass"] is True and j["failed"] is None and j["samples"] >= 1700
    assert [c["name"] for c in j["criteria"]] == list(CHECK_CODES)
    assert [c["exit_code"] for c in j["criteria"]] == list(CHECK_CODES.values())


def test_check_fails_the_right_criterion() -> None:
    code, j, err = _check("--sim-drop", "0.01")
    assert code == 12 and j["failed"] == "loss" and j["lost"] > 0, j
    assert "FAIL: loss" in err
    code, j, err = _check("--sim-corrupt", "0.01")
    assert code == 11 and j["failed"] == "errors" and j["errors"] > 0, j
    code, j, err = _check("--sim-overload-every", "0.5", "--sim-overload-duration", "0.1")
    assert code == 14 and j["failed"] == "overload" and j["overloads"] >= 2, j
    # the noise of the overloads is not taken for the sensor's
    assert next(c for c in j["criteria"] if c["name"] == "noise")["pass"] is True
    code, j, err = _check("--max-noise", "10")
    assert code == 15 and j["failed"] == "noise"
    code, j, err = _check("--min-rate", "101")
    assert code == 13 and j["failed"] == "rate"
    # tolerances let the same faults pass
    code, j, err = _check("--sim-drop", "0.01", "--max-loss", "1000")
    assert code == 0, j


def test_check_status_bits(tmp_path: Path) -> None:
    replay = tmp_path / "status.csv"
    replay.write_text("0,0,0,0,0,0,2\n1,0,0,0,0,0,0\n")
    code, j, err = _check("--sim-replay", str(replay))
    assert code == 10 and j["failed"] == "status" and j["status_bits"] & 2, j
    assert "sensor error" in err
    replay.write_text("0,0,0,0,0,0,1\n")
    code, j, err = _check("--sim-replay", str(replay))
    assert code == 10 and "ROM calibration data error" in err


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_check_interrupted_is_no_pass(sig: signal.Signals) -> None:
    # a script's `leptrino check PORT && ...` (or `timeout 5 leptrino check`) must not take
    # an interrupted check for a pass
    proc = subprocess.Popen([cli_path(), "check", "--sim", "--duration", "30"],
                            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    wait_catching(proc, sig)  # (before, the signal would kill it: no message to test)
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=20)
    assert proc.returncode == 1, (proc.returncode, out, err)
    assert "interrupted before the end of --duration: no verdict" in err, err
    assert "PASS" not in out


def test_check_usage() -> None:
    r = run(["check"])
    assert r.returncode == 2
    r = run(["check", "--sim", "--max-noise", "-1"])
    assert r.returncode == 2
    r = run(["check", "--help"])
    assert r.returncode == 0
    for code in range(10, 16):
        assert f"  {code} " in r.stdout


def test_stream_payload_compensated(tmp_path: Path) -> None:
    out = tmp_path / "c.csv"
    r = run(["stream", "--sim", "--sim-amplitude", "0", "--sim-noise", "0",
             "--sim-payload", "2,0.01,0,0.1", "--sim-gravity", "0,9.80665,0",
             "--payload", "2,0.01,0,0.1", "--gravity", "0,9.80665,0",
             "--columns", "raw,si", "--count", "50", "-o", str(out)])
    assert r.returncode == 0, r.stderr
    rec = Csv(out.read_text())
    meta = rec.metadata[0]
    assert meta["payload"] == {"mass_kg": 2, "com_m": [0.01, 0, 0.1]}
    assert meta["gravity"] == [0, 9.80665, 0]
    for row in rec.rows:
        assert row["fy_counts"] == 392  # the tool's 19.61 N as measured
        assert abs(row["fy_N"]) < 0.03 and abs(row["mx_Nm"]) < 0.001  # removed from SI


def test_stream_limits_and_stop_on_limit(tmp_path: Path) -> None:
    out = tmp_path / "l.csv"
    base = ["stream", "--sim", "--sim-amplitude", "0", "--sim-overload-every", "0.3",
            "--sim-overload-duration", "0.05", "--columns", "si,flags", "--limit", "fx=100,fy=100"]
    r = run([*base, "--duration", "1", "-o", str(out)])
    assert r.returncode == 0, r.stderr
    text = out.read_text()
    # episodes 1 and 2 drive fx and fy: two limit episodes, each cleared
    assert text.count("# limit exceeded") == 2 and text.count("# limit cleared") == 2
    assert "2 limit episodes" in r.stderr
    out2 = tmp_path / "s.csv"
    r = run([*base, "--stop-on-limit", "-o", str(out2)])
    assert r.returncode == 9, r.stderr
    assert "limit exceeded at t=" in r.stderr and "fx 1600 N beyond 100" in r.stderr
    rec = Csv(out2.read_text())
    last = rec.rows[-1]
    assert last["fx_N"] == 1600 and int(last["flags"]) & 16
    assert all(not int(row["flags"]) & 16 for row in rec.rows[:-1])
    r = run(["stream", "--sim", "--limit", "fz=0"])
    assert r.returncode == 2


def test_repeated_limits_add_up_and_an_axis_twice_is_refused(tmp_path: Path) -> None:
    out = tmp_path / "m.csv"
    r = run(["stream", "--sim", "--duration", "0.05", "--limit", "fz=50", "--limit", "mz=1",
             "-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert Csv(out.read_text()).metadata[0]["limit"] == [0, 0, 50, 0, 0, 1]  # neither lost
    for args in (["--limit", "fz=50", "--limit", "fz=60"], ["--limit", "fz=50,fz=60"]):
        r = run(["stream", "--sim", "--duration", "0.05", *args])
        assert r.returncode == 2, args
        assert "fz=" in r.stderr and "--limit" in r.stderr
    r = run(["stream", "--sim", "--payload", "-1,0,0,0"])
    assert r.returncode == 2 and "negative" in r.stderr
