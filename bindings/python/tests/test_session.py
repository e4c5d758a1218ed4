"""Sensor over the library's session: tare mid-stream, low-pass, frame,
health, metadata, events, and recordings saved through the C writer."""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

import leptrino
from leptrino import _constants as K


def test_session_runs_its_own_virtual_sensor(backend: str) -> None:
    with leptrino.Sensor(sim={"model": "CFS034CA301U", "output_rate_field": True},
                         backend=backend) as s:
        assert s.product_info.model == "CFS034CA301U" and s.product_info.output_rate_hz == 1200
        meta = s.metadata
        assert meta["model"] == "CFS034CA301U" and meta["sim"] is True
        assert meta["library_version"] == leptrino.__version__
        assert meta["rated"]["fz_N"] == 300
        rec = s.record(count=300)
        assert len(rec) == 300 and rec.missing() == 0
    with pytest.raises(ValueError, match="amplitude"):
        leptrino.Sensor(sim={"amplitude": 5}, backend=backend)
    with pytest.raises(TypeError, match="no_such"):
        leptrino.Sensor(sim={"no_such": 1}, backend=backend)
    with pytest.raises(ValueError):
        leptrino.Sensor(backend=backend)  # neither a port nor sim
    sim = leptrino.Simulator(backend=backend, model="CFS018CA201U")
    try:
        with pytest.raises(ValueError):
            leptrino.Sensor(sim, sim=True, backend=backend)  # both
        with leptrino.Sensor(sim, backend=backend) as s:  # a Simulator is its port
            assert s.port == sim.port and s.product_info.model == "CFS018CA201U"
            assert s.metadata["sim"] is False  # the session sees a serial port
    finally:
        sim.stop()


def test_tare_mid_stream_never_stalls(backend: str) -> None:
    with leptrino.Sensor(sim={"constant": True, "amplitude": 0.25}, backend=backend) as s:
        with s.stream(count=900) as st:
            samples = []
            for x in st:
                samples.append(x)
                if len(samples) == 200:
                    assert s.tare(100) is None  # streaming: runs beside the stream
                    assert s.taring
        assert not s.streaming
        seqs = [x.seq for x in samples]
        assert seqs == list(range(seqs[0], seqs[0] + 900))  # nothing lost, no stall
        taring = [i for i, x in enumerate(samples) if x.taring]
        assert len(taring) == 100 and taring[0] >= 200
        assert all(x.zeroed == tuple(float(v) for v in x.raw) for x in samples[:taring[-1] + 1])
        after = samples[taring[-1] + 1:]
        assert len(after) > 500
        assert all(max(abs(v) for v in x.si) < 1e-9 for x in after)
        assert all(x.zeroed == (0.0,) * 6 for x in after)
        tares = [e for e in st.events if e.type == "tare"]
        assert len(tares) == 1 and tares[0].tare == (2500.0,) * 6
        assert tares[0].sample == taring[-1] + 1
        assert s.tare_offsets == (2500.0,) * 6


def test_tare_over_seconds_and_untare(backend: str) -> None:
    with leptrino.Sensor(sim={"constant": True, "amplitude": 0.1}, backend=backend) as s:
        assert s.tare(seconds=0.1) == (1000.0,) * 6
        s.untare()
        rec = s.record(count=50)
        assert np.all(rec.zeroed == 1000.0)
        # the untare (done while stopped) applies from the recording's first row;
        # the tare's own event stayed with the stream tare() ran for it
        tares = [e for e in rec.events if e.type == "tare"]
        assert len(tares) == 1 and tares[0].tare == (0.0,) * 6 and tares[0].sample == 0
        assert [e.tare for e in s.events if e.type == "tare"] == [(1000.0,) * 6]


