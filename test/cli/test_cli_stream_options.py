"""`leptrino stream` options on the session: columns, metadata header, time
bases, low-pass, decimation, output frame, latency, tare during the run by
signal, gaps, the rate summary, the replay of the tool's own raw recording."""

from __future__ import annotations

import signal
import subprocess
import time
from pathlib import Path

from conftest import (AXES, RAW, Csv, SimProcess, cli_path, parse_jsonl, run,
                      wait_rows_after)


def mean(values: list[float]) -> float:
    return sum(values) / len(values)


def test_metadata_header_says_what_the_recording_is() -> None:
    r = run(["stream", "--sim", "--count", "5", "--lowpass", "20", "--tare", "10"])
    assert r.returncode == 0, r.stderr
    csv = Csv(r.stdout)
    assert len(csv.metadata) == 1
    text = r.stdout
    for word in ("PFS055YA501U6", "00000001", "1.13"):
        assert word in text.splitlines()[0]
    # Units are in the header; every row has every column.
    assert csv.header == ["t_s", *AXES, "status"]
    assert len(csv.rows) == 5


def test_all_columns_in_order_and_flags_seq() -> None:
    r = run(["stream", "--sim", "--count", "50", "--columns", "seq,flags,status,si,zeroed,raw"])
    assert r.returncode == 0, r.stderr
    csv = Csv(r.stdout)
    # The writer's fixed order, whatever the order asked.
    assert csv.header[0] == "t_s" and csv.header[1:7] == list(RAW)
    assert csv.header[-3:] == ["status", "flags", "seq"]
    seq = csv.column("seq")
    assert all(b - a == 1 for a, b in zip(seq, seq[1:]))  # no sample lost


def test_time_bases() -> None:
    before_utc, before_mono = time.time(), time.monotonic()
    utc = run(["stream", "--sim", "--count", "20", "--time", "utc"])
    mono = run(["stream", "--sim", "--count", "20", "--time", "mono"])
    after_utc, after_mono = time.time(), time.monotonic()
    assert utc.returncode == 0 and mono.returncode == 0
    t_utc = Csv(utc.stdout).column("t_utc_s")
    t_mono = Csv(mono.stdout).column("t_mono_s")
    assert all(before_utc - 1 <= t <= after_utc + 1 for t in t_utc)
    assert all(before_mono - 1 <= t <= after_mono + 1 for t in t_mono)


def roughness(values: list[float]) -> float:
    return mean([abs(b - a) for a, b in zip(values, values[1:])])


def test_lowpass_smooths_and_decimate_thins() -> None:
    plain = run(["stream", "--sim", "--sim-noise", "0.05", "--count", "1200"])
    smooth = run(["stream", "--sim", "--sim-noise", "0.05", "--count", "1200",
                  "--lowpass", "10"])
    assert plain.returncode == 0 and smooth.returncode == 0, smooth.stderr
    assert roughness(Csv(smooth.stdout).column("fx_N")) < \
        0.3 * roughness(Csv(plain.stdout).column("fx_N"))
    dec = run(["stream", "--sim", "--count", "100", "--decimate", "4", "--columns", "si,seq"])
    assert dec.returncode == 0, dec.stderr
    seq = Csv(dec.stdout).column("seq")
    assert len(seq) == 100
    assert all(b - a == 4 for a, b in zip(seq, seq[1:]))


def constant(*extra: str) -> dict[str, float]:
    """Mean of each SI column for a constant load of 0.2 x rated on every axis
    (Fx = Fy = Fz = 100 N, Mx = My = 2 N m, Mz = 1.6 N m on PFS055YA501U6)."""
    r = run(["stream", "--sim", "--sim-constant", "--count", "50", *extra])
    assert r.returncode == 0, r.stderr
    csv = Csv(r.stdout)
    return {a: mean(csv.column(a)) for a in AXES}


def close(a: float, b: float) -> bool:
    return abs(a - b) < 1e-3 * max(1.0, abs(b))


