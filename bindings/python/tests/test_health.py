"""Health after a loss (issue 19): the disconnect is counted, and stays
counted after the call that saw it (the counters cover the stream since its
start; the next start clears them)."""

from __future__ import annotations

import threading
from typing import Any

import pytest

import leptrino


def test_disconnect_counted_after_record(backend: str) -> None:
    sim = leptrino.Simulator()
    try:
        s = leptrino.Sensor(sim, backend=backend)
        threading.Timer(0.3, sim.hangup).start()
        with pytest.raises(leptrino.DisconnectedError) as e:
            s.record(seconds=3)
        assert [ev.type for ev in e.value.recording.events] == ["disconnected"]
        h = s.health
        assert h.disconnects == 1 and h.received > 0
        s.close()
    finally:
        sim.stop()


def test_disconnect_counted_after_a_stream(backend: str) -> None:
    sim = leptrino.Simulator()
    try:
        with leptrino.Sensor(sim, backend=backend) as s:
            n = 0
            with pytest.raises(leptrino.DisconnectedError):
                with s.stream() as samples:
                    for _ in samples:
                        n += 1
                        if n == 200:
                            sim.hangup()
            assert s.health.disconnects == 1
    finally:
        sim.stop()


def test_data_timeout_counted(backend: str) -> None:
    sim = leptrino.Simulator()
    try:
        with leptrino.Sensor(sim, data_timeout=0.3, backend=backend) as s:
            threading.Timer(0.3, lambda: sim.stall(2.0)).start()
            with pytest.raises(leptrino.TimeoutError, match="data_timeout="):
                s.record(seconds=3)
            assert s.health.disconnects == 1 and s.health.errors >= 1
    finally:
        sim.stop()


def test_health_before_any_stream_is_zero(sim: Any, backend: str) -> None:
    with leptrino.Sensor(sim, backend=backend) as s:
        s.read()  # a handshake sample is not the stream: health counts the stream
        assert s.health.received == 0 and s.health.disconnects == 0
