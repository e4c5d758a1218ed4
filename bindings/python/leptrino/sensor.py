"""A sensor through the library's host session: leptrino.Sensor.

Everything a session does (start-up recovery, tare, host low-pass,
decimation, rotation, gap detection, reconnect, health, metadata) runs in C
(leptrino/session.h): options go in by name (leptrino/options.h), samples
come out into numpy arrays the session fills directly, and events, health
and metadata are flat arrays of doubles read by field index or name. No C
layout is mirrored here.

Threads: one thread at a time drives a Sensor (record, stream, read, start,
stop, filter, stats, tare with wait); another thread's driving call raises
StateError at once (nothing waits, nothing is shared). tare (without wait),
untare, the tare offsets, the low-pass, the frame, health and metadata may be
used from any thread. close() from any thread is safe: a call in progress in
another thread raises StateError at its next read and close() waits for it
(leptrino/_guard.py).
"""

from __future__ import annotations

import functools
import json
import math
import warnings
from typing import (Any, Callable, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple,
                    TypeVar, Union, cast)

import numpy as np

from . import _constants as K
from . import _args as A
from . import _options as _opts
from ._backend import get_backend
from ._guard import Guard
from .errors import LeptrinoError, error_for
from .payload import Payload
from .values import (
    Six,
    EVENT_NAMES,
    ClientStats,
    Health,
    ProductInfo,
    Rated,
    Recording,
    Sample,
    SessionEvent,
)

#: Samples per lep_session_read in the sample iterator.
_ITER_BATCH = 256
#: Longest wait of one lep_session_read in record(): bounds how long Ctrl-C waits.
_RECORD_SLICE_S = 0.25
#: record() returns only at its end, so it may let the library hold samples
#: back this long (ms) to save wake-ups (about 1.5 us of CPU per sample
#: instead of 2.5 at 50 ms); the Sensor's own budget comes back after.
_RECORD_LATENCY_MS = 100
#: Reads after the end of record(seconds=...) that collect what the budget
#: held back (each takes one batch of what the kernel buffered).
_RECORD_FINAL_READS = 64


_F = TypeVar("_F", bound=Callable[..., Any])


def _driving(fn: _F) -> _F:
    """A call only the driving thread makes (StateError from another thread)."""
    @functools.wraps(fn)
    def wrap(self: Sensor, *a: Any, **k: Any) -> Any:
        g = self._guard
        g.enter_drive(self.port)
        try:
            return fn(self, *a, **k)
        finally:
            g.leave_drive()
    return cast(_F, wrap)


def _any_thread(fn: _F) -> _F:
    """A call any thread may make (close() waits for it)."""
    @functools.wraps(fn)
    def wrap(self: Sensor, *a: Any, **k: Any) -> Any:
        g = self._guard
        g.enter_call(self.port)
        try:
            return fn(self, *a, **k)
        finally:
            g.leave_call()
    return cast(_F, wrap)


class PowerCycleWarning(UserWarning):
    """A setting was stored by the sensor but takes effect only after a power cycle."""


_health_names_of: Dict[str, List[str]] = {}


def _health_names(be: Any) -> List[str]:
    """The names of the library's health fields (lep_session_health_field_name)."""
    names = _health_names_of.get(be.name)
    if names is None:
        lib = be.lib
        names = [be.text(lib.lep_session_health_field_name(i))
                 for i in range(int(lib.lep_session_health_fields()))]
        _health_names_of[be.name] = names
    return names


def _ms(seconds: float, what: str, lo_exclusive: bool = False) -> int:
    return int(math.ceil(A.number("Sensor", what, seconds, 0.0, 3600.0, lo_exclusive) * 1000))


