"""A sensor on a serial port: leptrino.Sensor.

Not thread-safe: one Sensor per port, used from one thread at a time.
"""

from __future__ import annotations

import math
import warnings
from typing import Any, Iterator, List, Optional, Tuple

import numpy as np

from . import _constants as K
from ._backend import get_backend
from .errors import LeptrinoError, error_for
from .values import (
    ClientStats,
    ProductInfo,
    Rated,
    Recording,
    Sample,
    copy_fields,
    make_sample,
)

#: Seconds per call of lep_record_fill in record(): bounds how long Ctrl-C waits.
_RECORD_SLICE_S = 0.25


class PowerCycleWarning(UserWarning):
    """A setting was stored by the sensor but takes effect only after a power cycle."""


def product_info_from(be: Any, c: Any) -> ProductInfo:
    return ProductInfo(
        model=be.text(c.model),
        serial=be.text(c.serial),
        firmware=be.text(c.firmware),
        output_rate=be.text(c.output_rate),
        output_rate_hz=int(c.output_rate_hz) or None,
        has_output_rate=bool(c.has_output_rate),
    )


class Sensor:
    """A Leptrino sensor on a serial port.

    Opening (the constructor) takes the port exclusively, then recovers from
    whatever state the sensor was left in: stops a running stream, drains the
    line until it is quiet, and checks that the sensor answers. Use it as a
    context manager; closing stops any stream and releases the port.

    timeout: seconds to wait for each answer (and for each stream sample).
    retries: times a command the sensor NAKs is sent again.
    backend: "ctypes" or "cffi" (default: LEPTRINO_BACKEND, else ctypes).
    """

    def __init__(
        self,
        port: str,
        timeout: float = 0.1,
        *,
        retries: int = K.LEP_CLIENT_DEFAULT_RETRIES,
        quiet: float = 0.05,
        backend: Optional[str] = None,
    ) -> None:
        self._be = be = get_backend(backend)
        self._serial: Any = None
        self.port = str(port)
        if not timeout > 0:
            raise ValueError("timeout must be > 0 seconds")
        self._timeout_ms = max(1, int(math.ceil(timeout * 1000)))
        self._rated: Optional[Rated] = None
        self._rated_c: Any = None
        self._offset = np.zeros(K.LEP_AXES)
        self._si = be.doubles(K.LEP_AXES)
        self._sample_c = be.new("lep_sample")

        out = be.new_handle("lep_serial")
        err = be.new_text(512)
        rc = be.lib.lep_serial_open(self.port.encode(), out, err, 512)
        if rc < 0:
            msg = be.text(err)
            raise error_for(be, rc, msg or self.port, complete=bool(msg))
        self._serial = be.handle(out)
        try:
            self._client, self._client_mem = be.new_client()
            self._check(be.lib.lep_serial_client_init(self._client, self._serial))
            self._check(be.lib.lep_client_set_timeout(self._client, self._timeout_ms))
            if not 0 <= retries <= 255:
                raise ValueError("retries must be 0..255")
            self._check(be.lib.lep_client_set_retries(self._client, retries))
            info = be.new("lep_product_info")
            quiet_ms = max(1, int(quiet * 1000))
            self._check(be.lib.lep_client_sync(self._client, quiet_ms, info), K.LEP_CMD_STOP,
                        f"{self.port}: start-up recovery")
            self._info = product_info_from(be, info)
        except BaseException:
            self._close_port()
            raise

    # -- life cycle ----------------------------------------------------------
    def __enter__(self) -> "Sensor":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:
            pass

    def __repr__(self) -> str:
        state = "closed" if self.closed else self._info.model
        return f"<leptrino.Sensor {self.port} {state} ({self._be.name})>"

    @property
    def closed(self) -> bool:
        return self._serial is None

    @property
    def backend(self) -> str:
        return str(self._be.name)

    def close(self) -> None:
        """Stop a running stream (best effort) and release the port. Idempotent."""
        if self._serial is None:
            return
        try:
            if self._be.lib.lep_client_streaming(self._client):
                self._be.lib.lep_client_stop(self._client)
        finally:
            self._close_port()

    def _close_port(self) -> None:
        if self._serial is not None:
            self._be.lib.lep_serial_close(self._serial)
            self._serial = None

    # -- helpers -------------------------------------------------------------
    def _live(self) -> Any:
        if self._serial is None:
            raise LeptrinoError(f"{self.port}: the sensor is closed", K.LEP_E_STATE)
        return self._client

    def _check(self, rc: int, command: Optional[int] = None, what: str = "") -> int:
        if rc < 0:
            result = None
            if rc == K.LEP_E_SENSOR:
                result = int(self._be.lib.lep_client_last_result(self._client))
            raise error_for(self._be, rc, what or self.port, result=result, command=command)
        return rc

    def _sample(self, t: float) -> Sample:
        be, s = self._be, self._sample_c
        be.lib.lep_sample_to_si(s, self._rated_struct(), self._si)
        si = [self._si[i] - self._offset[i] for i in range(K.LEP_AXES)]
        return make_sample(t, si, list(s.raw), s.status, s.reserved)

    def _rated_struct(self) -> Any:
        if self._rated_c is None:
            c = self._be.new("lep_rated")
            self._check(self._be.lib.lep_client_rated(self._live(), c), K.LEP_CMD_RATED)
            self._rated_c = c
            self._rated = Rated(*(float(v) for v in c.axis))
        return self._rated_c

    # -- queries -------------------------------------------------------------
    @property
    def product_info(self) -> ProductInfo:
        """Model, serial, firmware, output rate (read when the sensor was opened)."""
        return self._info

    @property
    def rated(self) -> Rated:
        """Rated (full-scale) values, N and N·m (asked once, then cached)."""
        self._rated_struct()
        assert self._rated is not None
        return self._rated

    @property
    def filter(self) -> int:
        """Digital filter code in effect (0 off, 1..3; see filter_label)."""
        code = self._be.new_scalar("uint8_t")
        self._check(self._be.lib.lep_client_filter_get(self._live(), code), K.LEP_CMD_FILTER_GET)
        return int(self._be.value(code))

    @filter.setter
    def filter(self, code: int) -> None:
        if not 0 <= int(code) <= K.LEP_FILTER_MAX:
            raise ValueError(f"filter code must be 0..{K.LEP_FILTER_MAX}, not {code}")
        self._check(self._be.lib.lep_client_filter_set(self._live(), int(code)),
                    K.LEP_CMD_FILTER_SET)
        warnings.warn(
            f"filter {int(code)} stored; it takes effect only after the sensor is "
            "power-cycled (switched off and on)",
            PowerCycleWarning,
            stacklevel=2,
        )

    def filter_label(self, code: Optional[int] = None) -> str:
        """The spec's label of a filter code ("off", "10 Hz", ...); models differ."""
        if code is None:
            code = self.filter
        return str(self._be.text(self._be.lib.lep_filter_label(int(code) & 0xFF)))

    @property
    def stats(self) -> ClientStats:
        """The client's counters (messages, BCC errors, NAKs, retries, ...)."""
        st = self._be.new("lep_client_stats")
        self._be.lib.lep_client_get_stats(self._live(), st)
        return copy_fields(ClientStats, st)  # type: ignore[no-any-return]

    @property
    def streaming(self) -> bool:
        return bool(self._be.lib.lep_client_streaming(self._live()))

    # -- data ----------------------------------------------------------------
    def read(self) -> Sample:
        """One sample in handshake mode (command 0x30). StateError while streaming."""
        self._rated_struct()
        rc = self._be.lib.lep_client_sample(self._live(), self._sample_c)
        t = float(self._be.lib.lep_monotonic_seconds())
        self._check(rc, K.LEP_CMD_SAMPLE)
        return self._sample(t)

    def start(self) -> None:
        """Start continuous output (prefer stream() or record())."""
        self._rated_struct()
        self._check(self._be.lib.lep_client_start(self._live()), K.LEP_CMD_START)

    def stop(self) -> None:
        """Stop continuous output; data already on the line is discarded."""
        self._check(self._be.lib.lep_client_stop(self._live()), K.LEP_CMD_STOP)

    def next_sample(self, timeout: Optional[float] = None) -> Sample:
        """The next stream sample (the stream must be running).

        timeout: seconds (default: the sensor's timeout). TimeoutError if none came."""
        ms = self._timeout_ms if timeout is None else max(0, int(math.ceil(timeout * 1000)))
        rc = self._be.lib.lep_client_next_sample(self._live(), self._sample_c, ms)
        t = float(self._be.lib.lep_monotonic_seconds())
        self._check(rc, None, f"{self.port}: waiting for a stream sample")
        return self._sample(t)

    def stream(self, count: Optional[int] = None, seconds: Optional[float] = None) -> "Stream":
        """Continuous output as a context manager and iterator of Samples.

            with sensor.stream() as samples:
                for s in samples: ...

        The stream starts on entry (or on the first iteration) and stops on exit.
        count / seconds end the iteration after that many samples / seconds."""
        return Stream(self, count, seconds)

    def record(self, seconds: Optional[float] = None, count: Optional[int] = None) -> Recording:
        """Record seconds of the stream, or count samples, into numpy arrays.

        The C library fills the arrays (one call per batch, no per-sample Python
        work). Starts the stream if it is not running and stops it again after.
        On an error (TimeoutError, DisconnectedError...) and on an interruption
        (KeyboardInterrupt, an exception raised by a signal handler) the
        exception's .recording holds what was recorded until then."""
        if (seconds is None) == (count is None):
            raise ValueError("give exactly one of seconds= or count=")
        if seconds is not None and not seconds > 0:
            raise ValueError("seconds must be > 0")
        if count is not None and int(count) <= 0:
            raise ValueError("count must be > 0")
        be, lib = self._be, self._be.lib
        rated = self._rated_struct()
        if count is not None:
            cap = int(count)
        else:
            assert seconds is not None
            rate = self._info.output_rate_hz or 1200
            cap = int(seconds * rate * 1.05) + 64
        arrays = _Batch(be, cap)
        started = False
        client = self._live()
        if not lib.lep_client_streaming(client):
            self._check(lib.lep_client_start(client), K.LEP_CMD_START)
            started = True
        try:
            end = float(lib.lep_monotonic_seconds()) + seconds if seconds is not None else 0.0
            while True:
                now = float(lib.lep_monotonic_seconds())
                if seconds is not None and now >= end:
                    break
                until = now + _RECORD_SLICE_S
                if seconds is not None:
                    until = min(until, end)
                rc = lib.lep_record_fill(client, rated, arrays.c, until, self._timeout_ms)
                if rc < 0:
                    exc = error_for(be, rc, f"{self.port}: recording")
                    exc.recording = arrays.result(self._offset)  # type: ignore[attr-defined]
                    raise exc
                if arrays.full():
                    if count is not None:
                        break
                    arrays.grow()
        except BaseException as exc:
            # Ctrl-C lands between two batches: keep what was received.
            if not isinstance(exc, LeptrinoError) and not hasattr(exc, "recording"):
                try:
                    exc.recording = arrays.result(self._offset)  # type: ignore[attr-defined]
                except Exception:
                    pass
            raise
        finally:
            if started and self._serial is not None:
                try:
                    lib.lep_client_stop(client)
                except Exception:
                    pass
        return arrays.result(self._offset)

    def tare(self, n: int = 100) -> Tuple[float, ...]:
        """Measure the mean of n samples and subtract it from every later
        sample (read, stream, record). Returns the offset (N, N·m).
        n=0 removes the offset."""
        if n <= 0:
            self._offset = np.zeros(K.LEP_AXES)
            return tuple(self._offset.tolist())
        saved = self._offset
        self._offset = np.zeros(K.LEP_AXES)
        try:
            rec = self.record(count=int(n))
        except BaseException:
            self._offset = saved
            raise
        self._offset = rec.si.mean(axis=0)
        return tuple(float(v) for v in self._offset)

    @property
    def offset(self) -> Tuple[float, ...]:
        """The tare offset subtracted from SI values (zeros when not tared)."""
        return tuple(float(v) for v in self._offset)