def test_rotate_matrix_and_shift() -> None:
    base = constant()
    assert close(base["fx_N"], 100.0) and close(base["mz_Nm"], 1.6)
    yaw = constant("--rotate", "0,0,90")   # x' = -y, y' = x
    assert close(yaw["fx_N"], -100.0) and close(yaw["fy_N"], 100.0)
    assert close(yaw["mx_Nm"], -2.0) and close(yaw["fz_N"], 100.0)
    same = constant("--matrix", "0,-1,0,1,0,0,0,0,1")
    for a in AXES:
        assert close(same[a], yaw[a]), a
    shifted = constant("--shift", "0,0,0.1")  # m' = m - r x f
    assert close(shifted["mx_Nm"], 2.0 + 10.0)
    assert close(shifted["my_Nm"], 2.0 - 10.0)
    assert close(shifted["mz_Nm"], 1.6)


def test_recording_latency_budget_loses_nothing() -> None:
    r = run(["stream", "--sim", "--duration", "2", "--latency", "100", "--columns", "si,seq"])
    assert r.returncode == 0, r.stderr
    seq = Csv(r.stdout).column("seq")
    assert abs(len(seq) - 2400) < 100
    assert all(b - a == 1 for a, b in zip(seq, seq[1:]))


def test_tare_and_untare_during_the_run_by_signal(tmp_path: Path) -> None:
    out = tmp_path / "t.csv"
    proc = subprocess.Popen([cli_path(), "stream", "--sim", "--sim-constant", "--retare", "50",
                             "--columns", "zeroed,si", "-o", str(out)],
                            stdin=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    # each signal once the recording shows what came before it
    wait_rows_after(out, 0, 100, proc)  # loaded rows
    proc.send_signal(signal.SIGUSR1)
    wait_rows_after(out, 1, 700, proc)  # zeroed rows after the tare
    proc.send_signal(signal.SIGUSR2)
    wait_rows_after(out, 2, 100, proc)  # loaded again after the untare
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=20)
    assert proc.returncode == 0, err
    csv = Csv(out.read_text())
    tares = csv.events("tare")
    assert len(tares) == 2, csv.comments
    # Rows before the tare are loaded, between tare and untare zero, after loaded.
    fx = csv.column("fx_N")
    assert abs(fx[0] - 100.0) < 1.0 and abs(fx[-1] - 100.0) < 1.0
    assert min(abs(v) for v in fx) < 0.05
    zeroed_rows = [v for v in fx if abs(v) < 0.05]
    assert len(zeroed_rows) > 600  # about one second of them
    assert "stopped by signal" in err


def test_stall_shorter_than_data_timeout_is_a_marked_gap() -> None:
    r = run(["stream", "--sim", "--sim-stall", "300", "--sim-stall-after", "1",
             "--duration", "2.5", "--columns", "si,seq,flags"], timeout=60)
    assert r.returncode == 0, r.stderr
    csv = Csv(r.stdout)
    gaps = csv.events("gap")
    assert len(gaps) == 1, csv.comments
    lost = int(gaps[0]["lost"])
    assert 300 <= lost <= 420  # 300 ms at 1.2 kHz = 360 samples
    # The row after the gap carries the gap flag.
    flagged = [r for r in csv.rows if int(r["flags"]) & 1]
    assert len(flagged) == 1
    summary = [line for line in r.stderr.splitlines() if "samples in" in line]
    assert "1 gaps" in summary[0] and f"{lost} samples lost" in summary[0]


def test_summary_says_a_rate_shortfall_plainly() -> None:
    r = run(["stream", "--sim", "--sim-drop", "0.2", "--duration", "2"])
    assert r.returncode == 0, r.stderr
    assert "RATE SHORTFALL" in r.stderr and "nominal 1200 Hz" in r.stderr
    ok = run(["stream", "--sim", "--duration", "2"])
    assert "SHORTFALL" not in ok.stderr and "nominal 1200 Hz" in ok.stderr


