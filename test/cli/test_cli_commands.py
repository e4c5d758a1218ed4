"""`leptrino list / info / read / filter`, and errors about the port."""

from __future__ import annotations

import subprocess
import time

from conftest import SimProcess, cli_path, parse_csv, parse_jsonl, run
from fake_sensor import FakeSensor


def info_fields(text: str) -> dict[str, str]:
    fields = {}
    for line in text.splitlines():
        key, _, value = line.partition(":")
        fields[key.strip()] = value.strip()
    return fields


def test_info_sim_default_model() -> None:
    r = run(["info", "--sim"])
    assert r.returncode == 0, r.stderr
    f = info_fields(r.stdout)
    assert f["model"] == "PFS055YA501U6"
    assert f["serial"] == "00000001"
    assert f["firmware"] == "1.13"
    assert f["output rate"] == "not reported"
    assert "32-byte" in f["protocol"]
    assert f["rated"].startswith("Fx 500 N,") and "N m" in f["rated"]
    assert f["filter"] == "0 (off)"
    # the port's latency settings (a pty: no low-latency flag, not an FTDI adapter)
    assert f["latency"] == "low-latency flag not set"


def test_info_sim_options() -> None:
    r = run(["info", "--sim", "--sim-model", "CFS034CA301U", "--sim-output-rate-field",
             "--sim-filter", "2", "--sim-serial", "12345678"])
    assert r.returncode == 0, r.stderr
    f = info_fields(r.stdout)
    assert f["model"] == "CFS034CA301U"
    assert f["serial"] == "12345678"
    assert f["output rate"].endswith("Hz")
    assert "38-byte" in f["protocol"]
    assert f["rated"].startswith("Fx 150 N,")
    assert f["filter"] == "2 (100 Hz)"


def test_read_n_samples() -> None:
    r = run(["read", "--sim", "-n", "5"])
    assert r.returncode == 0, r.stderr
    rows, _ = parse_csv(r.stdout)
    assert len(rows) == 5
    r = run(["read", "--sim", "--count", "3", "--format", "jsonl", "--units", "raw"])
    assert r.returncode == 0, r.stderr
    meta, recs, _ = parse_jsonl(r.stdout)
    assert len(meta) == 1 and meta[0]["model"] == "PFS055YA501U6"
    assert len(recs) == 3 and all(isinstance(rec["fx_counts"], int) for rec in recs)


def test_filter_set_power_cycle_get_round_trip() -> None:
    sim = SimProcess()
    try:
        r = run(["filter", sim.port])
        assert r.returncode == 0, r.stderr
        assert r.stdout.strip() == "filter: 0 (off)"
        r = run(["filter", sim.port, "2"])
        assert r.returncode == 0, r.stderr
        assert r.stdout.strip() == "filter set to 2 (100 Hz)"
        assert "power-cycled" in r.stderr
        assert sim.stats()["pending"] == 2
        assert sim.ask("power") == "ok"
        r = run(["filter", sim.port])
        assert r.returncode == 0, r.stderr
        assert r.stdout.strip() == "filter: 2 (100 Hz)"
        r = run(["filter", sim.port, "off"])
        assert r.returncode == 0, r.stderr
        assert sim.ask("power") == "ok"
        r = run(["filter", sim.port])
        assert r.stdout.strip() == "filter: 0 (off)"
    finally:
        sim.close()


def test_filter_with_sim_option() -> None:
    r = run(["filter", "--sim", "3"])
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "filter set to 3 (200 Hz)"


def test_list_runs() -> None:
    r = run(["list"])
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() != ""


def test_missing_port_exit_6_names_the_path() -> None:
    r = run(["info", "/dev/leptrino-no-such-port"])
    assert r.returncode == 6
    assert "/dev/leptrino-no-such-port" in r.stderr
    assert len(r.stderr.splitlines()) == 1


def test_not_a_tty_exit_6() -> None:
    r = run(["info", "/dev/null"])
    assert r.returncode == 6
    assert "/dev/null" in r.stderr


def test_virtual_sensor_that_cannot_start_exit_1() -> None:
    # A missing replay file is not "port not found" (6): an other failure, 1.
    r = run(["info", "--sim", "--sim-replay", "/nonexistent/leptrino-replay.csv"])
    assert r.returncode == 1, r.stderr
    assert "/nonexistent/leptrino-replay.csv" in r.stderr
    assert len(r.stderr.splitlines()) == 1


def test_busy_port_exit_7() -> None:
    sim = SimProcess()
    holder = subprocess.Popen([cli_path(), "stream", sim.port, "-o", "/dev/null"],
                              stdin=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 10
        while sim.stats()["streaming"] == 0 and time.monotonic() < deadline:
            time.sleep(0.05)
        r = run(["info", sim.port])
        assert r.returncode == 7, r.stderr
        assert sim.port in r.stderr
    finally:
        holder.terminate()
        holder.wait(timeout=10)
        sim.close()


def test_silent_port_times_out_exit_3() -> None:
    # A stalled virtual sensor answers nothing: exit code 3.
    r = run(["info", "--sim", "--sim-stall", "5000", "--timeout", "50"])
    assert r.returncode == 3, r.stderr
    assert "timed out" in r.stderr or "timeout" in r.stderr


def test_sensor_refusing_every_command_exit_5() -> None:
    # Every command NAKed past the retry limit: a sensor error, exit code 5.
    r = run(["info", "--sim", "--sim-nak", "1"])
    assert r.returncode == 5, r.stderr
    assert "NAK" in r.stderr
    assert len(r.stderr.splitlines()) == 1


def test_nak_faults_are_retried() -> None:
    r = run(["info", "--sim", "--sim-nak", "0.2", "--sim-seed", "7"])
    assert r.returncode == 0, r.stderr


def test_info_survives_a_refused_filter_query() -> None:
    sensor = FakeSensor(filter_result=0x02)
    try:
        r = run(["info", sensor.port])
    finally:
        sensor.close()
    assert r.returncode == 0, r.stderr
    f = info_fields(r.stdout)
    assert f["model"] == "PFS055YA501U6"
    assert f["serial"] == "00000042"
    assert f["rated"].startswith("Fx 500 N,")
    assert f["filter"] == "not supported by this sensor"
    assert 0xB6 in sensor.commands


def test_filter_query_refused_is_said_plainly() -> None:
    sensor = FakeSensor(filter_result=0x02)
    try:
        r = run(["filter", sensor.port])
    finally:
        sensor.close()
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "filter: not supported by this sensor"