class _Batch:
    """numpy arrays and the lep_record_batch that points into them."""

    t: np.ndarray
    si: np.ndarray
    raw: np.ndarray
    status: np.ndarray
    seq: np.ndarray

    def __init__(self, be: Any, cap: int) -> None:
        self.be = be
        self.c = be.new("lep_record_batch")
        self._alloc(cap, 0)

    def _alloc(self, cap: int, keep: int) -> None:
        t = np.empty(cap, dtype=np.float64)
        si = np.empty((cap, K.LEP_AXES), dtype=np.float64)
        raw = np.empty((cap, K.LEP_AXES), dtype=np.int16)
        status = np.empty(cap, dtype=np.uint8)
        seq = np.empty(cap, dtype=np.uint16)
        if keep:
            t[:keep] = self.t[:keep]
            si[:keep] = self.si[:keep]
            raw[:keep] = self.raw[:keep]
            status[:keep] = self.status[:keep]
            seq[:keep] = self.seq[:keep]
        self.t, self.si, self.raw, self.status, self.seq = t, si, raw, status, seq
        be, c = self.be, self.c
        c.cap = cap
        c.n = keep
        c.t = be.array_ptr(t, "double")
        c.si = be.array_ptr(si, "double")
        c.raw = be.array_ptr(raw, "int16_t")
        c.status = be.array_ptr(status, "uint8_t")
        c.seq = be.array_ptr(seq, "uint16_t")

    def full(self) -> bool:
        return int(self.c.n) >= int(self.c.cap)

    def grow(self) -> None:
        self._alloc(2 * int(self.c.cap), int(self.c.n))

    def result(self, offset: np.ndarray) -> Recording:
        n = int(self.c.n)
        si = self.si[:n].copy()
        if np.any(offset):
            si -= offset
        return Recording(
            t=self.t[:n].copy(),
            si=si,
            raw=self.raw[:n].copy(),
            status=self.status[:n].copy(),
            seq=self.seq[:n].copy(),
        )