def test_two_virtual_sensors_into_one_file_on_one_time_base(tmp_path: Path) -> None:
    out = tmp_path / "two.csv"
    r = run(["stream", "--sim", "--sim", "--sim-seed", "2", "--sim-model", "CFS018CA201U",
             "--duration", "2", "-o", str(out)])
    assert r.returncode == 0, r.stderr
    csv = Csv(out.read_text())
    assert len(csv.metadata) == 2
    assert "PFS055YA501U6" in str(csv.metadata[0]) and "CFS018CA201U" in str(csv.metadata[1])
    assert csv.header[:2] == ["t_s", "sensor"]
    by = {name: [row for row in csv.rows if row["sensor"] == name] for name in ("sim1", "sim2")}
    for rows in by.values():
        assert abs(len(rows) - 2400) < 120
        assert 0.0 <= rows[0]["t_s"] < 0.5 and rows[-1]["t_s"] < 2.5
    assert by["sim1"][5]["fx_N"] != by["sim2"][5]["fx_N"]  # other seed, other model
    assert len([line for line in r.stderr.splitlines() if "samples in" in line]) == 2


def test_split_one_file_per_sensor_jsonl(tmp_path: Path) -> None:
    pattern = str(tmp_path / "rec-{sensor}-{n}.jsonl")
    r = run(["stream", "--sim", "--sim", "--count", "100", "-f", "jsonl", "--split", pattern])
    assert r.returncode == 0, r.stderr
    for n in (1, 2):
        meta, rows, _ = parse_jsonl((tmp_path / f"rec-sim{n}-{n}.jsonl").read_text())
        assert len(meta) == 1 and len(rows) == 100
        assert "sensor" not in rows[0]


def test_several_virtual_sensors_send_different_data() -> None:
    r = run(["stream", "--sim", "--sim", "--count", "5", "--columns", "sensor,raw"])
    assert r.returncode == 0, r.stderr
    rows = Csv(r.stdout).rows
    first = {row["sensor"]: [row[a] for a in RAW] for row in reversed(rows)}
    assert first["sim1"] != first["sim2"]
    assert '"serial":"00000001"' in r.stdout and '"serial":"00000002"' in r.stdout


def test_split_refuses_before_creating_any_file(tmp_path: Path) -> None:
    kept = tmp_path / "rec-sim2.csv"
    kept.write_text("precious\n")
    r = run(["stream", "--sim", "--sim", "--duration", "0.3",
             "--split", str(tmp_path / "rec-{sensor}.csv")])
    assert r.returncode == 1
    assert "rec-sim2.csv: already exists" in r.stderr and "samples in" not in r.stderr
    assert kept.read_text() == "precious\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rec-sim2.csv"]  # no stray rec-sim1.csv


def test_replay_of_own_raw_recording_gives_the_same_counts(tmp_path: Path) -> None:
    rec = tmp_path / "rec.csv"
    r = run(["stream", "--sim", "--sim-seed", "5", "--count", "600", "--columns", "raw,seq",
             "-o", str(rec)])
    assert r.returncode == 0, r.stderr
    original = Csv(rec.read_text())
    seq = original.column("seq")
    assert all(b - a == 1 for a, b in zip(seq, seq[1:]))  # a recording with no loss
    r = run(["stream", "--sim", "--sim-replay", str(rec), "--count", "600", "--columns", "raw"])
    assert r.returncode == 0, r.stderr
    replayed = Csv(r.stdout)
    assert [[row[a] for a in RAW] for row in replayed.rows] == \
        [[row[a] for a in RAW] for row in original.rows]


def test_replay_of_own_raw_jsonl_recording_gives_the_same_counts(tmp_path: Path) -> None:
    rec = tmp_path / "rec.jsonl"
    r = run(["stream", "--sim", "--sim-seed", "6", "--count", "300", "--columns", "raw,status",
             "-f", "jsonl", "-o", str(rec)])
    assert r.returncode == 0, r.stderr
    _, original, _ = parse_jsonl(rec.read_text())
    r = run(["stream", "--sim", "--sim-replay", str(rec), "--count", "300", "--columns", "raw",
             "-f", "jsonl"])
    assert r.returncode == 0, r.stderr
    _, replayed, _ = parse_jsonl(r.stdout)
    assert [[row[a] for a in RAW] for row in replayed] == \
        [[row[a] for a in RAW] for row in original]