class Sensor:
    """A Leptrino sensor, through the library's session (leptrino/session.h).

        with leptrino.Sensor("/dev/ttyACM0") as sensor: ...
        with leptrino.Sensor(sim={"model": "CFS034CA301U"}) as sensor: ...

    port: a serial port path, or a running Simulator (its port). Or sim=:
    True or a dict of virtual sensor options (as Simulator takes) for a
    virtual sensor the session runs itself.

    Opening takes the port exclusively and recovers from whatever state the
    sensor was left in (stops a running stream, drains, identifies), then
    reads the rated values and the filter. A context manager; close() stops
    any stream and releases the port.

    timeout: seconds to wait for each answer (per attempt) and for stream data.
    retries: times a command the sensor NAKs is sent again.
    latency: how long the library may hold samples back to save wake-ups
      (record() and the iterator then cost a fraction of the CPU); 0 delivers
      each sample as soon as it is read (a control loop).
    tare: tare over the first N samples after the stream starts.
    lowpass: host low-pass cut-off in Hz (0 off); decimate: keep every Nth.
    rotation: (roll, pitch, yaw) in degrees (as `leptrino --rotate` and
      `leptrino-bridge --rotate`; degrees=False: radians) or a 3x3 matrix;
      shift: the moment reference point (x, y, z) in metres, in the output frame.
    reconnect: reopen the port after a disconnect (with backoff) and go on.
    data_timeout: no data for this long while streaming is a disconnect.
    """

    def __init__(
        self,
        port: Union[str, Any, None] = None,
        timeout: float = 0.5,
        *,
        sim: Union[bool, Mapping[str, Any], None] = None,
        retries: int = K.LEP_CLIENT_DEFAULT_RETRIES,
        quiet: float = 0.03,
        latency: float = 0.05,
        tare: int = 0,
        lowpass: float = 0.0,
        decimate: int = 1,
        rotation: Optional[Sequence[Any]] = None,
        shift: Optional[Sequence[float]] = None,
        reconnect: bool = False,
        data_timeout: float = 2.0,
        gap_periods: float = 3.0,
        nominal_hz: float = 0.0,
        backend: Optional[str] = None,
        degrees: bool = True,
    ) -> None:
        self._guard = Guard()
        self.port: str = str(port or "virtual sensor")
        self._s: Any = None
        self._be = be = get_backend(backend)
        lib = be.lib
        # every argument checked before the library sees any (leptrino/_args.py)
        A.number("Sensor", "timeout", timeout, 0.0, 3600.0, lo_exclusive=True)
        retries = A.whole("Sensor", "retries", retries, 0, 255)
        decimate = A.whole("Sensor", "decimate", decimate, 1, 100000)
        tare = A.whole("Sensor", "tare", tare, 0, 1000000)
        lowpass = A.number("Sensor", "lowpass", lowpass, 0.0, 1e5)
        gap_periods = A.number("Sensor", "gap_periods", gap_periods, 1.0, 1e6)
        nominal_hz = A.number("Sensor", "nominal_hz", nominal_hz, 0.0, 1e5)
        reconnect = A.flag("Sensor", "reconnect", reconnect)
        degrees = A.flag("Sensor", "degrees", degrees)
        rot = None if rotation is None else self._matrix(rotation, degrees, "Sensor")
        sh = None if shift is None else self._vec3(shift, "Sensor")
        self._timeout_ms = max(1, _ms(timeout, "timeout"))
        self._retries = int(retries)  # named by a lost stream's message
        if port is not None and not isinstance(port, str):
            port = getattr(port, "port", port)  # a Simulator
        if (port is None) == (sim is None or sim is False):
            raise ValueError("give a port, or sim=True / sim={options}, not both")
        data_timeout_ms = max(1, _ms(data_timeout, "data_timeout", lo_exclusive=True))
        with _opts.Options(be) as o:
            if port is not None:
                o.set("port", str(port), "Sensor: ")
            else:
                from .simulator import fill_options

                o.set("sim", True, "Sensor: ")
                fill_options(be, o, dict(sim) if isinstance(sim, Mapping) else {})
            o.set("timeout", self._timeout_ms, "Sensor: ")
            o.set("retries", int(retries), "Sensor: ")
            o.set("sync-quiet", max(1, _ms(quiet, "quiet")), "Sensor: ")
            o.set("latency", _ms(latency, "latency"), "Sensor: ")
            o.set("tare-samples", int(tare), "Sensor: ")
            o.set("lowpass", float(lowpass), "Sensor: ")
            o.set("decimate", int(decimate), "Sensor: ")
            o.set("reconnect", bool(reconnect), "Sensor: ")
            # above 0, as `leptrino --data-timeout` (0 would take every pause for a lost stream)
            o.set("data-timeout", data_timeout_ms, "Sensor: ")
            o.set("gap-periods", float(gap_periods), "Sensor: ")
            o.set("nominal-rate", float(nominal_hz), "Sensor: ")
            if rot is not None:
                o.set("rotation", rot, "Sensor: ")
            if sh is not None:
                o.set("shift", sh, "Sensor: ")
            self._data_timeout_s = data_timeout_ms / 1000  # named by a lost stream's message
            out = be.new_handle("lep_session")
            err = be.new_text(512)
            rc = lib.lep_session_open(o.handle, out, err, 512)
        if rc < 0:
            msg = be.text(err)
            if rc == K.LEP_E_ARG:
                raise ValueError(msg or "bad session options")
            raise error_for(be, rc, msg or str(port or "virtual sensor"), complete=bool(msg))
        self._s = be.handle(out)
        self.port = be.text(lib.lep_session_port(self._s))
        if be.text(err):  # opened, with the virtual sensor's warning (a replay file cut short)
            warnings.warn(be.text(err), RuntimeWarning, stacklevel=2)
        try:
            md = self._md()
            rate_text = self._text(K.LEP_INFO_OUTPUT_RATE)
            rate_hz = int(md[K.LEP_MD_OUTPUT_RATE_HZ])
            self._info = ProductInfo(
                model=self._text(K.LEP_INFO_MODEL), serial=self._text(K.LEP_INFO_SERIAL),
                firmware=self._text(K.LEP_INFO_FIRMWARE), output_rate=rate_text,
                output_rate_hz=rate_hz or None,
                has_output_rate=bool(md[K.LEP_MD_OUTPUT_RATE_FIELD]))
            self._rated = Rated(*md[K.LEP_MD_RATED:K.LEP_MD_RATED + K.LEP_AXES])
            self._nominal_hz = md[K.LEP_MD_NOMINAL_HZ] or float(K.LEP_SESSION_NOMINAL_HZ)
        except BaseException:
            self.close()
            raise
        self._one = _Arrays(be, 1)  # read()'s batch
        self._ev = be.doubles(K.LEP_EVF_COUNT)
        self._offsets = be.doubles(K.LEP_AXES)
        #: events read by tare(wait=True) in a stream of its own (not a recording's)
        self.events: List[SessionEvent] = []
        self._decimate = int(decimate)

    # -- life cycle ----------------------------------------------------------
    def __enter__(self) -> Sensor:
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
        return self._s is None

    @property
    def backend(self) -> str:
        return str(self._be.name)

    def close(self) -> None:
        """Stop a running stream (best effort), release the port, stop the
        session's virtual sensor. Idempotent. Safe from any thread: a call in
        progress in another thread raises StateError and is waited for."""
        if getattr(self, "_s", None) is None:
            return

        def free() -> None:
            if self._s is not None:
                s, self._s = self._s, None
                self._be.lib.lep_session_close(s)

        self._guard.close(free)

    # -- helpers -------------------------------------------------------------
    def _live(self) -> Any:
        if self._guard.closing and self._s is not None:
            raise self._guard.closed_error(self.port)
        if self._s is None:
            raise LeptrinoError(f"{self.port}: the sensor is closed", K.LEP_E_STATE)
        return self._s

    def _client(self) -> Any:
        c = self._be.lib.lep_session_client(self._live())
        if not c:
            raise error_for(self._be, K.LEP_E_DISCONNECTED, f"{self.port}: disconnected")
        return c

    def _check(self, rc: int, command: Optional[int] = None, what: str = "") -> int:
        if rc < 0:
            result = None
            if rc == K.LEP_E_SENSOR and self._s is not None:
                c = self._be.lib.lep_session_client(self._s)
                if c:
                    result = int(self._be.lib.lep_client_last_result(c))
            raise error_for(self._be, rc, what or self.port, result=result, command=command)
        return rc

    @_any_thread
    def _md(self) -> List[float]:
        """The session's metadata numbers (lep_session_metadata; LEP_MD_* index them)."""
        m = self._be.doubles(K.LEP_MD_COUNT)
        self._check(self._be.lib.lep_session_metadata(self._live(), m, K.LEP_MD_COUNT), None,
                    f"{self.port}: metadata")
        return [float(m[i]) for i in range(K.LEP_MD_COUNT)]

    @_any_thread
    def _text(self, which: int) -> str:
        """A text of the session (lep_session_info, LEP_INFO_*), whatever its length."""
        be, s = self._be, self._live()
        return _opts.text_result(be, lambda buf, cap, n: be.lib.lep_session_info(
            s, which, buf, cap, n))

    def _set(self, name: str, value: Any, where: str) -> None:
        """Change a live option of the open session (lep_session_set*, by name)."""
        _opts.set_value(self._be, self._live(), name, value, session=True, where=f"{where}: ")

    def _latency_ms(self) -> int:
        v = self._be.new_scalar("int64_t")
        self._check(self._be.lib.lep_session_get_int(self._live(), b"latency", v))
        return int(self._be.value(v))

    def _set_latency_ms(self, ms: int) -> None:
        """The latency budget (a driving call: from the thread that reads)."""
        self._set("latency", int(ms), "latency")

    def _matrix(self, rotation: Any, degrees: bool, where: str) -> List[float]:
        what = "(roll, pitch, yaw) or a 3x3 rotation matrix"
        shape = np.shape(rotation) if not isinstance(rotation, (str, bytes)) else ()
        if shape == (3,):
            r = A.numbers_of(where, "rotation", rotation, (3,), what)
            if degrees:
                r = [math.radians(x) for x in r]
            out = self._be.doubles(9)
            self._be.lib.lep_rotation_from_rpy(r[0], r[1], r[2], out)
            return [float(out[i]) for i in range(9)]
        m = A.numbers_of(where, "rotation", rotation, (3, 3), what)
        if not A.is_rotation(m):  # the CLI's words (session.c)
            raise ValueError(f"{where}: rotation is not a rotation matrix (R R^T != I)")
        return m

    @staticmethod
    def _vec3(v: Sequence[float], where: str) -> List[float]:
        return A.numbers_of(where, "shift", v, (3,), "(x, y, z) in metres")

    def _lost_words(self, what: str, rc: int) -> str:
        """The message of a read that failed; a lost stream names the option."""
        if rc == K.LEP_E_LOST:
            # the stop that follows (record() makes it, a stream() at its close) waits for a
            # sensor that went quiet: say how long (the library's bound) and what changes it,
            # as `leptrino` does
            wait = float(self._be.lib.lep_session_stop_wait(self._live()))
            return (f"{self.port}: {what}: no data for {self._data_timeout_s:g} s "
                    "(data_timeout=): the stream is lost (reconnect=True waits for the sensor "
                    f"to come back); stopping the sensor's stream waits up to {wait:g} s for an "
                    f"answer (timeout= {self._timeout_ms / 1000:g} s a try, "
                    f"retries= {self._retries} more)")
        return f"{self.port}: {what}"

    def _drain_events(self, first: Optional[int] = None) -> List[SessionEvent]:
        """The queued events, .sample the stream's row (LEP_EVF_SAMPLE); with
        first (the caller's row count before its last read), first plus the
        event's row in that read's batch (LEP_EVF_ROW); one from before the
        caller's first row is at 0."""
        be, ev, s = self._be, self._ev, self._s
        out: List[SessionEvent] = []
        while s is not None and be.lib.lep_session_next_event(s, ev, K.LEP_EVF_COUNT) == 1:
            f = [float(ev[i]) for i in range(K.LEP_EVF_COUNT)]
            typ = int(f[K.LEP_EVF_TYPE])
            out.append(SessionEvent(
                type=EVENT_NAMES.get(typ, str(typ)),
                sample=(int(f[K.LEP_EVF_SAMPLE]) if first is None
                        else max(0, first + int(f[K.LEP_EVF_ROW]))),
                t=f[K.LEP_EVF_T_MONO], t_utc=f[K.LEP_EVF_T_UTC],
                gap_from=f[K.LEP_EVF_GAP_FROM], gap_to=f[K.LEP_EVF_GAP_TO],
                lost=int(f[K.LEP_EVF_LOST]), error=int(f[K.LEP_EVF_ERROR]),
                axes=int(f[K.LEP_EVF_AXES]), status=int(f[K.LEP_EVF_STATUS]),
                tare=cast(Six, tuple(f[K.LEP_EVF_TARE:K.LEP_EVF_TARE + K.LEP_AXES])),
                wrench=cast(Six, tuple(f[K.LEP_EVF_WRENCH:K.LEP_EVF_WRENCH + K.LEP_AXES])),
            ))
        return out

    # -- batches and events, for a program with its own reading loop ---------
    def sample_buffer(self, capacity: int = 256) -> SampleBuffer:
        """Arrays for read_batch(): up to capacity samples, every column of
        lep_session_read (t_mono, t_utc, si, raw, zeroed, status, flags, seq)."""
        return SampleBuffer(self._be, A.whole("sample_buffer", "capacity", capacity, 1, 1 << 20))

    @_driving
    def read_batch(self, buffer: SampleBuffer, timeout: float) -> int:
        """Read what the session has, up to buffer.cap samples, into buffer's
        arrays (rows [0, buffer.n)), waiting at most timeout s for the first.

        Returns the session's status without raising for it: 0 (samples or
        not), or a negative LEP_E_* code: LEP_E_TIMEOUT (nothing came),
        LEP_E_END (the stream ended), another error while the session
        reconnects (status_text() says it). LeptrinoError when the sensor is
        closed."""
        return buffer.read(self._live(), max(0, int(timeout * 1000)), buffer.cap)

    @property
    def latency(self) -> float:
        """How long the library may hold samples back to save wake-ups (s);
        settable by the thread that reads (0 .. 1 s, as Sensor(latency=))."""
        return self._latency_ms() / 1000.0

    @latency.setter
    def latency(self, seconds: float) -> None:
        self._set_latency_ms(_ms(seconds, "latency"))

    @_any_thread
    def take_events(self) -> List[SessionEvent]:
        """The session's events queued since the last call (gaps, reconnects,
        tare done, limits...), .sample the stream's row it comes before (counted
        from the start; 0 for one queued while stopped)."""
        return self._drain_events()

    def status_text(self, rc: int) -> str:
        """The library's text for a status code (read_batch's)."""
        return str(self._be.text(self._be.lib.lep_strerror(int(rc))))

    # -- what the sensor is --------------------------------------------------
    @property
    def product_info(self) -> ProductInfo:
        """Model, serial, firmware, output rate (read when the sensor was opened)."""
        return self._info

    @property
    def rated(self) -> Rated:
        """Rated (full-scale) values, N and N·m (read when the sensor was opened)."""
        return self._rated

    @property
    def metadata(self) -> Dict[str, Any]:
        """What a recording says about itself: model, serial, firmware, protocol,
        rated values, filters, tare, frame, start time (UTC), library version.
        The library's own JSON object (lep_session_info, LEP_INFO_METADATA_JSON), as
        a dict."""
        return dict(json.loads(self.metadata_json()))

    @_any_thread
    def metadata_json(self) -> str:
        """The metadata as the library writes it (one JSON object)."""
        return self._text(K.LEP_INFO_METADATA_JSON)

    @property
    @_any_thread
    def health(self) -> Health:
        """Measured against nominal rate, samples lost, gaps, errors, overloads,
        reconnects, since the stream started (lep_session_health, by field name)."""
        be = self._be
        names = _health_names(be)
        h = be.doubles(max(1, len(names)))
        self._check(be.lib.lep_session_health(self._live(), h, len(names)), None,
                    f"{self.port}: health")
        return Health.from_fields({k: float(h[i]) for i, k in enumerate(names)})

    @property
    @_driving
    def stats(self) -> ClientStats:
        """The current connection's client counters (messages, BCC errors, NAKs, ...)."""
        st = self._be.new("lep_client_stats")
        self._be.lib.lep_client_get_stats(self._client(), st)
        return ClientStats.from_c(st)

    @property
    @_any_thread
    def streaming(self) -> bool:
        return bool(self._be.lib.lep_session_streaming(self._live()))

    @property
    @_driving
    def filter(self) -> int:
        """The sensor's digital filter code in effect (0 off, 1..3; see filter_label)."""
        code = self._be.new_scalar("uint8_t")
        self._check(self._be.lib.lep_client_filter_get(self._client(), code),
                    K.LEP_CMD_FILTER_GET)
        return int(self._be.value(code))

    @filter.setter
    @_driving
    def filter(self, code: int) -> None:
        code = A.whole("filter", "code", code, 0, K.LEP_FILTER_MAX)
        self._check(self._be.lib.lep_client_filter_set(self._client(), int(code)),
                    K.LEP_CMD_FILTER_SET)
        warnings.warn(
            f"filter {int(code)} stored; it takes effect only after the sensor is "
            "power-cycled (switched off and on)",
            PowerCycleWarning,
            stacklevel=2,
        )

    @_driving
    def filter_label(self, code: Optional[int] = None) -> str:
        """The spec's label of a filter code ("off", "10 Hz", ...); models differ."""
        if code is None:
            code = self.filter
        code = A.whole("filter_label", "code", code, 0, 255)
        return str(self._be.text(self._be.lib.lep_filter_label(int(code) & 0xFF)))

    # -- processing ----------------------------------------------------------
    @_any_thread
    def tare(self, n: int = 100, seconds: Optional[float] = None,
             wait: Optional[bool] = None) -> Optional[Tuple[float, ...]]:
        """Zero on the mean raw counts of the next n samples (1 .. 1000000, as
        `leptrino --tare N`), or of seconds (> 0) when given.

        While streaming the tare runs beside the stream (nothing stalls; the
        samples it averages carry the taring flag) and this returns None at
        once. Otherwise (or with wait=True) it starts the stream, waits for the
        tare to finish, stops the stream again and returns the offsets in
        counts. untare() removes a tare (n=0 is a ValueError, not an untare)."""
        if seconds is None:
            n = A.whole("tare", "n", n, 1, 1000000)
        else:
            seconds = A.number("tare", "seconds", seconds, 0.0, 3600.0, lo_exclusive=True)
        wait = A.optional_flag("tare", "wait", wait)
        s = self._live()
        lib = self._be.lib
        self._check(lib.lep_session_tare(s, 0 if seconds is not None else int(n),
                                         float(seconds or 0.0)), None, f"{self.port}: tare")
        streaming = bool(lib.lep_session_streaming(s))
        if wait is None:
            wait = not streaming
        if not wait:
            return None
        self._guard.hold(self.port)  # reads the stream: the driving thread's part
        started = False
        try:
            if not streaming:
                self.start()
                started = True
            arrays = _Arrays(self._be, _ITER_BATCH)
            while lib.lep_session_taring(s):
                rc = arrays.read(s, self._timeout_ms, _ITER_BATCH)
                self._guard.check(self.port)
                if rc < 0 and rc != K.LEP_E_END:
                    self._check(rc, None, f"{self.port}: tare")
                self.events += self._drain_events()
        finally:
            try:
                if started and self._s is not None:
                    lib.lep_session_stop(self._s)
            finally:
                self._guard.release()
        return self.tare_offsets

    @_any_thread
    def untare(self) -> None:
        """Remove the tare (offsets zero); cancels a tare in progress."""
        self._check(self._be.lib.lep_session_untare(self._live()))

    @property
    @_any_thread
    def tare_offsets(self) -> Tuple[float, ...]:
        """The tare offsets in raw counts (zeros when not tared); settable."""
        self._be.lib.lep_session_get_tare(self._live(), self._offsets)
        return tuple(float(self._offsets[i]) for i in range(K.LEP_AXES))

    @tare_offsets.setter
    @_any_thread
    def tare_offsets(self, counts: Sequence[float]) -> None:
        a = A.numbers_of("tare_offsets", "counts", counts, (K.LEP_AXES,), "six numbers (counts)")
        buf = self._be.doubles(K.LEP_AXES)
        for i in range(K.LEP_AXES):
            buf[i] = a[i]
        self._check(self._be.lib.lep_session_set_tare(self._live(), buf))

    @property
    @_any_thread
    def tared(self) -> bool:
        return bool(self._be.lib.lep_session_get_tare(self._live(), self._offsets))

    @property
    @_any_thread
    def taring(self) -> bool:
        """True while a tare is averaging."""
        return bool(self._be.lib.lep_session_taring(self._live()))

    @property
    @_any_thread
    def lowpass(self) -> float:
        """Host low-pass cut-off in Hz (0 off); settable at any time."""
        return self._md()[K.LEP_MD_LOWPASS_HZ]

    @lowpass.setter
    @_any_thread
    def lowpass(self, cutoff_hz: float) -> None:
        top = 0.45 * self._nominal_hz
        if A.number("lowpass", "cutoff_hz", cutoff_hz, 0.0, math.inf) > top:
            raise ValueError(f"lowpass: cutoff_hz: {cutoff_hz!r} is out of range (from 0 .. "
                             f"{top:g}: a low-pass cut-off is at most 0.45 x the "
                             f"{self._nominal_hz:g} Hz output rate)")
        self._set("lowpass", float(cutoff_hz), "lowpass")

    @property
    @_any_thread
    def rotation(self) -> np.ndarray:
        """The output frame's rotation matrix (3x3)."""
        m = self._md()
        return np.array(m[K.LEP_MD_ROTATION:K.LEP_MD_ROTATION + 9]).reshape(3, 3)

    @property
    @_any_thread
    def shift(self) -> Tuple[float, float, float]:
        """The moment reference point (x, y, z), metres, in the output frame."""
        m = self._md()
        return (m[K.LEP_MD_SHIFT_M], m[K.LEP_MD_SHIFT_M + 1], m[K.LEP_MD_SHIFT_M + 2])

    @_any_thread
    def set_frame(self, rotation: Optional[Sequence[Any]] = None,
                  shift: Optional[Sequence[float]] = None, *, degrees: bool = True) -> None:
        """Output in another frame: rotation as (roll, pitch, yaw) in degrees
        (as `leptrino --rotate`; degrees=False: radians) or a 3x3 matrix (None:
        identity), shift the moment reference point (metres, None: origin).
        Takes effect from the next sample."""
        degrees = A.flag("set_frame", "degrees", degrees)
        m = self._matrix(rotation if rotation is not None else np.eye(3), degrees, "set_frame")
        v = self._vec3(shift if shift is not None else (0.0, 0.0, 0.0), "set_frame")
        self._set("rotation", m, "set_frame")
        self._set("shift", v, "set_frame")

    # -- payload and limits (leptrino/payload.h; docs/session.md) ------------
    @_any_thread
    def set_payload(self, payload: Optional[Any]) -> None:
        """Remove a tool's gravity wrench from the SI values (raw and zeroed
        counts stay as measured): a leptrino.Payload (its mass and centre of
        mass), (mass kg, cx, cy, cz m, sensor frame), or None for none. A tare
        taken while a payload is set removes the bias only. ValueError for a
        negative mass, non-finite values or not four numbers, TypeError for
        the wrong kind (leptrino/_args.py). Takes effect from the next sample."""
        v = [0.0, 0.0, 0.0, 0.0]
        if payload is not None:
            if isinstance(payload, Payload):
                payload = tuple(payload)
            v = A.numbers_of("set_payload", "payload", payload, (4,),
                             "(mass kg, cx, cy, cz m)")
            if v[0] < 0:
                raise ValueError(f"set_payload: payload: the mass {v[0]:g} kg is negative")
        self._set("payload", v, "set_payload")

    @_any_thread
    def set_gravity(self, gravity: Sequence[float]) -> None:
        """Gravity in the sensor frame, m/s² ((0, 0, -9.80665) when the z axis
        points up); call it as often as the robot moves. ValueError when not
        three finite numbers, TypeError for the wrong kind."""
        a = A.numbers_of("set_gravity", "gravity", gravity, (3,), "(gx, gy, gz) in m/s²")
        self._set("gravity", a, "set_gravity")

    @_any_thread
    def set_limits(self, limits: Optional[Any] = None, **axes: float) -> None:
        """Limits on the SI values (compensated, output frame), N and N·m:
        set_limits(fz=50, mz=2), a dict of the same, six numbers (fx..mz, 0 =
        none), or None to remove them. Beyond a limit a sample is flagged
        (LEP_SF_LIMIT) and limit_exceeded / limit_cleared events come with the
        data. ValueError for a negative or non-finite limit or an unknown axis,
        TypeError for a limit that is not a number."""
        names = ("fx", "fy", "fz", "mx", "my", "mz")
        v = [0.0] * K.LEP_AXES
        given: Dict[str, float] = dict(axes)
        if isinstance(limits, Mapping):
            given.update(limits)
        elif limits is not None:
            v = A.numbers_of("set_limits", "limits", limits, (K.LEP_AXES,),
                             "six limits (fx .. mz, N and N·m, 0: none)")
        for name, value in given.items():
            if name not in names:
                raise ValueError(f"set_limits: unknown axis {name!r} (one of {', '.join(names)})")
            v[names.index(name)] = A.number("set_limits", name, value, 0.0, math.inf)
        for name, value in zip(names, v):
            A.number("set_limits", name, value, 0.0, math.inf)  # six numbers: each >= 0
        self._set("limit", v, "set_limits")

    # -- data ----------------------------------------------------------------
    @_driving
    def read(self) -> Sample:
        """One sample in handshake mode (command 0x30), outside the stream,
        through the session (lep_session_read_one): zeroed and SI values with
        the tare and the frame in force (the low-pass and decimation are the
        stream's). StateError while streaming."""
        a = self._one
        self._check(self._be.lib.lep_session_read_one(self._live(), *a.pointers(0)),
                    K.LEP_CMD_SAMPLE)
        return a.samples(1)[0]

    @_driving
    def start(self) -> None:
        """Start the stream (stream(), record() and tare() do it themselves)."""
        self._check(self._be.lib.lep_session_start(self._live()), K.LEP_CMD_START)

    @_driving
    def stop(self) -> None:
        """Stop the stream; samples received and not yet read are dropped."""
        self._check(self._be.lib.lep_session_stop(self._live()), K.LEP_CMD_STOP)

    def stream(self, count: Optional[int] = None, seconds: Optional[float] = None) -> Stream:
        """The stream as a context manager and iterator of Samples (read in
        batches underneath). Starts the stream if needed and stops it on exit
        (or when count samples / seconds are done) when it started it.

            with sensor.stream() as samples:
                for s in samples: ...
        """
        if count is not None:
            count = A.whole("stream", "count", count, 0, 2**63 - 1)
        if seconds is not None:
            seconds = A.number("stream", "seconds", seconds, 0.0, 1e9, lo_exclusive=True)
        return Stream(self, count, seconds)

    @_driving
    def record(self, seconds: Optional[float] = None, count: Optional[int] = None) -> Recording:
        """Record seconds of the stream, or count samples, into numpy arrays.

        The session fills the arrays in C (no per-sample Python work). Starts
        the stream if it is not running and stops it again after. The result
        carries the events (gaps, tare, overload...) and the metadata. On an
        error (TimeoutError, DisconnectedError...) and on an interruption
        (KeyboardInterrupt, an exception from a signal handler) the exception's
        .recording holds what was recorded until then."""
        if (seconds is None) == (count is None):
            raise ValueError("record: give exactly one of seconds= or count=")
        if seconds is not None:
            seconds = A.number("record", "seconds", seconds, 0.0, 1e6, lo_exclusive=True)
        if count is not None:
            count = A.whole("record", "count", count, 1, 10**9)
        be, lib = self._be, self._be.lib
        s = self._live()
        rate = self._nominal_hz / self._decimate
        if count is not None:
            cap = int(count)
        else:
            assert seconds is not None
            cap = int(seconds * rate * 1.05) + 64
        arrays = _Arrays(be, cap)
        events: List[SessionEvent] = []
        started = False
        if not lib.lep_session_streaming(s):
            self.start()
            started = True
        latency_before = self._latency_ms()
        if latency_before < _RECORD_LATENCY_MS:
            self._set_latency_ms(_RECORD_LATENCY_MS)
        try:
            now = float(lib.lep_monotonic_seconds())
            # seconds count from the first row's arrival, as `leptrino stream
            # --duration` (the session's duration_s) does: a tare's samples
            # before it are not part of the recording's time
            end = math.inf
            final_reads = 0
            while True:
                n = arrays.n
                if count is not None:
                    room = int(count) - n
                    if room <= 0:
                        break
                    wait_s = min(_RECORD_SLICE_S, self._timeout_ms / 1000)
                else:
                    assert seconds is not None
                    left = end - now if n > 0 else seconds
                    if left <= 0:
                        # Time is up, but the latency budget may still hold
                        # samples that arrived before the end: take them with
                        # reads that do not wait, up to the first one after it.
                        if n > 0 and arrays.t_mono[n - 1] >= end:
                            break
                        if final_reads >= _RECORD_FINAL_READS:
                            break
                        if final_reads == 0:
                            self._set_latency_ms(0)
                        final_reads += 1
                    room = max(64, int(math.ceil(max(left, 0.0) * rate)))
                    wait_s = min(_RECORD_SLICE_S, max(left, 0.001), self._timeout_ms / 1000)
                arrays.reserve(n + room)
                rc = arrays.read(s, max(1, int(wait_s * 1000)), room, at=n)
                self._guard.check(self.port)
                if seconds is not None and n == 0 and arrays.n > 0:
                    end = float(arrays.t_mono[0]) + seconds
                events += self._drain_events(n)  # .sample: rows of the recording
                now = float(lib.lep_monotonic_seconds())
                if rc == K.LEP_E_END:
                    break
                if rc == K.LEP_E_TIMEOUT:
                    continue  # nothing in this slice of the wait (a lost stream: LEP_E_LOST)
                if rc < 0:
                    exc = error_for(be, rc, self._lost_words("recording", rc),
                                    complete=rc == K.LEP_E_LOST)
                    # an exception of any kind carries what was recorded (documented)
                    exc.recording = arrays.result(events, self)  # type: ignore[attr-defined]
                    raise exc
        except BaseException as exc:
            # Ctrl-C lands between two reads: keep what was received.
            if not hasattr(exc, "recording"):
                try:  # (as above)
                    exc.recording = arrays.result(events, self)  # type: ignore[attr-defined]
                except Exception:
                    pass
            raise
        finally:
            if self._s is not None:
                try:  # the session's own budget back (refused once close() has begun)
                    _opts.set_value(be, self._s, "latency", latency_before, session=True)
                except (LeptrinoError, ValueError):
                    pass
            if started and self._s is not None:
                try:
                    lib.lep_session_stop(self._s)
                except Exception:
                    pass
        return arrays.result(events, self)


