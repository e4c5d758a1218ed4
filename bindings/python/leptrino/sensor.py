"""A sensor through the library's host session: leptrino.Sensor.

Everything a session does (start-up recovery, tare, host low-pass,
decimation, rotation, gap detection, reconnect, health, metadata) runs in C
(leptrino/session.h); this module moves its batches into numpy arrays and
turns its structs into Python values.

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
from ._backend import get_backend
from ._guard import Guard
from .errors import LeptrinoError, error_for
from .payload import Payload
from .values import (
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
    def wrap(self: "Sensor", *a: Any, **k: Any) -> Any:
        with self._guard.drive(self.port):
            return fn(self, *a, **k)
    return cast(_F, wrap)


def _any_thread(fn: _F) -> _F:
    """A call any thread may make (close() waits for it)."""
    @functools.wraps(fn)
    def wrap(self: "Sensor", *a: Any, **k: Any) -> Any:
        with self._guard.call(self.port):
            return fn(self, *a, **k)
    return cast(_F, wrap)


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
        o = be.new("lep_session_options")
        lib.lep_session_options_init(o)
        keep: List[Any] = []
        if port is not None and not isinstance(port, str):
            port = getattr(port, "port", port)  # a Simulator
        if (port is None) == (sim is None or sim is False):
            raise ValueError("give a port, or sim=True / sim={options}, not both")
        if port is not None:
            o.port = be.cstr(str(port), keep)
        else:
            from .simulator import fill_options

            o.use_sim = True
            fill_options(be, be.field_ptr(o, "sim"), dict(sim) if isinstance(sim, Mapping)
                         else {})
        o.timeout_ms = self._timeout_ms
        o.sync_quiet_ms = max(1, _ms(quiet, "quiet"))
        o.latency_ms = _ms(latency, "latency")
        o.tare_samples = int(tare)
        o.lowpass_hz = float(lowpass)
        o.decimate = int(decimate)
        o.reconnect = bool(reconnect)
        # above 0, as `leptrino --data-timeout` (0 would take every pause for a lost stream)
        o.data_timeout_ms = max(1, _ms(data_timeout, "data_timeout", lo_exclusive=True))
        self._data_timeout_s = o.data_timeout_ms / 1000  # named by a lost stream's message
        o.gap_periods = float(gap_periods)
        o.nominal_hz = float(nominal_hz)
        if rot is not None:
            for i, v in enumerate(rot):
                o.rotation[i] = v
        if sh is not None:
            for i, v in enumerate(sh):
                o.shift_m[i] = v
        out = be.new_handle("lep_session")
        err = be.new_text(512)
        rc = lib.lep_session_open(o, out, err, 512)
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
            client = lib.lep_session_client(self._s)
            self._check(lib.lep_client_set_retries(client, retries))
            meta = self._metadata_struct()
            self._info = product_info_from(be, meta.info)
            self._rated = Rated(*(float(v) for v in meta.rated.axis))
            self._nominal_hz = float(meta.nominal_hz) or 1200.0
        except BaseException:
            self.close()
            raise
        self._one = _Arrays(be, 1)  # read()'s batch
        self._ev = be.new("lep_session_event")
        self._offsets = be.doubles(K.LEP_AXES)
        #: events read by tare(wait=True) in a stream of its own (not a recording's)
        self.events: List[SessionEvent] = []
        self._start_mono = 0.0
        self._delivered = 0
        self._decimate = int(decimate)

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
    def _metadata_struct(self) -> Any:
        m = self._be.new("lep_session_metadata")
        self._be.lib.lep_session_get_metadata(self._live(), m)
        return m

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
            # sensor that went quiet: say how long and what changes it, as `leptrino` does
            tries = self._retries + 1
            return (f"{self.port}: {what}: no data for {self._data_timeout_s:g} s "
                    "(data_timeout=): the stream is lost (reconnect=True waits for the sensor "
                    f"to come back); stopping the sensor's stream waits up to "
                    f"{tries * self._timeout_ms / 1000:g} s for an answer "
                    f"(timeout= {self._timeout_ms / 1000:g} s a try, {tries} tries: retries=)")
        return f"{self.port}: {what}"

    def _drain_events(self, base: int = 0) -> List[SessionEvent]:
        """The queued events, .sample counted from the stream's sample base."""
        be, ev, s = self._be, self._ev, self._s
        out: List[SessionEvent] = []
        while s is not None and be.lib.lep_session_next_event(s, ev):
            out.append(SessionEvent(
                type=EVENT_NAMES.get(int(ev.type), str(int(ev.type))),
                # queued before this stream started (an untare while stopped): at its start
                sample=(max(0, int(ev.sample) - base) if float(ev.t_mono) >= self._start_mono
                        else 0),
                t=float(ev.t_mono), t_utc=float(ev.t_utc),
                gap_from=float(ev.gap_from), gap_to=float(ev.gap_to), lost=int(ev.lost),
                error=int(ev.error), axes=int(ev.axes), status=int(ev.status),
                tare=tuple(float(ev.tare[i]) for i in range(K.LEP_AXES)),  # type: ignore[arg-type]
                wrench=tuple(float(ev.wrench[i])  # type: ignore[arg-type]
                             for i in range(K.LEP_AXES)),
            ))
        return out

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
        The library's own JSON object (lep_session_metadata_json), as a dict."""
        return dict(json.loads(self.metadata_json()))

    @_any_thread
    def metadata_json(self) -> str:
        """The metadata as the library writes it (one JSON object)."""
        be = self._be
        cap = 4096
        while True:
            buf = be.new_text(cap)
            n = be.new_scalar("size_t")
            rc = be.lib.lep_session_metadata_json(self._live(), buf, cap, n)
            if rc == K.LEP_E_BUFFER and cap < 1 << 20:
                cap *= 4
                continue
            self._check(rc, None, f"{self.port}: metadata")
            return str(be.bytes_at(buf, int(be.value(n))).decode("utf-8"))

    @property
    @_any_thread
    def health(self) -> Health:
        """Measured against nominal rate, samples lost, gaps, errors, overloads,
        reconnects, since the stream started."""
        be = self._be
        h = be.new("lep_session_health")
        be.lib.lep_session_get_health(self._live(), h)
        return Health.from_c(h)

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
                arrays.c.n = 0
                rc = lib.lep_session_read(s, arrays.c, self._timeout_ms)
                self._guard.check(self.port)
                self._delivered += arrays.n
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
        return float(self._metadata_struct().lowpass_hz)

    @lowpass.setter
    @_any_thread
    def lowpass(self, cutoff_hz: float) -> None:
        top = 0.45 * self._nominal_hz
        if A.number("lowpass", "cutoff_hz", cutoff_hz, 0.0, math.inf) > top:
            raise ValueError(f"lowpass: cutoff_hz: {cutoff_hz!r} is out of range (from 0 .. "
                             f"{top:g}: a low-pass cut-off is at most 0.45 x the "
                             f"{self._nominal_hz:g} Hz output rate)")
        rc = self._be.lib.lep_session_set_lowpass(self._live(), float(cutoff_hz))
        if rc == K.LEP_E_VALUE:
            raise ValueError(f"low-pass cut-off {cutoff_hz!r} Hz: must be >= 0 and at most "
                             f"0.45 x the rate ({0.45 * self._nominal_hz:g} Hz)")
        self._check(rc)

    @property
    @_any_thread
    def rotation(self) -> np.ndarray:
        """The output frame's rotation matrix (3x3)."""
        m = self._metadata_struct()
        return np.array([float(m.rotation[i]) for i in range(9)]).reshape(3, 3)

    @property
    @_any_thread
    def shift(self) -> Tuple[float, float, float]:
        """The moment reference point (x, y, z), metres, in the output frame."""
        m = self._metadata_struct()
        return (float(m.shift_m[0]), float(m.shift_m[1]), float(m.shift_m[2]))

    @_any_thread
    def set_frame(self, rotation: Optional[Sequence[Any]] = None,
                  shift: Optional[Sequence[float]] = None, *, degrees: bool = True) -> None:
        """Output in another frame: rotation as (roll, pitch, yaw) in degrees
        (as `leptrino --rotate`; degrees=False: radians) or a 3x3 matrix (None:
        identity), shift the moment reference point (metres, None: origin).
        Takes effect from the next sample."""
        be = self._be
        degrees = A.flag("set_frame", "degrees", degrees)
        m = self._matrix(rotation if rotation is not None else np.eye(3), degrees, "set_frame")
        v = self._vec3(shift if shift is not None else (0.0, 0.0, 0.0), "set_frame")
        r = be.doubles(9)
        for i, x in enumerate(m):
            r[i] = x
        sh = be.doubles(3)
        for i, x in enumerate(v):
            sh[i] = x
        self._check(be.lib.lep_session_set_rotation(self._live(), r, sh))

    # -- payload and limits (leptrino/payload.h; docs/session.md) ------------
    @_any_thread
    def set_payload(self, payload: Optional[Any]) -> None:
        """Remove a tool's gravity wrench from the SI values (raw and zeroed
        counts stay as measured): a leptrino.Payload (its mass and centre of
        mass), (mass kg, cx, cy, cz m, sensor frame), or None for none. A tare
        taken while a payload is set removes the bias only. ValueError for a
        negative mass, non-finite values or not four numbers, TypeError for
        the wrong kind (leptrino/_args.py). Takes effect from the next sample."""
        be = self._be
        c = be.new("lep_payload")
        if payload is not None:
            if isinstance(payload, Payload):
                payload = tuple(payload)
            v = A.numbers_of("set_payload", "payload", payload, (4,),
                             "(mass kg, cx, cy, cz m)")
            if v[0] < 0:
                raise ValueError(f"set_payload: payload: the mass {v[0]:g} kg is negative")
            c.mass_kg = v[0]
            for i in range(3):
                c.com_m[i] = v[1 + i]
        if be.lib.lep_session_set_payload(self._live(), c) < 0:
            raise ValueError(f"payload {payload!r}: a mass >= 0 and finite numbers expected")

    @_any_thread
    def set_gravity(self, gravity: Sequence[float]) -> None:
        """Gravity in the sensor frame, m/s² ((0, 0, -9.80665) when the z axis
        points up); call it as often as the robot moves. ValueError when not
        three finite numbers, TypeError for the wrong kind."""
        be = self._be
        a = A.numbers_of("set_gravity", "gravity", gravity, (3,), "(gx, gy, gz) in m/s²")
        g = be.doubles(3)
        for i in range(3):
            g[i] = a[i]
        if be.lib.lep_session_set_gravity(self._live(), g) < 0:
            raise ValueError(f"gravity {gravity!r}: three finite numbers expected")

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
        be = self._be
        c = be.doubles(K.LEP_AXES)
        for i in range(K.LEP_AXES):
            c[i] = v[i]
        if be.lib.lep_session_set_limits(self._live(), c) < 0:
            raise ValueError(f"limits {v}: each must be 0 (none) or > 0, finite")

    # -- data ----------------------------------------------------------------
    @_driving
    def read(self) -> Sample:
        """One sample in handshake mode (command 0x30), outside the stream,
        through the session (lep_session_read_one): zeroed and SI values with
        the tare and the frame in force (the low-pass and decimation are the
        stream's). StateError while streaming."""
        a = self._one
        a.c.n = 0
        a.c.cap = 1
        self._check(self._be.lib.lep_session_read_one(self._live(), a.c), K.LEP_CMD_SAMPLE)
        return a.samples(1)[0]

    @_driving
    def start(self) -> None:
        """Start the stream (stream(), record() and tare() do it themselves)."""
        self._check(self._be.lib.lep_session_start(self._live()), K.LEP_CMD_START)
        self._delivered = 0  # samples read since the start: the events' .sample base
        self._start_mono = float(self._metadata_struct().start_mono)

    @_driving
    def stop(self) -> None:
        """Stop the stream; samples received and not yet read are dropped."""
        self._check(self._be.lib.lep_session_stop(self._live()), K.LEP_CMD_STOP)

    def stream(self, count: Optional[int] = None, seconds: Optional[float] = None) -> "Stream":
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
        base = self._delivered
        latency_before = int(lib.lep_session_latency(s))
        if latency_before < _RECORD_LATENCY_MS:
            lib.lep_session_set_latency(s, _RECORD_LATENCY_MS)
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
                            lib.lep_session_set_latency(s, 0)
                        final_reads += 1
                    room = max(64, int(math.ceil(max(left, 0.0) * rate)))
                    wait_s = min(_RECORD_SLICE_S, max(left, 0.001), self._timeout_ms / 1000)
                arrays.reserve(n + room)
                arrays.c.cap = n + room
                rc = lib.lep_session_read(s, arrays.c, max(1, int(wait_s * 1000)))
                self._guard.check(self.port)
                if seconds is not None and n == 0 and arrays.n > 0:
                    end = float(arrays.t_mono[0]) + seconds
                self._delivered += arrays.n - n
                new = self._drain_events(base)
                events += new
                now = float(lib.lep_monotonic_seconds())
                if rc == K.LEP_E_END:
                    break
                if rc == K.LEP_E_TIMEOUT:
                    continue  # nothing in this slice of the wait (a lost stream: LEP_E_LOST)
                if rc < 0:
                    exc = error_for(be, rc, self._lost_words("recording", rc),
                                    complete=rc == K.LEP_E_LOST)
                    exc.recording = arrays.result(events, self)  # type: ignore[attr-defined]
                    raise exc
        except BaseException as exc:
            # Ctrl-C lands between two reads: keep what was received.
            if not hasattr(exc, "recording"):
                try:
                    exc.recording = arrays.result(events, self)  # type: ignore[attr-defined]
                except Exception:
                    pass
            raise
        finally:
            if self._s is not None:
                lib.lep_session_set_latency(self._s, latency_before)
            if started and self._s is not None:
                try:
                    lib.lep_session_stop(self._s)
                except Exception:
                    pass
        return arrays.result(events, self)