def test_replay_of_a_two_sensor_recording_takes_the_first_rows_sensor(tmp_path: Path) -> None:
    rec = tmp_path / "two.csv"
    r = run(["stream", "--sim", "--sim-seed", "8", "--sim", "--sim-seed", "9", "--count", "300",
             "--columns", "raw,status", "-o", str(rec)])
    assert r.returncode == 0, r.stderr
    rows = Csv(rec.read_text()).rows
    first = [row for row in rows if row["sensor"] == rows[0]["sensor"]]  # the first row's sensor
    assert len(first) == 300
    r = run(["stream", "--sim", "--sim-replay", str(rec), "--count", "300", "--columns", "raw"])
    assert r.returncode == 0, r.stderr
    assert [[row[a] for a in RAW] for row in Csv(r.stdout).rows] == \
        [[row[a] for a in RAW] for row in first]


def test_sim_option_ranges_come_from_the_simulator() -> None:
    # leptrino-sim accepts an amplitude up to 4 x rated: so does --sim-amplitude.
    r = run(["stream", "--sim", "--sim-amplitude", "3.5", "--count", "5"])
    assert r.returncode == 0, r.stderr
    help_text = run(["help", "sim"]).stdout
    for name in ("--sim-amplitude", "--sim-output-rate-field", "--sim-replay", "--sim-link"):
        assert name in help_text


def test_two_ports_and_a_virtual_sensor_split_by_name(tmp_path: Path) -> None:
    a, b = SimProcess(), SimProcess()
    try:
        pattern = str(tmp_path / "{sensor}.csv")
        r = run(["stream", a.port, b.port, "--sim", "--count", "200", "--split", pattern])
        assert r.returncode == 0, r.stderr
        # Ports are named by their path ('/' as '_', no leading '_'), virtual ones sim1...
        for name in (a.port, b.port, "sim1"):
            path = tmp_path / (name.strip("/").replace("/", "_") + ".csv")
            csv = Csv(path.read_text())
            assert len(csv.rows) == 200 and csv.header[0] == "t_s"
            assert f"leptrino: stream: {name}: 200 samples" in r.stderr
        # The sensors were left quiet.
        assert a.stats()["streaming"] == 0 and b.stats()["streaming"] == 0
    finally:
        a.close()
        b.close()


def test_data_timeout_ends_with_exit_3_and_keeps_the_rows(tmp_path: Path) -> None:
    out = tmp_path / "t.csv"
    r = run(["stream", "--sim", "--sim-stall", "4000", "--sim-stall-after", "0.5",
             "--data-timeout", "1", "-o", str(out)], timeout=60)
    assert r.returncode == 3, r.stderr
    # LEP_E_LOST, in words that name the option deciding it
    assert "no data for 1 s (--data-timeout 1): the stream is lost" in r.stderr
    csv = Csv(out.read_text())
    assert len(csv.rows) > 300
    assert [e["reason"] for e in csv.events("disconnected")] == ["no-data"], csv.comments


def test_stall_longer_than_data_timeout_with_reconnect_resumes(tmp_path: Path) -> None:
    out = tmp_path / "r.csv"
    r = run(["stream", "--sim", "--sim-stall", "1500", "--sim-stall-after", "0.5",
             "--data-timeout", "0.5", "--reconnect", "--duration", "3.5", "-o", str(out)],
            timeout=60)
    assert r.returncode == 0, r.stderr
    assert "no data" in r.stderr and "resumed" in r.stderr
    csv = Csv(out.read_text())
    gaps = csv.events("gap")
    assert len(gaps) == 1 and gaps[0]["reason"] == "no-data", csv.comments
    assert float(gaps[0]["to"]) - float(gaps[0]["from"]) > 1.0
