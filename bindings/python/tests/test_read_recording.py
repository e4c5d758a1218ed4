"""leptrino.read_recording and Recording.load read the tool's own CSV and
JSON lines (written by `leptrino stream -o` and Recording.save through the
one writer) and the .npz, with the metadata and the events; a last line cut
by a crash is left out with a warning."""

from __future__ import annotations

import subprocess
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import leptrino

ALL = ["raw", "zeroed", "si", "status", "flags", "seq"]


def _cli() -> str:
    from leptrino import _tools

    return str(_tools.program_path("leptrino"))  # the bundled program, or LEPTRINO_CLI


@pytest.mark.parametrize("fmt", ["csv", "jsonl"])
def test_reads_what_the_tool_writes(tmp_path: Path, fmt: str) -> None:
    f = tmp_path / f"rec.{fmt}"
    subprocess.run([_cli(), "stream", "--sim", "--sim-drop", "0.01", "--sim-seed", "3",
                    "--count", "1200", "--tare", "20", "-f", fmt, "--columns", ",".join(ALL),
                    "-o", str(f)], check=True, capture_output=True, timeout=60)
    r = leptrino.read_recording(f)
    assert r.format == fmt and len(r) == 1200 and r.time == "t_s"
    assert r.metadata["tared"] is True and r.metadata["sim"] is True
    assert r.columns["fx_counts"].dtype == np.int16 and r.columns["seq"].dtype == np.uint16
    assert np.all(np.diff(r.columns["t_s"]) >= 0)
    steps = np.mod(np.diff(r.columns["seq"].astype(np.int64)), 65536)
    gaps = [e for e in r.events if e["event"] == "gap"]
    assert len(gaps) == int(np.sum(steps > 1)) > 0  # one event per hole, at its row
    for e in gaps:
        assert r.columns["flags"][e["row"]] & 1 and e["lost"] >= 1 and e["reason"] == "gap"
    tares = [e for e in r.events if e["event"] == "tare"]
    assert tares and tares[0]["row"] == 0
    # the SI values are the zeroed counts scaled by the rated values
    rated = r.metadata["rated"]
    fx = r.columns["fx_zeroed_counts"] * rated["fx_N"] / 10000
    assert np.allclose(r.columns["fx_N"], fx, atol=1e-5)
    rec = leptrino.Recording.load(f)
    assert len(rec) == 1200 and np.array_equal(rec.seq, r.columns["seq"])
    assert rec.missing() == sum(e["lost"] for e in gaps)
    assert [e.type for e in rec.events] == [e["event"] for e in r.events]


def test_python_save_round_trip(tmp_path: Path, backend: str) -> None:
    with leptrino.Sensor(sim=True, backend=backend) as s:
        rec = s.record(count=300)
    for name in ("r.csv", "r.jsonl", "r.npz"):
        p = tmp_path / name
        rec.save(p, columns=ALL) if not name.endswith("npz") else rec.save(p)
        r = leptrino.read_recording(p)
        assert len(r) == 300
        assert np.allclose(r.columns["fx_N"], rec.si[:, 0], atol=1e-6)
        assert np.array_equal(r.columns["mz_counts"], rec.raw[:, 5])
        back = leptrino.Recording.load(p)
        assert np.allclose(back.si, rec.si, atol=1e-6)
        assert np.array_equal(back.seq, rec.seq)
        assert back.metadata["model"] == rec.metadata["model"]


def test_pandas(tmp_path: Path, backend: str) -> None:
    pd = pytest.importorskip("pandas")
    with leptrino.Sensor(sim=True, backend=backend) as s:
        s.record(count=10).save(tmp_path / "r.csv")
    df = leptrino.read_recording(tmp_path / "r.csv", pandas=True)
    assert isinstance(df, pd.DataFrame) and list(df.columns)[:2] == ["t_s", "fx_N"]
    assert len(df) == 10 and df.attrs["metadata"]["model"]
    same = pd.read_csv(tmp_path / "r.csv", comment="#")  # what the docs say also works
    assert np.allclose(same["fx_N"], df["fx_N"])


def test_a_line_cut_by_a_crash(tmp_path: Path, backend: str) -> None:
    with leptrino.Sensor(sim=True, backend=backend) as s:
        s.record(count=50).save(tmp_path / "r.csv")
    text = (tmp_path / "r.csv").read_text()
    (tmp_path / "cut.csv").write_text(text[:-7])
    with pytest.warns(RuntimeWarning, match="cut"):
        r = leptrino.read_recording(tmp_path / "cut.csv")
    assert len(r) == 49


def test_not_a_recording(tmp_path: Path) -> None:
    p = tmp_path / "x.csv"
    p.write_text("a,b\n1,2\n")
    with pytest.raises(ValueError, match="not a leptrino recording"):
        leptrino.read_recording(p)
    p.write_text("# leptrino-metadata: {}\nt_s,fx_N\n1.0\n")
    with pytest.raises(ValueError, match="fields where the header has"):
        leptrino.read_recording(p)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        p.write_text("# leptrino-metadata: {}\nt_s,fx_N\n")
        assert len(leptrino.read_recording(p)) == 0


def test_replay_of_a_cut_file_warns(tmp_path: Path, backend: str) -> None:
    """The virtual sensor replays a recording cut by a crash up to its last
    whole row, with a warning (Simulator and Sensor(sim=...))."""
    with leptrino.Sensor(sim=True, backend=backend) as s:
        rec = s.record(count=40)
    rec.save(tmp_path / "raw.csv", columns=["raw"])
    text = (tmp_path / "raw.csv").read_text()
    (tmp_path / "cut.csv").write_text(text[:-3])
    with pytest.warns(RuntimeWarning, match="39 whole rows"):
        sim = leptrino.Simulator(replay=str(tmp_path / "cut.csv"), backend=backend)
    sim.stop()
    with pytest.warns(RuntimeWarning, match="the last line is cut"):
        with leptrino.Sensor(sim={"replay": str(tmp_path / "cut.csv")}, backend=backend) as s:
            again = s.record(count=39)
    assert np.array_equal(again.raw, rec.raw[:39])
