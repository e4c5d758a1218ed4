"""The virtual sensor in-process: leptrino.Simulator."""

from __future__ import annotations

from typing import Any, Dict, List, Optional

from ._backend import get_backend
from .errors import LeptrinoError, error_for
from .values import Rated, SimStats, copy_fields

#: Options of lep_sim_options, by kind (names as in leptrino/sim.h).
_STR_OPTIONS = ("model", "serial", "firmware", "replay_csv", "link")
_BOOL_OPTIONS = ("output_rate_field", "constant", "start_streaming")
_INT_OPTIONS = ("filter", "seed", "stall_ms", "reopen_after_ms")
_FLOAT_OPTIONS = (
    "rate_hz",
    "amplitude",
    "noise",
    "overload_every_s",
    "overload_duration_s",
    "p_nak",
    "p_corrupt",
    "p_garbage",
    "p_drop",
    "stall_after_s",
    "hangup_after_s",
)
OPTIONS = _STR_OPTIONS + _BOOL_OPTIONS + _INT_OPTIONS + _FLOAT_OPTIONS


class Simulator:
    """A virtual Leptrino sensor on a pseudo-terminal, served by a C thread.

        with leptrino.Simulator(model="CFS034CA301U", p_nak=0.1) as port:
            with leptrino.Sensor(port) as sensor: ...

    Options (see leptrino/sim.h; defaults are the library's):
      model, serial, firmware, output_rate_field (38-byte product info),
      rate_hz (1200), filter, seed, amplitude, noise, constant, replay_csv,
      overload_every_s, overload_duration_s,
      faults: p_nak, p_corrupt, p_garbage, p_drop (probabilities 0..1),
      stall_ms with stall_after_s, hangup_after_s, reopen_after_ms (needs link),
      start_streaming (a stream left running by an earlier program), link.
    The virtual sensor starts in the constructor; stop() (or leaving the
    with block) ends it.
    """

    def __init__(self, *, backend: Optional[str] = None, **options: Any) -> None:
        self._be = be = get_backend(backend)
        self._sim: Any = None
        unknown = sorted(set(options) - set(OPTIONS))
        if unknown:
            raise TypeError(
                f"unknown Simulator option(s) {', '.join(unknown)}; "
                f"known: {', '.join(OPTIONS)}"
            )
        opts = be.new("lep_sim_options")
        be.lib.lep_sim_options_init(opts)
        keep: List[Any] = []
        for name, value in options.items():
            if value is None:
                continue
            if name in _STR_OPTIONS:
                setattr(opts, name, be.cstr(str(value), keep))
            elif name in _BOOL_OPTIONS:
                setattr(opts, name, bool(value))
            elif name in _INT_OPTIONS:
                setattr(opts, name, int(value))
            else:
                setattr(opts, name, float(value))
        self.options: Dict[str, Any] = dict(options)
        out = be.new_handle("lep_sim")
        err = be.new_text(512)
        rc = be.lib.lep_sim_start(opts, out, err, 512)
        if rc < 0:
            msg = be.text(err)
            raise error_for(be, rc, msg or "starting the virtual sensor", complete=bool(msg))
        self._sim = be.handle(out)
        self.port: str = be.text(be.lib.lep_sim_port(self._sim))

    def __enter__(self) -> str:
        return self.port

    def __exit__(self, *exc: Any) -> None:
        self.stop()

    def __del__(self) -> None:
        try:
            self.stop()
        except Exception:
            pass

    def __repr__(self) -> str:
        return f"<leptrino.Simulator {self.port if self._sim is not None else 'stopped'}>"

    def _live(self) -> Any:
        if self._sim is None:
            raise LeptrinoError("the virtual sensor is stopped")
        return self._sim

    def stop(self) -> None:
        """Stop the thread, close the pty, remove the link. Idempotent."""
        if self._sim is not None:
            sim, self._sim = self._sim, None
            self._be.lib.lep_sim_stop(sim)

    def power_cycle(self) -> None:
        """Switch the virtual power off and on: the stream stops, a pending filter applies."""
        self._be.lib.lep_sim_power_cycle(self._live())

    def hangup(self) -> None:
        """Hang up now, as if the USB cable were pulled."""
        self._be.lib.lep_sim_hangup(self._live())

    def stall(self, seconds: float) -> None:
        """Send nothing and answer nothing for this long, from now."""
        self._be.lib.lep_sim_stall(self._live(), int(seconds * 1000))

    @property
    def stats(self) -> SimStats:
        st = self._be.new("lep_sim_stats")
        self._be.lib.lep_sim_get_stats(self._live(), st)
        return copy_fields(SimStats, st)  # type: ignore[no-any-return]

    @staticmethod
    def models(backend: Optional[str] = None) -> List[str]:
        """Names of the model presets."""
        be = get_backend(backend)
        return list(be.string_list(be.lib.lep_sim_models()))

    @staticmethod
    def model_rated(model: str, backend: Optional[str] = None) -> Rated:
        """Published rated values of a model preset."""
        be = get_backend(backend)
        r = be.new("lep_rated")
        rc = be.lib.lep_sim_model_rated(model.encode(), r)
        if rc < 0:
            raise error_for(be, rc, f"unknown model {model!r}")
        return Rated(*(float(v) for v in r.axis))