class SampleBuffer:
    """numpy arrays that lep_session_read fills directly (every column);
    Sensor.sample_buffer() makes one, Sensor.read_batch() fills it: n rows."""

    t_mono: np.ndarray
    t_utc: np.ndarray
    raw: np.ndarray
    zeroed: np.ndarray
    si: np.ndarray
    status: np.ndarray
    flags: np.ndarray
    seq: np.ndarray

    #: column -> (dtype, C element type), in lep_session_read's order
    COLUMNS = (("t_mono", np.float64, "double"), ("t_utc", np.float64, "double"),
               ("si", np.float64, "double"), ("raw", np.int16, "int16_t"),
               ("zeroed", np.float64, "double"), ("status", np.uint8, "uint8_t"),
               ("flags", np.uint8, "uint8_t"), ("seq", np.uint16, "uint16_t"))

    def __init__(self, be: Any, cap: int) -> None:
        self.be = be
        self.lib = be.lib
        self.cap = 0
        #: rows filled (by read(): at + what the last read wrote)
        self.n = 0
        self._got = be.new_scalar("size_t")
        self._p0: Tuple[Any, ...] = ()
        self._alloc(max(1, cap), 0)

    def _alloc(self, cap: int, keep: int) -> None:
        for k, dt, _ in self.COLUMNS:
            shape = (cap, K.LEP_AXES) if k in ("si", "raw", "zeroed") else (cap,)
            a = np.empty(shape, dt)
            if keep:
                a[:keep] = getattr(self, k)[:keep]
            setattr(self, k, a)
        self.cap = cap
        self.n = keep
        self._p0 = self.pointers(0)

    def pointers(self, at: int) -> Tuple[Any, ...]:
        """The eight column pointers at row at, in lep_session_read's order."""
        if at == 0 and self._p0:
            return self._p0
        be = self.be
        return tuple(be.array_ptr(getattr(self, k)[at:], ct) for k, _, ct in self.COLUMNS)

    def read(self, s: Any, timeout_ms: int, room: int, at: int = 0) -> int:
        """lep_session_read of up to room samples into rows [at, at + room)
        (room clipped to the arrays); self.n becomes at + the samples written."""
        room = max(0, min(room, self.cap - at))
        rc = int(self.lib.lep_session_read(s, int(timeout_ms), room, self._got,
                                           *self.pointers(at)))
        self.n = at + int(self.be.value(self._got))
        return rc

    def samples(self, n: int) -> List[Sample]:
        """The first n rows as Samples."""
        return list(map(Sample, self.t_mono[:n].tolist(), self.t_utc[:n].tolist(),
                        list(map(tuple, self.si[:n].tolist())),
                        list(map(tuple, self.raw[:n].tolist())),
                        list(map(tuple, self.zeroed[:n].tolist())), self.status[:n].tolist(),
                        self.flags[:n].tolist(), self.seq[:n].tolist()))

    def reserve(self, cap: int) -> None:
        if cap > self.cap:
            self._alloc(max(cap, 2 * self.cap), self.n)

    def result(self, events: List[SessionEvent], sensor: Optional[Sensor]) -> Recording:
        n = self.n
        meta, start = "{}", 0.0
        if sensor is not None and not sensor.closed:
            try:
                meta = sensor.metadata_json()
                start = sensor._md()[K.LEP_MD_START_MONO]
            except LeptrinoError:
                pass
        return Recording(
            t=self.t_mono[:n].copy(), si=self.si[:n].copy(), raw=self.raw[:n].copy(),
            status=self.status[:n].copy(), seq=self.seq[:n].copy(),
            t_utc=self.t_utc[:n].copy(), zeroed=self.zeroed[:n].copy(),
            flags=self.flags[:n].copy(), events=list(events), metadata_json=meta,
            start_mono=start,
        )