class Stream:
    """Iterator of stream samples; a context manager that stops the stream on exit."""

    def __init__(self, sensor: Sensor, count: Optional[int], seconds: Optional[float]) -> None:
        self._sensor = sensor
        self._count = count
        self._seconds = seconds
        self._started = False
        self._n = 0
        self._end: Optional[float] = None

    def __enter__(self) -> "Stream":
        self._start()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def _start(self) -> None:
        if not self._started:
            s = self._sensor
            if not s.streaming:
                s.start()
            self._started = True
            if self._seconds is not None:
                self._end = float(s._be.lib.lep_monotonic_seconds()) + self._seconds

    def close(self) -> None:
        """Stop the stream (best effort when the port is gone)."""
        if self._started:
            self._started = False
            s = self._sensor
            if not s.closed and s.streaming:
                s.stop()

    def __iter__(self) -> Iterator[Sample]:
        self._start()
        return self

    def __next__(self) -> Sample:
        if not self._started:
            raise StopIteration
        if self._count is not None and self._n >= self._count:
            self.close()  # done: do not leave the sensor streaming until collected
            raise StopIteration
        if self._end is not None:
            left = self._end - float(self._sensor._be.lib.lep_monotonic_seconds())
            if left <= 0:
                self.close()
                raise StopIteration
        sample = self._sensor.next_sample()
        self._n += 1
        return sample

    def __del__(self) -> None:
        # Best effort when the iteration was abandoned; close() is the contract.
        try:
            self.close()
        except Exception:
            pass


def list_ports(backend: Optional[str] = None) -> List[Any]:
    """Serial ports on this machine (path, by-id name, USB VID:PID, likely sensor)."""
    from .values import PortInfo

    be = get_backend(backend)
    n = be.new_scalar("size_t")
    rc = be.lib.lep_serial_list(be.new("lep_port_info"), 0, n)
    if rc < 0:
        raise error_for(be, rc, "listing serial ports")
    total = int(be.value(n))
    if total == 0:
        return []
    arr = (be.new_array("lep_port_info", total))
    rc = be.lib.lep_serial_list(arr, total, n)
    if rc < 0:
        raise error_for(be, rc, "listing serial ports")
    out = []
    for i in range(min(total, int(be.value(n)))):
        p = arr[i]
        out.append(PortInfo(path=be.text(p.path), by_id=be.text(p.by_id),
                            description=be.text(p.description), vid=int(p.vid),
                            pid=int(p.pid), likely_sensor=bool(p.likely_sensor)))
    return out
