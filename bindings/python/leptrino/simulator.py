"""The virtual sensor in-process: leptrino.Simulator."""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any, Dict, List, Optional

from . import _constants as K
from ._backend import get_backend
from .errors import LeptrinoError, error_for
from .values import Rated, SimStats

_TYPES = {
    K.LEP_SIM_OPT_FLAG: "flag",
    K.LEP_SIM_OPT_INT: "int",
    K.LEP_SIM_OPT_UINT: "uint",
    K.LEP_SIM_OPT_DOUBLE: "float",
    K.LEP_SIM_OPT_STRING: "str",
    K.LEP_SIM_OPT_CHOICE: "choice",
    K.LEP_SIM_OPT_NUMBERS: "numbers",
}


@dataclass(frozen=True)
class SimOption:
    """One row of the C table of the virtual sensor's options (lep_sim_option_at)."""

    name: str  # as a Python keyword: "output_rate_field"
    flag: str  # as on a command line, without the prefix: "output-rate-field"
    type: str  # "flag", "int", "uint", "float", "str", "choice" or "numbers"
    arg: Optional[str]  # the argument's name for help ("HZ"); None for flags
    help: str
    default: Optional[str]  # the default as text; None when off or empty
    min: float  # numbers: the range; str: the length in bytes
    max: float
    min_exclusive: bool

    def describe(self) -> str:
        """help, range and default in one line, as leptrino-sim prints them."""
        text = self.help
        if self.type in ("int", "uint", "float", "numbers"):
            lo = "(" if self.min_exclusive else "["
            text += f" {lo}{self.min:g}, {self.max:g}]"
        if self.default is not None:
            text += f" (default {self.default})"
        return text


def _row(be: Any, info: Any) -> SimOption:
    flag = be.text(info.name)
    return SimOption(
        name=flag.replace("-", "_"),
        flag=flag,
        type=_TYPES.get(int(info.type), str(int(info.type))),
        arg=be.text(info.arg) or None,
        help=be.text(info.help),
        default=be.text(info.default_text) if be.text(info.default_text) else None,
        min=float(info.min),
        max=float(info.max),
        min_exclusive=bool(info.min_exclusive),
    )


def sim_options(backend: Optional[str] = None) -> List[SimOption]:
    """The virtual sensor's options, read from the C table every program uses."""
    be = get_backend(backend)
    lib = be.lib
    return [_row(be, be.deref(lib.lep_sim_option_at(i)))
            for i in range(int(lib.lep_sim_option_count()))]


def _text(value: Any, is_flag: bool) -> str:
    """A Python value as the text lep_sim_option_set parses. True/False are
    "1"/"0" for a flag only; elsewhere they stay "True"/"False" (refused)."""
    if is_flag and isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return repr(value)
    if not isinstance(value, (str, bytes)) and hasattr(value, "__iter__"):
        # payload=(m, cx, cy, cz), gravity=(gx, gy, gz): "M,CX,CY,CZ"
        return ",".join(repr(float(v)) for v in value)
    return str(value)


def fill_options(be: Any, opts: Any, options: Dict[str, Any]) -> None:
    """Set options (name -> value) in the lep_sim_options opts through the C
    table: TypeError for an unknown name (listing the known ones), ValueError
    with the library's message for a value leptrino-sim would refuse. A value
    of None leaves the default."""
    lib = be.lib
    err = be.new_text(256)
    for name, value in options.items():
        if value is None:
            continue
        key = str(name).encode()
        info = lib.lep_sim_option_find(key)
        if not info:
            known = ", ".join(o.name for o in sim_options(be))
            raise TypeError(f"unknown virtual sensor option {name!r}; known: {known}")
        is_flag = int(be.deref(info).type) == K.LEP_SIM_OPT_FLAG
        rc = lib.lep_sim_option_set(opts, key, _text(value, is_flag).encode(), err, 256)
        if rc < 0:
            raise ValueError(be.text(err) or f"{name}={value!r}: not accepted")


class Simulator:
    """A virtual Leptrino sensor on a pseudo-terminal, served by a C thread.

        with leptrino.Simulator(model="CFS034CA301U", nak=0.1) as port:
            with leptrino.Sensor(port) as sensor: ...

    Options are those of `leptrino-sim` (and the `--sim-*` options of the
    `leptrino` tool), from the same C table: the name with underscores for
    dashes (output_rate_field, overload_every, stall_after, ...; the C field
    names rate_hz, p_nak, replay_csv... are accepted too), values checked by
    the library exactly as leptrino-sim checks them. Simulator.options()
    lists them with help, range and default. An unknown name is a
    TypeError, a bad value a ValueError. The virtual sensor starts in the
    constructor; stop() (or leaving the with block) ends it.
    """

    def __init__(self, *, backend: Optional[str] = None, **options: Any) -> None:
        self._be = be = get_backend(backend)
        self._sim: Any = None
        opts = be.new("lep_sim_options")
        be.lib.lep_sim_options_init(opts)
        fill_options(be, opts, options)
        self.options: Dict[str, Any] = dict(options)
        out = be.new_handle("lep_sim")
        err = be.new_text(512)
        rc = be.lib.lep_sim_start(opts, out, err, 512)
        if rc < 0:
            msg = be.text(err)
            if rc == K.LEP_E_ARG:
                raise ValueError(msg or "bad virtual sensor options")
            raise error_for(be, rc, msg or "starting the virtual sensor", complete=bool(msg))
        self._sim = be.handle(out)
        self.port: str = be.text(be.lib.lep_sim_port(self._sim))
        if be.text(err):  # started, with a warning (a replay file cut short)
            warnings.warn(be.text(err), RuntimeWarning, stacklevel=2)

    @staticmethod
    def option_table(backend: Optional[str] = None) -> List[SimOption]:
        """The options Simulator accepts, from the C table (see SimOption)."""
        return sim_options(backend)

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
        from . import _args as A

        ms = A.number("stall", "seconds", seconds, 0.0, 86400.0) * 1000
        self._be.lib.lep_sim_stall(self._live(), int(ms))

    def hold(self, seconds: float) -> None:
        """Hold the output for this long, from now: samples are made at their
        times and sent together when the hold ends (a sender running late).
        ``hold(0)`` releases them now."""
        from . import _args as A

        ms = A.number("hold", "seconds", seconds, 0.0, 86400.0) * 1000
        self._be.lib.lep_sim_hold(self._live(), int(ms))

    @property
    def stats(self) -> SimStats:
        st = self._be.new("lep_sim_stats")
        self._be.lib.lep_sim_get_stats(self._live(), st)
        return SimStats.from_c(st)

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
