"""leptrino-bridge's MCAP output and its command line, run as a user would
(a child process, no network), read back with the mcap reader plus
mcap-ros2-support's decoder, and with rosbags."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any, Dict, List, Tuple

import pytest
from conftest import subprocess_env


def bridge(*args: str, timeout: float = 60) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "leptrino.bridge", *args],
                          capture_output=True, text=True, env=subprocess_env(),
                          timeout=timeout)


def read_mcap(path: Path) -> Tuple[Dict[str, List[Any]], Dict[str, Tuple[str, str, str]]]:
    """topic -> decoded messages (mcap + mcap_ros2), topic -> (schema name,
    schema encoding, message encoding)."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    out: Dict[str, List[Any]] = {}
    kinds: Dict[str, Tuple[str, str, str]] = {}
    with path.open("rb") as f:
        r = make_reader(f, decoder_factories=[DecoderFactory()])
        assert r.get_header().profile == "ros2"
        for schema, channel, message, decoded in r.iter_decoded_messages():
            out.setdefault(channel.topic, []).append((message, decoded))
            kinds[channel.topic] = (schema.name, schema.encoding, channel.message_encoding)
        summary = r.get_summary()
        assert summary is not None and summary.statistics is not None  # finished cleanly
        assert summary.statistics.message_count == sum(len(v) for v in out.values())
    return out, kinds


def test_mcap_without_network(tmp_path: Path) -> None:
    out = tmp_path / "out.mcap"
    p = bridge("--sim", "a", "--sim", "b,amplitude=0.1", "--frame-id", "b=b_ft",
               "--mcap", str(out), "--duration", "2", "--tare", "50")
    assert p.returncode == 0, p.stderr
    assert "messages" in p.stderr and "zenoh session" not in p.stderr
    msgs, kinds = read_mcap(out)
    assert set(msgs) == {f"/{s}/{t}" for s in "ab" for t in ("wrench", "wrench_raw",
                                                              "diagnostics")}
    assert kinds["/a/wrench"] == ("geometry_msgs/msg/WrenchStamped", "ros2msg", "cdr")
    assert kinds["/b/diagnostics"] == ("diagnostic_msgs/msg/DiagnosticArray", "ros2msg",
                                       "cdr")
    for s, frame in (("a", "a"), ("b", "b_ft")):
        w = msgs[f"/{s}/wrench"]
        assert 1200 < len(w) < 3000  # 2 s at 1.2 kHz (the tare's samples come too)
        assert len(msgs[f"/{s}/wrench_raw"]) == len(w)
        assert [m.sequence for m, _ in w] == list(range(1, len(w) + 1))
        assert all(d.header.frame_id == frame for _, d in w)
        stamps = [d.header.stamp.sec * 10**9 + d.header.stamp.nanosec for _, d in w]
        assert stamps == sorted(stamps)
        assert [m.publish_time for m, _ in w] == stamps
        assert 1 <= len(msgs[f"/{s}/diagnostics"]) <= 3
    # tared on the first 50 samples: the zeroed wrench is near zero (the sine
    # moves it a little), the raw one is not
    last_raw = msgs["/b/wrench_raw"][60][1].wrench.force
    last = msgs["/b/wrench"][60][1].wrench.force
    assert abs(last.z) < abs(last_raw.z)

    # rosbags reads the same file, with the types from the file's own schemas
    from rosbags.highlevel import AnyReader

    counts: Counter = Counter()
    with AnyReader([out]) as reader:
        types = {c.topic: c.msgtype for c in reader.connections}
        for conn, _t, raw in reader.messages():
            m = reader.deserialize(raw, conn.msgtype)
            counts[conn.topic] += 1
            if conn.topic == "/a/diagnostics":
                kv = {v.key: v.value for v in m.status[0].values}
                assert float(kv["nominal_rate_hz"]) == 1200
    assert types["/a/wrench"] == "geometry_msgs/msg/WrenchStamped"
    assert counts == Counter({k: len(v) for k, v in msgs.items()})

    # the first diagnostics already say the rate (issue 19: it said 0.00 after 1,200 samples)
    first = msgs["/a/diagnostics"][0][1]
    kv = {v.key: v.value for v in first.status[0].values}
    assert float(kv["recent_rate_hz"]) > 1000, kv

    # each channel says the QoS it was offered with, as rosbag2 writes it (and reads it on
    # playback); read back with rosbags' own parser of that field
    from mcap.reader import make_reader
    from rosbags.rosbag2.reader import parse_qos

    with out.open("rb") as f:
        summary = make_reader(f).get_summary()
    assert summary is not None
    for ch in summary.channels.values():
        qos = parse_qos(ch.metadata["offered_qos_profiles"])
        assert len(qos) == 1, ch.topic
        q = qos[0]
        assert (q.history.name, q.depth, q.reliability.name, q.durability.name,
                q.liveliness.name) == ("KEEP_LAST", 10, "RELIABLE", "VOLATILE", "AUTOMATIC")