_Arrays = SampleBuffer  # the name inside this module


class Stream:
    """Iterator of stream samples, read from the session in batches; a
    context manager that stops the stream on exit when it started it.
    .events collects the session's events (gaps, tare, overload...)."""

    def __init__(self, sensor: Sensor, count: Optional[int], seconds: Optional[float]) -> None:
        if count is not None and int(count) < 0:
            raise ValueError("count must be >= 0")
        self._sensor = sensor
        self._count = count
        self._seconds = seconds
        self._open = False
        self._started = False
        self._n = 0
        self._end: Optional[float] = None
        self._arrays = _Arrays(sensor._be, _ITER_BATCH)
        self._pending: Iterator[Sample] = iter(())
        self._rows = 0  # read by this iterator: its events' .sample count from its start
        self.events: List[SessionEvent] = []

    def __enter__(self) -> Stream:
        self._begin()
        return self

    def __exit__(self, *exc: Any) -> None:
        if exc[0] is None:
            self.close()
            return
        try:
            self.close()
        except LeptrinoError:
            pass  # the error that ended the iteration (a lost stream) is the one to see

    def _begin(self) -> None:
        if self._open:
            return
        s = self._sensor
        lib = s._be.lib
        s._guard.hold(s.port)  # the iterator's thread drives the sensor until close()
        try:
            if not lib.lep_session_streaming(s._live()):
                s.start()
                self._started = True
        except BaseException:
            s._guard.release()
            raise
        self._open = True

    def close(self) -> None:
        """Stop the stream if this iterator started it (best effort when the port is gone)."""
        if self._open:
            self._open = False
            s = self._sensor
            try:
                if self._started and not s.closed and not s._guard.closing and s.streaming:
                    self._started = False
                    s.stop()
            finally:
                s._guard.release()

    def __iter__(self) -> Iterator[Sample]:
        self._begin()
        return self

    def __next__(self) -> Sample:
        if not self._open:
            raise StopIteration
        if self._count is not None and self._n >= self._count:
            self.close()  # done: do not leave the sensor streaming until collected
            raise StopIteration
        try:
            sample = next(self._pending)
        except StopIteration:
            sample = self._fill()
        if self._seconds is not None:
            # seconds from the first sample's arrival (the session's duration_s rule)
            if self._end is None:
                self._end = sample.t + self._seconds
            elif sample.t >= self._end:
                self.close()
                raise StopIteration
        self._n += 1
        return sample

    def _fill(self) -> Sample:
        with self._sensor._guard.drive(self._sensor.port):
            return self._fill_held()

    def _fill_held(self) -> Sample:
        s = self._sensor
        lib = s._be.lib
        a = self._arrays
        room = _ITER_BATCH
        if self._count is not None:
            room = max(1, min(room, self._count - self._n))
        while True:
            wait = s._timeout_ms
            left = math.inf
            if self._end is not None:
                left = self._end - float(lib.lep_monotonic_seconds())
                wait = max(1, min(wait, int(math.ceil(left * 1000))))
            rc = a.read(s._live(), wait, room)
            s._guard.check(s.port)
            if a.n == 0 and left <= 0:
                self.close()  # past the end and nothing more arrived before it
                raise StopIteration
            self.events += s._drain_events(self._rows)
            self._rows += a.n
            if a.n:
                break
            if rc == K.LEP_E_END:
                self.close()
                raise StopIteration
            if rc == K.LEP_E_TIMEOUT:
                continue  # nothing in this wait (a lost stream is LEP_E_LOST)
            if rc < 0:
                if rc == K.LEP_E_LOST:
                    raise error_for(s._be, rc, s._lost_words("stream", rc), complete=True)
                s._check(rc, None, f"{s.port}: waiting for stream data")
        self._pending = iter(a.samples(a.n))
        return next(self._pending)

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
    lib = be.lib
    out = be.new_handle("lep_port_list")
    rc = lib.lep_port_list_new(out)
    if rc < 0:
        raise error_for(be, rc, "listing serial ports")
    lst = be.handle(out)
    try:
        return [PortInfo(path=be.text(lib.lep_port_list_path(lst, i)),
                         by_id=be.text(lib.lep_port_list_by_id(lst, i)),
                         description=be.text(lib.lep_port_list_description(lst, i)),
                         vid=int(lib.lep_port_list_vid(lst, i)),
                         pid=int(lib.lep_port_list_pid(lst, i)),
                         likely_sensor=bool(lib.lep_port_list_likely_sensor(lst, i)))
                for i in range(int(lib.lep_port_list_count(lst)))]
    finally:
        lib.lep_port_list_free(lst)
