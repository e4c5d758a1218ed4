"""`leptrino stream --sim`: output formats, sample counts, units, tare."""

from __future__ import annotations

import json
from pathlib import Path

from conftest import AXES, CSV_HEADER, RAW, ZEROED, Csv, parse_csv, parse_jsonl, run

RATE = 1200.0
DURATION = 5.0


def expect_count_near(n: int, duration: float, rate: float) -> None:
    expected = duration * rate
    assert abs(n - expected) <= 0.02 * expected, (n, expected)


def test_csv_well_formed_and_count_matches_duration(tmp_path: Path) -> None:
    out = tmp_path / "f.csv"
    r = run(["stream", "--sim", "--duration", str(DURATION), "-o", str(out)])
    assert r.returncode == 0, r.stderr
    text = out.read_text()
    assert text.splitlines()[0].startswith("# leptrino-metadata: {")
    assert text.splitlines()[1] == CSV_HEADER
    rows, comments = parse_csv(text)
    assert comments == []
    expect_count_near(len(rows), DURATION, RATE)
    ts = [row[0] for row in rows]
    assert all(0.0 <= t < DURATION + 0.1 for t in ts)
    assert ts == sorted(ts)
    # The summary line is always printed on stderr (not a terminal here).
    summary = [line for line in r.stderr.splitlines() if "samples in" in line]
    assert len(summary) == 1 and f"{len(rows)} samples" in summary[0]
    assert "\r" not in r.stderr  # no live status line when stderr is not a tty


def test_jsonl_well_formed_and_count_matches_duration() -> None:
    r = run(["stream", "--sim", "--sim-rate", "800", "--duration", "4", "--format", "jsonl"])
    assert r.returncode == 0, r.stderr
    meta, records, events = parse_jsonl(r.stdout)
    assert len(meta) == 1 and events == []
    assert json.loads(r.stdout.splitlines()[0]).keys() == {"metadata"}
    expect_count_near(len(records), 4.0, 800.0)
    for rec in records:
        assert list(rec) == ["t_s", *AXES, "status"]
        assert all(isinstance(rec[a], float) for a in AXES)
        assert isinstance(rec["status"], int)


def test_count_gives_exactly_n_samples() -> None:
    r = run(["stream", "--sim", "--count", "250"])
    assert r.returncode == 0, r.stderr
    rows, _ = parse_csv(r.stdout)
    assert len(rows) == 250


def test_raw_units_are_integer_counts_and_si_is_scaled() -> None:
    raw = run(["stream", "--sim", "--sim-constant", "--count", "20", "--units", "raw"])
    si = run(["stream", "--sim", "--sim-constant", "--count", "20"])
    assert raw.returncode == 0 and si.returncode == 0
    raw_csv = Csv(raw.stdout, "t_s," + ",".join(RAW) + ",status")
    si_csv = Csv(si.stdout, CSV_HEADER)
    for line in raw_csv.lines_after_header:
        assert all(f.lstrip("-").isdigit() for f in line.split(",")[1:])
    # Default model PFS055YA501U6 is rated 500 N on Fx: counts * 500 / 10000.
    assert raw_csv.rows[0]["fx_counts"] != 0
    assert abs(si_csv.rows[0]["fx_N"] - raw_csv.rows[0]["fx_counts"] * 500.0 / 10000.0) < 1e-3


def mean(values: list[float]) -> float:
    return sum(values) / len(values)


def test_tare_zeroes_a_constant_signal_raw_and_zeroed_side_by_side() -> None:
    r = run(["stream", "--sim", "--sim-constant", "--tare", "100", "--count", "300",
             "--columns", "raw,zeroed,si,status"])
    assert r.returncode == 0, r.stderr
    csv = Csv(r.stdout, "t_s," + ",".join(RAW) + "," + ",".join(ZEROED) + ","
              + ",".join(AXES) + ",status")
    assert len(csv.rows) == 300  # the tare samples are not written
    assert csv.metadata[0]["tared"] is True
    for raw, zeroed, si in zip(RAW, ZEROED, AXES):
        assert abs(mean(csv.column(raw))) > 100      # a real load, as received ...
        assert abs(mean(csv.column(zeroed))) < 1.0   # ... and zeroed beside it
        assert abs(mean(csv.column(si))) < 0.05
    # The tare samples come first: the first written t is after them.
    assert csv.rows[0]["t_s"] > 0.0


def test_tare_in_si_units_jsonl() -> None:
    r = run(["stream", "--sim", "--sim-constant", "--tare", "50", "--count", "100",
             "-f", "jsonl"])
    assert r.returncode == 0, r.stderr
    _, records, _ = parse_jsonl(r.stdout)
    for a in AXES:
        assert abs(mean([rec[a] for rec in records])) < 0.05


def test_output_file_that_cannot_be_opened(tmp_path: Path) -> None:
    r = run(["stream", "--sim", "--count", "1", "-o", str(tmp_path / "no" / "such" / "f.csv")])
    assert r.returncode == 1
    assert str(tmp_path / "no" / "such") in r.stderr


def test_unreachable_port_leaves_the_output_file_alone(tmp_path: Path) -> None:
    out = tmp_path / "keep.csv"
    out.write_text("precious\n")
    r = run(["stream", "/dev/leptrino-no-such-port", "-o", str(out)])
    assert r.returncode == 6
    assert out.read_text() == "precious\n"


def test_existing_output_file_is_kept_unless_overwrite(tmp_path: Path) -> None:
    out = tmp_path / "keep.csv"
    out.write_text("precious\n")
    r = run(["stream", "--sim", "--count", "10", "-o", str(out)])
    assert r.returncode == 1 and "exists" in r.stderr
    assert out.read_text() == "precious\n"
    r = run(["stream", "--sim", "--count", "10", "-o", str(out), "--overwrite"])
    assert r.returncode == 0, r.stderr
    assert len(parse_csv(out.read_text())[0]) == 10


def test_stale_stream_is_recovered_at_start_up() -> None:
    r = run(["stream", "--sim", "--sim-start-streaming", "--count", "50"])
    assert r.returncode == 0, r.stderr
    rows, _ = parse_csv(r.stdout)
    assert len(rows) == 50
