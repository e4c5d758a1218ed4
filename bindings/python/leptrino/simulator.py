"""The virtual sensor in-process: leptrino.Simulator."""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any, Dict, List, Optional

from . import _constants as K
from . import _options as _opts
from ._backend import get_backend
from .errors import LeptrinoError, error_for
from .values import Rated, SimStats

#: The virtual sensor's options are the table's rows named "sim-...".
_PREFIX = "sim-"


@dataclass(frozen=True)
class SimOption:
    """One of the virtual sensor's options: a row of the library's option
    table (leptrino/options.h) whose name begins with "sim-"."""

    name: str  # as a Python keyword: "output_rate_field"
    flag: str  # as on a command line, without the prefix: "output-rate-field"
    type: str  # "flag", "int", "float", "str", "choice" or "numbers"
    arg: Optional[str]  # the argument's name for help ("HZ"); None for flags
    help: str
    default: Optional[str]  # the default as text; None when off or empty
    min: float  # numbers: the range; str: the length in bytes
    max: float
    min_exclusive: bool

    def describe(self) -> str:
        """help, range and default in one line, as leptrino-sim prints them."""
        text = self.help
        if self.type in ("int", "float", "numbers"):
            lo = "(" if self.min_exclusive else "["
            text += f" {lo}{self.min:g}, {self.max:g}]"
        if self.default is not None:
            text += f" (default {self.default})"
        return text


def sim_options(backend: Optional[str] = None) -> List[SimOption]:
    """The virtual sensor's options, read from the C table every program uses."""
    be = get_backend(backend)
    out = []
    for r in _opts.table(be):
        if r.scope != K.LEP_SCOPE_SIM or not r.name.startswith(_PREFIX):
            continue
        flag = r.name[len(_PREFIX):]
        out.append(SimOption(
            name=flag.replace("-", "_"), flag=flag,
            type=_opts.TYPES.get(r.type, str(r.type)), arg=r.arg or None, help=r.help,
            default=r.default or None, min=r.min, max=r.max, min_exclusive=r.min_exclusive))
    return out


def fill_options(be: Any, opts: _opts.Options, options: Dict[str, Any]) -> None:
    """Set the virtual sensor's options (name -> value, without the "sim-"
    prefix) on an options handle by name: TypeError for an unknown name
    (listing the known ones), ValueError with the library's message for a
    value leptrino-sim would refuse. A value of None leaves the default."""
    for name, value in options.items():
        if value is None:
            continue
        full = _PREFIX + str(name).replace("_", "-")
        if str(name).startswith(("sim-", "sim_")) or _opts.option_type(be, full) is None:
            known = ", ".join(o.name for o in sim_options(be))
            raise TypeError(f"unknown virtual sensor option {name!r}; known: {known}")
        opts.set(full, value)


class Simulator:
    """A virtual Leptrino sensor on a pseudo-terminal, served by a C thread.

        with leptrino.Simulator(model="CFS034CA301U", nak=0.1) as port:
            with leptrino.Sensor(port) as sensor: ...

    Options are those of `leptrino-sim` (and the `--sim-*` options of the
    `leptrino` tool), from the same C table (leptrino/options.h, the rows
    "sim-..."): the name with underscores for dashes (output_rate_field,
    overload_every, stall_after, ...), values checked by the library exactly
    as leptrino-sim checks them. Simulator.options()
    lists them with help, range and default. An unknown name is a
    TypeError, a bad value a ValueError. The virtual sensor starts in the
    constructor; stop() (or leaving the with block) ends it.
    """

    def __init__(self, *, backend: Optional[str] = None, **options: Any) -> None:
        self._be = be = get_backend(backend)
        self._sim: Any = None
        with _opts.Options(be) as opts:
            fill_options(be, opts, options)
            self.options: Dict[str, Any] = dict(options)
            out = be.new_handle("lep_sim")
            err = be.new_text(512)
            rc = be.lib.lep_sim_start(opts.handle, out, err, 512)
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
        """What the virtual sensor did since it started (lep_sim_stats, by field name)."""
        be = self._be
        n = int(be.lib.lep_sim_stats_fields())
        out = be.new_array("uint64_t", max(1, n))
        be.lib.lep_sim_stats(self._live(), out, n)
        names = [be.text(be.lib.lep_sim_stats_field_name(i)) for i in range(n)]
        return SimStats.from_fields({k: int(out[i]) for i, k in enumerate(names)})

    @staticmethod
    def models(backend: Optional[str] = None) -> List[str]:
        """Names of the model presets."""
        be = get_backend(backend)
        return [be.text(be.lib.lep_sim_model_name(i))
                for i in range(int(be.lib.lep_sim_model_count()))]

    @staticmethod
    def model_rated(model: str, backend: Optional[str] = None) -> Rated:
        """Published rated values of a model preset."""
        be = get_backend(backend)
        r = be.doubles(6)
        rc = be.lib.lep_sim_model_rated(model.encode(), r)
        if rc < 0:
            raise error_for(be, rc, f"unknown model {model!r}")
        return Rated(*(float(r[i]) for i in range(6)))