def test_events_sit_at_rows_of_a_recording_in_a_running_stream(backend: str) -> None:
    """The library places each event (LEP_EVF_ROW): a recording made in a
    stream that runs already has its tare at its own first zeroed row; an
    untare while stopped is at the next stream's row 0."""
    with leptrino.Sensor(sim={"constant": True, "amplitude": 0.25}, backend=backend) as s:
        s.start()
        assert len(s.record(count=300)) == 300  # rows the next recording does not hold
        s.tare(50, wait=False)
        rec = s.record(count=400)
        tares = [e for e in rec.events if e.type == "tare"]
        assert len(tares) == 1
        i = tares[0].sample
        assert 0 < i < len(rec)
        assert np.all(rec.zeroed[i] == 0.0) and np.all(rec.zeroed[i - 1] == 2500.0)
        # the same event place for a Stream begun in the running stream
        s.tare(50, wait=False)
        with s.stream(count=400) as st:
            rows = list(st)
        tares = [e for e in st.events if e.type == "tare"]
        assert len(tares) == 1 and 0 < tares[0].sample < len(rows)
        assert rows[tares[0].sample].taring is False and rows[tares[0].sample - 1].taring
        s.stop()
        s.untare()
        untare = [e for e in s.take_events() if e.type == "tare"]
        assert len(untare) == 1 and untare[0].sample == 0  # not the last stream's count


def test_lowpass_and_decimate(backend: str) -> None:
    with leptrino.Sensor(sim={"seed": 3}, lowpass=50.0, decimate=4, backend=backend) as s:
        assert s.lowpass == 50.0
        meta = s.metadata
        assert meta["host_lowpass_hz"] == 50 and meta["host_lowpass"] and meta["decimate"] == 4
        rec = s.record(seconds=1.0)
        assert 300 * 0.95 <= len(rec) <= 300 * 1.05, len(rec)
        assert np.all(np.mod(np.diff(rec.seq.astype(np.int64)), 65536) == 4)
        s.lowpass = 0
        assert s.lowpass == 0.0
        with pytest.raises(ValueError, match="low-pass"):
            s.lowpass = 10000.0
    with leptrino.Sensor(sim={"seed": 3}, backend=backend) as raw_s:
        raw = raw_s.record(count=1200)
    with leptrino.Sensor(sim={"seed": 3}, lowpass=20.0, backend=backend) as f_s:
        filt = f_s.record(count=1200)
    # the same waveform, smoothed: far less sample-to-sample noise
    assert np.array_equal(raw.raw, filt.raw)
    assert np.std(np.diff(filt.si[600:, 0])) < 0.2 * np.std(np.diff(raw.si[600:, 0]))