class _Arrays:
    """numpy arrays and the lep_session_batch that points into them."""

    t_mono: np.ndarray
    t_utc: np.ndarray
    raw: np.ndarray
    zeroed: np.ndarray
    si: np.ndarray
    status: np.ndarray
    flags: np.ndarray
    seq: np.ndarray

    def __init__(self, be: Any, cap: int) -> None:
        self.be = be
        self.c = be.new("lep_session_batch")
        self.cap = 0
        self._alloc(max(1, cap), 0)

    @property
    def n(self) -> int:
        return int(self.c.n)

    def _alloc(self, cap: int, keep: int) -> None:
        new: Dict[str, np.ndarray] = {
            "t_mono": np.empty(cap, np.float64),
            "t_utc": np.empty(cap, np.float64),
            "raw": np.empty((cap, K.LEP_AXES), np.int16),
            "zeroed": np.empty((cap, K.LEP_AXES), np.float64),
            "si": np.empty((cap, K.LEP_AXES), np.float64),
            "status": np.empty(cap, np.uint8),
            "flags": np.empty(cap, np.uint8),
            "seq": np.empty(cap, np.uint16),
        }
        if keep:
            for k, a in new.items():
                a[:keep] = getattr(self, k)[:keep]
        ctypes_of = {"t_mono": "double", "t_utc": "double", "raw": "int16_t",
                     "zeroed": "double", "si": "double", "status": "uint8_t",
                     "flags": "uint8_t", "seq": "uint16_t"}
        be, c = self.be, self.c
        for k, a in new.items():
            setattr(self, k, a)
            setattr(c, k, be.array_ptr(a, ctypes_of[k]))
        self.cap = cap
        c.n = keep
        c.cap = cap

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
                start = float(sensor._metadata_struct().start_mono)
            except LeptrinoError:
                pass
        return Recording(
            t=self.t_mono[:n].copy(), si=self.si[:n].copy(), raw=self.raw[:n].copy(),
            status=self.status[:n].copy(), seq=self.seq[:n].copy(),
            t_utc=self.t_utc[:n].copy(), zeroed=self.zeroed[:n].copy(),
            flags=self.flags[:n].copy(), events=list(events), metadata_json=meta,
            start_mono=start,
        )


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
        self._base = 0
        self.events: List[SessionEvent] = []

    def __enter__(self) -> "Stream":
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
        self._base = s._delivered

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
            a.c.n = 0
            a.c.cap = room
            wait = s._timeout_ms
            left = math.inf
            if self._end is not None:
                left = self._end - float(lib.lep_monotonic_seconds())
                wait = max(1, min(wait, int(math.ceil(left * 1000))))
            rc = lib.lep_session_read(s._live(), a.c, wait)
            s._guard.check(s.port)
            if a.n == 0 and left <= 0:
                self.close()  # past the end and nothing more arrived before it
                raise StopIteration
            s._delivered += a.n
            new = s._drain_events(self._base)
            self.events += new
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
    n = be.new_scalar("size_t")
    rc = be.lib.lep_serial_list(be.new("lep_port_info"), 0, n)
    if rc < 0:
        raise error_for(be, rc, "listing serial ports")
    total = int(be.value(n))
    if total == 0:
        return []
    arr = be.new_array("lep_port_info", total)
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