def test_refuses_to_overwrite(tmp_path: Path) -> None:
    out = tmp_path / "keep.mcap"
    out.write_bytes(b"someone's file")
    p = bridge("--sim", "a", "--mcap", str(out), "--duration", "0.5")
    # exit 1 and the flag's name, as `leptrino stream -o` says it
    assert p.returncode == 1 and "already exists" in p.stderr and "--overwrite" in p.stderr
    assert out.read_bytes() == b"someone's file"
    p = bridge("--sim", "a", "--mcap", str(out), "--duration", "0.5", "--overwrite")
    assert p.returncode == 0, p.stderr
    msgs, _ = read_mcap(out)
    assert len(msgs["/a/wrench"]) > 100


def test_sigint_and_sigterm_close_the_file(tmp_path: Path) -> None:
    for sig in (signal.SIGINT, signal.SIGTERM):
        out = tmp_path / f"sig{int(sig)}.mcap"
        child = subprocess.Popen(
            [sys.executable, "-m", "leptrino.bridge", "--sim", "a", "--sim", "b",
             "--mcap", str(out)], env=subprocess_env(), stderr=subprocess.PIPE, text=True)
        try:
            end = time.monotonic() + 30
            while time.monotonic() < end and (not out.exists() or out.stat().st_size < 20000):
                time.sleep(0.1)
            child.send_signal(sig)
            _, err = child.communicate(timeout=30)
        finally:
            if child.poll() is None:
                child.kill()
                child.wait(10)
        assert child.returncode == 0, err
        msgs, _ = read_mcap(out)  # a complete file: summary and statistics
        assert len(msgs["/a/wrench"]) > 100 and len(msgs["/b/wrench"]) > 100


@pytest.mark.parametrize("args, message, code", [
    ([], "no sensors", 2),
    (["--sensor", "nameonly"], "NAME=PORT", 2),
    (["--sim", "bad-name"], "sensor name", 2),
    (["--sim", "a", "--sim", "a", "--mcap", "x.mcap"], "differ", 2),
    (["--sim", "a,nosuchoption=1", "--no-zenoh", "--mcap", "x.mcap"], "nosuchoption", 2),
    (["--sim", "a,rate=-5", "--no-zenoh", "--mcap", "x.mcap"], "rate", 2),
    (["--sim", "a", "--no-zenoh"], "--mcap", 2),
    (["--sim", "a", "--no-zenoh", "--connect", "tcp/127.0.0.1:1"], "--no-zenoh", 2),
    (["--sim", "a", "--mode", "client", "--listen", "tcp/127.0.0.1:0"], "client", 2),
    (["--sim", "a", "--frame-id", "zz=f", "--mcap", "x.mcap"], "--frame-id", 2),
    (["--sim", "a", "--namespace", "a b", "--mcap", "x.mcap"], "namespace", 2),
    (["--sim", "a", "--duration", "0", "--mcap", "x.mcap"], "> 0", 2),
    (["--sim", "a", "--dds-interface", "127.0.0.1", "--mcap", "x.mcap"], "needs --dds", 2),
    (["--sim", "a", "--dds", "--dds-interface", "eth0", "--mcap", "x.mcap"], "IP address", 2),
    (["--sim", "a", "--foxglove", "host:port", "--mcap", "x.mcap"], "[HOST:]PORT", 2),
    (["--sim", "a", "--dds", "--ros-distro", "foxy"], "invalid choice", 2),
    (["--sim", "a", "--dds-impl", "cyclone", "--mcap", "x.mcap"], "needs --dds", 2),
    (["--sim", "a", "--dds", "--dds-impl", "fast"], "invalid choice", 2),
    # the `leptrino` tool's exit codes: a missing port 6, an output that cannot be created 1
    (["--sensor", "a=/nonexistent/tty", "--mcap", "x.mcap"], "/nonexistent/tty", 6),
    (["--sim", "a", "--mcap", "/nonexistent/dir/x.mcap"], "nonexistent", 1),
])
def test_bad_arguments(tmp_path: Path, args: List[str], message: str, code: int) -> None:
    p = subprocess.run([sys.executable, "-m", "leptrino.bridge", *args], cwd=tmp_path,
                       capture_output=True, text=True, env=subprocess_env(), timeout=60)
    assert p.returncode == code, (p.stdout, p.stderr)
    assert message in p.stderr
    assert not (tmp_path / "x.mcap").exists()


def test_foxglove_port_in_use(tmp_path: Path) -> None:
    """A --foxglove port another program holds: one line, exit status 1 (an
    output that cannot be made, as the `leptrino` tool's), no file."""
    pytest.importorskip("foxglove")
    import socket

    with socket.socket() as held:
        held.bind(("127.0.0.1", 0))
        held.listen(1)
        port = held.getsockname()[1]
        p = subprocess.run([sys.executable, "-m", "leptrino.bridge", "--sim", "a", "--foxglove",
                            f"127.0.0.1:{port}", "--mcap", "x.mcap"], cwd=tmp_path,
                           capture_output=True, text=True, env=subprocess_env(), timeout=60)
    assert p.returncode == 1, (p.stdout, p.stderr)
    assert f"--foxglove 127.0.0.1:{port}" in p.stderr
    assert not (tmp_path / "x.mcap").exists()