def test_rotation_and_shift(backend: str) -> None:
    with leptrino.Sensor(sim={"constant": True, "amplitude": 0.3},
                         rotation=(0.0, 0.0, math.pi / 2), degrees=False,
                         backend=backend) as s:
        r = s.rotation
        assert np.allclose(r, [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-12)
        rec = s.record(count=20)
        f = rec.raw[0, :3] * np.array(s.rated.force) / 10000
        m = rec.raw[0, 3:] * np.array(s.rated.torque) / 10000
        assert np.allclose(rec.force, r @ f) and np.allclose(rec.torque, r @ m)
        s.set_frame(np.eye(3), shift=(0.0, 0.0, 0.1))
        assert s.shift == (0.0, 0.0, 0.1)
        rec = s.record(count=20)
        shifted = m - np.cross((0.0, 0.0, 0.1), f)
        assert np.allclose(rec.force, f) and np.allclose(rec.torque, shifted)
        with pytest.raises(ValueError):
            s.set_frame((1.0, 2.0))


def test_health_and_gaps(backend: str) -> None:
    with leptrino.Sensor(sim={"drop": 0.02, "seed": 5}, backend=backend) as s:
        rec = s.record(seconds=1.0)
        h = s.health
        assert h.nominal_hz == 1200
        assert 1100 < h.measured_hz < 1300
        assert h.received >= len(rec) and h.delivered >= len(rec)
        gaps = [e for e in rec.events if e.type == "gap"]
        assert gaps and rec.gap.sum() == len(gaps)
        assert sum(e.lost for e in gaps) == rec.missing()
        assert h.gaps >= len(gaps) and h.lost >= rec.missing()
        assert h.client.samples >= len(rec)


def test_disconnect_is_an_event_and_an_error(backend: str) -> None:
    with leptrino.Sensor(sim={"hangup_after": 0.3}, backend=backend) as s:
        with pytest.raises(leptrino.DisconnectedError) as info:
            s.record(seconds=5.0)
        partial = info.value.recording  # type: ignore[attr-defined]
        assert len(partial) > 100 and partial.missing() == 0


def test_reconnect_marks_the_gap(backend: str) -> None:
    with leptrino.Sensor(sim={"hangup_after": 0.3, "reopen_after": 300}, reconnect=True,
                         backend=backend) as s:
        rec = s.record(seconds=2.0)
        kinds = [e.type for e in rec.events]
        assert "disconnected" in kinds and "reconnected" in kinds
        assert rec.gap.any()
        assert s.health.reconnects == 1


def _csv_rows(path: Path) -> tuple:
    text = path.read_text()
    lines = text.splitlines()
    comments = [ln for ln in lines if ln.startswith("#")]
    body = [ln for ln in lines if not ln.startswith("#")]
    rows = list(csv.reader(io.StringIO("\n".join(body))))
    return comments, rows[0], rows[1:]


def test_save_csv_through_the_c_writer(backend: str, tmp_path: Path) -> None:
    with leptrino.Sensor(sim={"seed": 9}, backend=backend) as s:
        rec = s.record(count=200)
        s.tare(50, wait=False)
        rec2 = s.record(count=120)
        meta_json = s.metadata_json()
    path = tmp_path / "r.csv"
    rec.save(path)
    comments, header, rows = _csv_rows(path)
    assert comments[0] == "# leptrino-metadata: " + rec.metadata_json
    assert json.loads(rec.metadata_json)["serial"] == "00000001"
    assert header == ["t_s", "fx_N", "fy_N", "fz_N", "mx_Nm", "my_Nm", "mz_Nm", "status"]
    assert len(rows) == 200
    for i in (0, 77, 199):
        assert rows[i][0] == f"{rec.t[i] - rec.start_mono:.6f}"
        assert rows[i][1:7] == [f"{v:.6f}" for v in rec.si[i]]
        assert rows[i][7] == str(rec.status[i])
    with pytest.raises(FileExistsError):
        rec.save(path)  # never over someone's file
    rec.save(path, overwrite=True)

    every = tmp_path / "all.csv"
    rec2.save(every, columns=("raw", "zeroed", "si", "status", "flags", "seq"), time="mono")
    comments, header, rows = _csv_rows(every)
    assert header[:8] == ["t_mono_s", "fx_counts", "fy_counts", "fz_counts", "mx_counts",
                          "my_counts", "mz_counts", "fx_zeroed_counts"]
    assert header[-3:] == ["status", "flags", "seq"]
    assert len(rows) == 120
    # the tare's event sits where the new offsets start: after the last taring row
    lines = [ln for ln in every.read_text().splitlines()[2:]]
    at = next(i for i, ln in enumerate(lines) if ln.startswith("# tare "))
    assert int(lines[at - 1].split(",")[-2]) & K.LEP_SF_TARING
    assert not int(lines[at + 1].split(",")[-2]) & K.LEP_SF_TARING
    assert [int(r[-1]) for r in rows] == [int(v) for v in rec2.seq]
    assert [int(r[-2]) for r in rows] == [int(v) for v in rec2.flags]
    assert json.loads(comments[0].split(": ", 1)[1])["model"] == json.loads(meta_json)["model"]

    jl = tmp_path / "r.jsonl"
    rec.save(jl)
    objs = [json.loads(line) for line in jl.read_text().splitlines()]
    assert objs[0] == {"metadata": json.loads(rec.metadata_json)}
    assert len(objs) == 201 and objs[1]["fx_N"] == pytest.approx(rec.si[0, 0], abs=1e-6)
    with pytest.raises(ValueError, match="column"):
        rec.save(tmp_path / "x.csv", columns=("bogus",))
    with pytest.raises(ValueError):
        rec.save(tmp_path / "x.txt")


def test_save_npz_round_trip(backend: str, tmp_path: Path) -> None:
    with leptrino.Sensor(sim={"constant": True}, backend=backend) as s:
        s.tare(10, wait=False)
        rec = s.record(count=100)
    path = tmp_path / "r.npz"
    rec.save(path)
    back = leptrino.Recording.load(path)
    for name in ("t", "t_utc", "si", "raw", "zeroed", "status", "flags", "seq"):
        assert np.array_equal(getattr(back, name), getattr(rec, name)), name
        assert getattr(back, name).dtype == getattr(rec, name).dtype
    assert back.events == rec.events and back.metadata == rec.metadata
    assert back.start_mono == rec.start_mono
    with pytest.raises(FileExistsError):
        rec.save(path)


def test_record_arrays_come_from_the_session(backend: str) -> None:
    with leptrino.Sensor(sim={}, backend=backend) as s:
        rec = s.record(count=400)
    assert rec.t_utc.shape == (400,) and rec.zeroed.shape == (400, 6)
    assert rec.flags.dtype == np.uint8 and rec.zeroed.dtype == np.float64
    assert np.all(np.diff(rec.t) >= 0)
    # the wall clock moves with the monotonic one
    assert np.allclose(rec.t_utc - rec.t, (rec.t_utc - rec.t)[0], atol=0.05)
    assert rec.metadata["start_utc"] > 1.6e9
    assert 0 <= rec.t[0] - rec.start_mono < 1.0
    assert not (rec.flags & K.LEP_SF_TARING).any()


def _normalised(path: Path) -> list:
    """The file without what differs between two runs: times and the start."""
    import re

    out = []
    for line in path.read_text().splitlines():
        if line.startswith("# leptrino-metadata: "):
            meta = json.loads(line.split(": ", 1)[1])
            for k in ("start_utc", "start_utc_iso", "port"):
                meta.pop(k)
            out.append(meta)
        elif line.startswith("#"):
            out.append(re.sub(r"\b(at|from|to)=[0-9.]+", r"\1=T", line))
        else:
            out.append(line.split(",", 1)[1])  # drop the time column
    return out


@pytest.mark.parametrize("cli_args,kwargs", [
    (["--tare", "50"], {"tare": 50}),
    (["--lowpass", "50", "--decimate", "2", "--rotate", "0,0,90"],
     # one unit: --rotate and rotation= are both degrees
     {"lowpass": 50.0, "decimate": 2, "rotation": (0.0, 0.0, 90.0)}),
])
def test_same_rows_as_the_c_tool(backend: str, tmp_path: Path, cli_args: list,
                                 kwargs: dict) -> None:
    """The same options give the same file from `leptrino stream` and from
    Recording.save, but for the arrival times and the start time."""
    import subprocess

    from leptrino import _tools

    cols = "raw,zeroed,si,status,flags,seq"
    c_file, py_file = tmp_path / "c.csv", tmp_path / "py.csv"
    r = subprocess.run([str(_tools.program_path("leptrino")), "stream", "--sim", "--sim-seed",
                        "4", "-c", "300", "--columns", cols, "-o", str(c_file), *cli_args],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    with leptrino.Sensor(sim={"seed": 4}, backend=backend, **kwargs) as s:
        rec = s.record(count=300)
    rec.save(py_file, columns=tuple(cols.split(",")))
    c, py = _normalised(c_file), _normalised(py_file)
    assert len(c) == len(py) >= 302
    assert c == py


def test_seconds_count_as_the_c_tools_duration(backend: str, tmp_path: Path) -> None:
    """record(seconds=S) and stream(seconds=S) with a tare hold S seconds of
    rows, from the first row's arrival, as `leptrino stream --duration S
    --tare N` does (the tare's samples are not part of the time): the same
    number of rows from both, give or take the clock's jitter."""
    import subprocess

    from leptrino import _tools

    c_file = tmp_path / "c.csv"
    r = subprocess.run([str(_tools.program_path("leptrino")), "stream", "--sim", "--tare",
                        "240", "-d", "1", "-o", str(c_file)],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    c_rows = sum(1 for line in c_file.read_text().splitlines()
                 if line and not line.startswith(("#", "t_s")))
    with leptrino.Sensor(sim={}, tare=240, backend=backend) as s:
        rec = s.record(seconds=1.0)
    period = 1 / 1200
    # record() keeps the last read whole (samples the latency budget held back)
    assert 1.0 - 6 * period < rec.t[-1] - rec.t[0] < 1.05
    # the 240 tare samples are not part of either's second (a 2 % margin for a loaded machine)
    assert abs(len(rec) - c_rows) <= 24, (len(rec), c_rows)
    with leptrino.Sensor(sim={}, tare=240, backend=backend) as s:
        with s.stream(seconds=0.5) as st:
            t = [x.t for x in st]
    assert 0.5 - 6 * period < t[-1] - t[0] < 0.5


def test_stall_shorter_than_the_data_timeout_is_a_gap(backend: str) -> None:
    with leptrino.Sensor(sim={"stall": 300, "stall_after": 0.3}, timeout=0.1,
                         backend=backend) as s:
        n, gap_events = 0, 0
        with s.stream(seconds=1.2) as st:
            for x in st:  # a 0.3 s hole, three times the answer timeout: no error
                n += 1
            gap_events = sum(1 for e in st.events if e.type == "gap")
        assert n > 500 and gap_events >= 1
        assert s.health.gaps >= 1 and s.health.max_gap_s >= 0.25


def test_data_timeout_ends_the_stream(backend: str) -> None:
    import time

    with leptrino.Sensor(sim={"stall": 2500, "stall_after": 0.2}, data_timeout=0.5,
                         backend=backend) as s:
        t0 = time.monotonic()
        with pytest.raises(leptrino.TimeoutError) as info:
            s.record(seconds=10.0)
        # given up after the data timeout, not the 10 s (the stop then waits for
        # the stalled sensor's answer)
        assert time.monotonic() - t0 < 6.0
        partial = info.value.recording  # type: ignore[attr-defined]
        assert 100 < len(partial) and partial.t[-1] - partial.t[0] < 1.0
        lost = [e for e in partial.events if e.type == "disconnected"]
        assert lost and lost[0].error == K.LEP_E_TIMEOUT
        # the session says the stream is lost (LEP_E_LOST), not "nothing yet"
        assert info.value.error == K.LEP_E_LOST
        # no silent wait: the message names the stop's wait and what changes it
        assert "no data for 0.5 s (data_timeout=)" in str(info.value)
        assert ("stopping the sensor's stream waits up to 2 s for an answer "
                "(timeout= 0.5 s a try, retries= 3 more)") in str(info.value), str(info.value)


def test_a_lost_stream_ends_the_iterator_with_the_sessions_code(backend: str) -> None:
    import time

    with leptrino.Sensor(sim={"stall": 2500, "stall_after": 0.2}, data_timeout=0.5,
                         timeout=0.1, backend=backend) as s:
        t0 = time.monotonic()
        n = 0
        with pytest.raises(leptrino.TimeoutError) as info:
            with s.stream() as st:
                for _ in st:
                    n += 1
        assert info.value.error == K.LEP_E_LOST
        assert n > 100 and time.monotonic() - t0 < 6.0
        assert any(e.type == "disconnected" for e in st.events)


def test_health_counts_dropped_events(backend: str) -> None:
    with leptrino.Sensor(sim={}, backend=backend) as s:
        for _ in range(1030):
            s.untare()  # one tare event each, never read: the queue keeps 1024
        assert s.health.events_dropped == 6


def test_read_batch_take_events_and_status_text(backend: str) -> None:
    """A program's own reading loop (the bridge's): batches into a
    SampleBuffer, status codes without exceptions, the events taken."""
    with leptrino.Sensor(sim={"constant": True}, backend=backend, latency=0.002) as s:
        buf = s.sample_buffer(64)
        assert isinstance(buf, leptrino.SampleBuffer) and buf.cap == 64
        s.start()
        got = 0
        events = []
        s.tare(50, wait=False)
        for _ in range(200):
            rc = s.read_batch(buf, 0.5)
            assert rc == 0 or rc == K.LEP_E_TIMEOUT, s.status_text(rc)
            assert buf.n <= 64
            got += buf.n
            events += s.take_events()
            if got > 300 and any(e.type == "tare" for e in events):
                break
        s.stop()
        assert got > 300
        tare = [e for e in events if e.type == "tare"]
        assert tare and any(tare[0].tare) and 0 < tare[0].sample <= got
        assert buf.si.shape == (64, 6) and buf.raw.dtype == np.int16
        assert s.status_text(K.LEP_E_TIMEOUT)
