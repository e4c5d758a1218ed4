"""`leptrino stream --sim`: output formats, sample counts, units, tare."""

from __future__ import annotations

import json
from pathlib import Path

from conftest import AXES, CSV_HEADER, parse_csv, run

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
    assert text.splitlines()[0] == CSV_HEADER
    rows, comments = parse_csv(text)
    assert comments == []
    expect_count_near(len(rows), DURATION, RATE)
    ts = [row[0] for row in rows]
    assert all(0.0 <= t < DURATION for t in ts)
    assert ts == sorted(ts)
    # The summary line is always printed on stderr (not a terminal here).
    summary = [line for line in r.stderr.splitlines() if "samples in" in line]
    assert len(summary) == 1 and f"{len(rows)} samples" in summary[0]
    assert "\r" not in r.stderr  # no live status line when stderr is not a tty


def test_jsonl_well_formed_and_count_matches_duration() -> None:
    r = run(["stream", "--sim", "--sim-rate", "800", "--duration", "4", "--format", "jsonl"])
    assert r.returncode == 0, r.stderr
    records = [json.loads(line) for line in r.stdout.splitlines()]
    expect_count_near(len(records), 4.0, 800.0)
    for rec in records:
        assert list(rec) == ["t", *AXES, "status"]
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
    raw_rows, _ = parse_csv(raw.stdout)
    si_rows, _ = parse_csv(si.stdout)
    for line in raw.stdout.splitlines()[1:]:
        assert all(f.lstrip("-").isdigit() for f in line.split(",")[1:])
    # Default model PFS055YA501U6 is rated 500 N on Fx: counts * 500 / 10000.
    assert raw_rows[0][1] != 0
    assert abs(si_rows[0][1] - raw_rows[0][1] * 500.0 / 10000.0) < 1e-3


def mean(values: list[float]) -> float:
    return sum(values) / len(values)


def test_tare_zeroes_a_constant_signal() -> None:
    plain = run(["stream", "--sim", "--sim-constant", "--count", "200", "--units", "raw"])
    tared = run(["stream", "--sim", "--sim-constant", "--tare", "100", "--count", "300",
                 "--units", "raw"])
    assert plain.returncode == 0 and tared.returncode == 0, tared.stderr
    plain_rows, _ = parse_csv(plain.stdout)
    tared_rows, _ = parse_csv(tared.stdout)
    assert len(tared_rows) == 300  # the tare samples are not written
    for axis in range(1, 7):
        assert abs(mean([r[axis] for r in plain_rows])) > 100  # a real load ...
        assert abs(mean([r[axis] for r in tared_rows])) < 1.0  # ... taken away
    # The tare samples come first: the first written t is after them.
    assert tared_rows[0][0] > 0.0


def test_tare_in_si_units_jsonl() -> None:
    r = run(["stream", "--sim", "--sim-constant", "--tare", "50", "--count", "100",
             "-f", "jsonl"])
    assert r.returncode == 0, r.stderr
    records = [json.loads(line) for line in r.stdout.splitlines()]
    for a in AXES:
        assert abs(mean([rec[a] for rec in records])) < 0.05


def test_output_file_that_cannot_be_opened(tmp_path: Path) -> None:
    r = run(["stream", "--sim", "--count", "1", "-o", str(tmp_path / "no" / "such" / "f.csv")])
    assert r.returncode == 1
    assert "cannot open output" in r.stderr


def test_unreachable_port_leaves_the_output_file_alone(tmp_path: Path) -> None:
    out = tmp_path / "keep.csv"
    out.write_text("precious\n")
    r = run(["stream", "/dev/leptrino-no-such-port", "-o", str(out)])
    assert r.returncode == 6
    assert out.read_text() == "precious\n"


def test_stale_stream_is_recovered_at_start_up() -> None:
    r = run(["stream", "--sim", "--sim-start-streaming", "--count", "50"])
    assert r.returncode == 0, r.stderr
    rows, _ = parse_csv(r.stdout)
    assert len(rows) == 50
