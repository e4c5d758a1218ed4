"""python -m leptrino: the `leptrino` tool, plus `plot`.

Every command but plot runs the bundled `leptrino` program (leptrino._tools),
so options, output and exit codes are the C tool's own. `plot` records from a
sensor (or a virtual one) and draws the six axes with matplotlib; its
--sim-* options come from the library's table of virtual sensor options, and
its exit status for an error from the library's table (lep_exit_code), the
one the C tool uses.
"""

from __future__ import annotations

import argparse
import sys
from contextlib import ExitStack
from typing import Any, Dict, NoReturn, Optional, Sequence, TextIO

from . import _constants as K
from . import errors as E
from ._backend import BACKENDS, get_backend

EXIT_OK, EXIT_FAIL, EXIT_USAGE = K.LEP_EXIT_OK, K.LEP_EXIT_FAIL, K.LEP_EXIT_USAGE


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one clear line, exit 2
        self.exit(EXIT_USAGE, f"{self.prog}: {message} (try --help)\n")


def build_plot_parser(backend: Optional[str] = None) -> argparse.ArgumentParser:
    from .simulator import sim_options

    p = _Parser(prog="python -m leptrino plot",
                description="Record from a sensor (or --sim, a virtual one) and draw forces "
                            "and moments against time into a PNG (needs matplotlib).")
    p.add_argument("port", nargs="?", help="serial device, e.g. /dev/ttyACM0")
    p.add_argument("--sim", action="store_true", help="use a virtual sensor instead of a port")
    p.add_argument("-t", "--timeout", type=int, default=500, metavar="MS",
                   help="answer timeout per command in ms (default 500)")
    p.add_argument("-s", "--seconds", type=float, default=3.0, help="seconds to record (3)")
    p.add_argument("-o", "--output", default="forces.png", metavar="PNG",
                   help="image file (default forces.png)")
    p.add_argument("--tare", type=int, default=0, metavar="N",
                   help="zero on the mean of N samples taken first")
    p.add_argument("--lowpass", type=float, default=0.0, metavar="HZ",
                   help="host low-pass cut-off in Hz (default off)")
    p.add_argument("--backend", choices=BACKENDS,
                   help="FFI backend (default: LEPTRINO_BACKEND, else ctypes)")
    g = p.add_argument_group("virtual sensor (with --sim only; the options of leptrino-sim)")
    for o in sim_options(backend):
        if o.type == "flag":
            g.add_argument(f"--sim-{o.flag}", dest=f"sim_{o.name}", action="store_const",
                           const="1", default=None, help=o.describe())
        else:
            g.add_argument(f"--sim-{o.flag}", dest=f"sim_{o.name}", metavar=o.arg or "X",
                           default=None, help=o.describe())
    return p


class _Usage(Exception):
    pass



def cmd_plot(args: argparse.Namespace, out: TextIO) -> int:
    """Run plot with the options build_plot_parser() parsed."""
    from .sensor import Sensor

    sim: Dict[str, Any] = {k[4:]: v for k, v in vars(args).items()
                           if k.startswith("sim_") and v is not None}
    if args.sim and args.port:
        raise _Usage("give a PORT or --sim, not both")
    if not args.sim and not args.port:
        raise _Usage("give a PORT, or --sim for the virtual sensor")
    if sim and not args.sim:
        raise _Usage("--sim-* options need --sim")
    if args.timeout <= 0:
        raise _Usage("--timeout must be > 0 ms")
    if not args.seconds > 0:
        raise _Usage("--seconds must be > 0")
    if args.tare < 0:
        raise _Usage("--tare must be >= 0")
    from .plot import plot_recording, pyplot

    pyplot(args.output)  # ImportError with the hint before any recording

    with ExitStack() as stack:
        try:
            s = stack.enter_context(Sensor(
                args.port, timeout=args.timeout / 1000.0, backend=args.backend,
                sim=sim if args.sim else None, lowpass=args.lowpass))
        except ValueError as exc:  # a bad --sim-* value or option, in the library's words
            raise _Usage(str(exc)) from exc
        if args.tare:
            s.tare(args.tare)
        rec = s.record(seconds=args.seconds)
        title = f"{s.product_info.model} {s.product_info.serial}" + (
            " (virtual sensor)" if args.sim else "")
    plot_recording(rec, args.output, title=title)
    print(f"wrote {args.output}: {len(rec)} samples over {args.seconds:g} s", file=out)
    return EXIT_OK


def exit_code(exc: BaseException, backend: Optional[str] = None) -> int:
    """The C tool's exit status for exc (lep_exit_code through backend)."""
    return E.exit_code(get_backend(backend), exc)


def main(argv: Optional[Sequence[str]] = None, out: TextIO = sys.stdout) -> int:
    """plot here; everything else replaces this process with `leptrino`."""
    args = list(sys.argv[1:] if argv is None else argv)
    if not args or args[0] != "plot":
        if not args or args[0] in ("-h", "--help", "help"):
            print("python -m leptrino runs the leptrino tool (below); one more command: "
                  "plot (python -m leptrino plot --help).\n", file=sys.stderr, flush=True)
        from ._tools import run

        run("leptrino", args)
    backend: Optional[str] = None
    try:
        ns = build_plot_parser().parse_args(args[1:])  # exits 2 on a bad command line
        backend = ns.backend
        return cmd_plot(ns, out)
    except _Usage as exc:
        print(f"python -m leptrino plot: {exc} (try --help)", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        return EXIT_OK
    except E.LeptrinoError as exc:
        print(f"python -m leptrino plot: {exc}", file=sys.stderr)
        return exit_code(exc, backend)
    except (ImportError, OSError) as exc:
        print(f"python -m leptrino plot: {exc}", file=sys.stderr)
        return EXIT_FAIL
