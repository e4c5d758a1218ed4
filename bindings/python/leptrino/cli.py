"""python -m leptrino: the CLI's info and stream, plus plot, for people who live in Python.

Options, output formats and exit codes follow the C tool `leptrino`.
"""

from __future__ import annotations

import argparse
import json
import signal
import sys
from contextlib import ExitStack
from typing import Any, Dict, List, NoReturn, Optional, Sequence, TextIO

from . import errors as E
from ._backend import BACKENDS, get_backend

EXIT_OK, EXIT_FAIL, EXIT_USAGE = 0, 1, 2
EXIT_TIMEOUT, EXIT_DISCONNECTED, EXIT_SENSOR = 3, 4, 5
EXIT_NOT_FOUND, EXIT_BUSY, EXIT_PERMISSION = 6, 7, 8

EXIT_CODES = """exit codes:
  0  success (also: stream stopped by Ctrl-C or SIGTERM)
  1  other failure (I/O error, output file, protocol error)
  2  bad command line
  3  timeout: the sensor did not answer, or data stopped arriving
  4  disconnected: the port went away
  5  sensor error: the sensor refused a command (result code, or NAKs)
  6  port not found, or not a serial port
  7  port busy: in use by another program
  8  permission denied on the port"""

# --sim-* option -> (Simulator option, type); type None is a flag
SIM_OPTIONS: Dict[str, Any] = {
    "model": ("model", str, "model preset (default PFS055YA501U6)"),
    "rate": ("rate_hz", float, "continuous output rate in Hz (default 1200)"),
    "seed": ("seed", int, "seed of the waveform and of the faults (default 1)"),
    "serial": ("serial", str, "serial number, 8 digits"),
    "firmware": ("firmware", str, "firmware version, 4 characters"),
    "output-rate-field": ("output_rate_field", None, "product info in the 38-byte form"),
    "filter": ("filter", int, "filter code in effect at power-on, 0..3"),
    "amplitude": ("amplitude", float, "sine amplitude (or constant level), fraction of rated"),
    "noise": ("noise", float, "noise amplitude as a fraction of rated"),
    "constant": ("constant", None, "hold a constant load (the amplitude), no noise"),
    "replay": ("replay_csv", str, "replay raw counts fx,fy,fz,mx,my,mz per line"),
    "overload-every": ("overload_every_s", float, "an overload episode every S seconds"),
    "overload-duration": ("overload_duration_s", float, "length of an overload episode"),
    "nak": ("p_nak", float, "fault: probability of NAKing a valid command"),
    "corrupt": ("p_corrupt", float, "fault: probability of corrupting a message"),
    "garbage": ("p_garbage", float, "fault: probability of garbage between messages"),
    "drop": ("p_drop", float, "fault: probability of dropping a data message"),
    "stall": ("stall_ms", int, "fault: stall for MS ms ..."),
    "stall-after": ("stall_after_s", float, "... starting S seconds after start"),
    "hangup-after": ("hangup_after_s", float, "fault: hang up the port after S s"),
    "reopen-after": ("reopen_after_ms", int, "after a hang-up, bring the port back after MS ms"),
    "start-streaming": ("start_streaming", None, "power up already streaming"),
    "link": ("link", str, "also make a symlink PATH to the virtual port"),
}


class _Terminated(Exception):
    """SIGTERM arrived."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one clear line, exit 2
        self.exit(EXIT_USAGE, f"{self.prog}: {message} (try --help)\n")


def _port_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("port", nargs="?", help="serial device, e.g. /dev/ttyACM0")
    p.add_argument("--sim", action="store_true", help="use a virtual sensor instead of a port")
    p.add_argument("-t", "--timeout", type=int, default=500, metavar="MS",
                   help="answer timeout per command in ms (default 500)")
    g = p.add_argument_group("virtual sensor (with --sim only)")
    for flag, (dest, typ, text) in SIM_OPTIONS.items():
        if typ is None:
            # --sim-output-rate: the C tool's earlier spelling, still accepted
            names = [f"--sim-{flag}"] + (["--sim-output-rate"] if flag == "output-rate-field"
                                         else [])
            g.add_argument(*names, dest=f"sim_{dest}", action="store_true", default=None,
                           help=text)
        else:
            g.add_argument(f"--sim-{flag}", dest=f"sim_{dest}", type=typ, help=text)


def build_parser() -> argparse.ArgumentParser:
    top = _Parser(prog="python -m leptrino", epilog=EXIT_CODES,
                  formatter_class=argparse.RawDescriptionHelpFormatter,
                  description="Leptrino force/torque sensors from Python (mirrors the "
                              "`leptrino` tool's info and stream; plot draws the six axes).")
    top.add_argument("--version", action="store_true", help="show versions and exit")
    top.add_argument("--backend", choices=BACKENDS,
                     help="FFI backend (default: LEPTRINO_BACKEND, else ctypes)")
    sub = top.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    sub.add_parser("list", help="list serial ports, marking likely sensors")

    p = sub.add_parser("info", help="show model, serial, firmware, rated values, filter",
                       epilog=EXIT_CODES, formatter_class=argparse.RawDescriptionHelpFormatter)
    _port_args(p)

    p = sub.add_parser("stream", help="record continuous data to CSV or JSON lines",
                       epilog=EXIT_CODES, formatter_class=argparse.RawDescriptionHelpFormatter,
                       description="CSV header t,fx,fy,fz,mx,my,mz,status: t in s since "
                       "streaming started (monotonic clock), forces in N, moments in N m.")
    _port_args(p)
    p.add_argument("-d", "--duration", type=float, metavar="S",
                   help="stop after S seconds (the tare period included)")
    p.add_argument("-c", "--count", type=int, metavar="N", help="stop after N samples")
    p.add_argument("-o", "--output", default="-", metavar="FILE", help="output file (- = stdout)")
    p.add_argument("-f", "--format", choices=("csv", "jsonl"), default="csv")
    p.add_argument("-u", "--units", choices=("si", "raw"), default="si")
    p.add_argument("--tare", type=int, default=0, metavar="N",
                   help="subtract the mean of the first N samples (not written)")

    p = sub.add_parser("plot", help="record and draw the six axes into a PNG (matplotlib)",
                       epilog=EXIT_CODES, formatter_class=argparse.RawDescriptionHelpFormatter)
    _port_args(p)
    p.add_argument("-s", "--seconds", type=float, default=3.0, help="seconds to record (3)")
    p.add_argument("-o", "--output", default="forces.png", metavar="PNG",
                   help="image file (default forces.png)")
    p.add_argument("--tare", type=int, default=0, metavar="N",
                   help="subtract the mean of N samples taken first")
    return top


def _sim_options(args: argparse.Namespace) -> Dict[str, Any]:
    return {dest: getattr(args, f"sim_{dest}") for dest, _t, _h in SIM_OPTIONS.values()
            if getattr(args, f"sim_{dest}") is not None}


def _open(args: argparse.Namespace, stack: ExitStack) -> Any:
    from .sensor import Sensor
    from .simulator import Simulator

    sim_opts = _sim_options(args)
    if args.sim and args.port:
        raise _Usage("give a PORT or --sim, not both")
    if not args.sim and not args.port:
        raise _Usage("give a PORT, or --sim for the virtual sensor")
    if sim_opts and not args.sim:
        raise _Usage("--sim-* options need --sim")
    if args.timeout <= 0:
        raise _Usage("--timeout must be > 0 ms")
    port = args.port
    if args.sim:
        port = stack.enter_context(Simulator(backend=args.backend, **sim_opts))
    return stack.enter_context(Sensor(port, timeout=args.timeout / 1000.0,
                                      backend=args.backend))


class _Usage(Exception):
    pass


def cmd_list(args: argparse.Namespace, out: TextIO) -> int:
    from .sensor import list_ports

    ports = list_ports(args.backend)
    if not ports:
        print("no serial ports found", file=out)
    for p in ports:
        ids = f" {p.vid:04x}:{p.pid:04x}" if p.vid or p.pid else ""
        mark = "  <- likely sensor" if p.likely_sensor else ""
        print(f"{p.path}{ids}{'  ' + p.by_id if p.by_id else ''}"
              f"{'  ' + p.description if p.description else ''}{mark}", file=out)
    return EXIT_OK


def _num(v: float) -> str:
    return f"{v:g}"


def cmd_info(args: argparse.Namespace, out: TextIO) -> int:
    with ExitStack() as stack:
        s = _open(args, stack)
        info, r, filt = s.product_info, s.rated, s.filter
        print(f"port:         {s.port}{' (virtual sensor)' if args.sim else ''}", file=out)
        print(f"model:        {info.model}", file=out)
        print(f"serial:       {info.serial}", file=out)
        print(f"firmware:     {info.firmware}", file=out)
        rate = f"{info.output_rate_hz} Hz" if info.output_rate_hz else (
            info.output_rate or "not reported")
        print(f"output rate:  {rate}", file=out)
        print("protocol:     " + ("38-byte product info (with output rate)"
                                  if info.has_output_rate else "32-byte product info (v1.13)"),
              file=out)
        print(f"rated:        Fx {_num(r.fx)} N, Fy {_num(r.fy)} N, Fz {_num(r.fz)} N, "
              f"Mx {_num(r.mx)} N m, My {_num(r.my)} N m, Mz {_num(r.mz)} N m", file=out)
        print(f"filter:       {filt} ({s.filter_label(filt)})", file=out)
    return EXIT_OK


def _write_rows(out: TextIO, fmt: str, t: Any, vals: Any, status: Any, raw: bool) -> None:
    names = ("fx", "fy", "fz", "mx", "my", "mz")
    lines: List[str] = []
    for i in range(len(t)):
        v = vals[i]
        if fmt == "csv":
            cells = [f"{t[i]:.6f}"] + [str(int(x)) if raw else f"{x:.6f}" for x in v]
            lines.append(",".join(cells) + f",{int(status[i])}\n")
        else:
            obj = "".join(f',"{n}":{int(x) if raw else format(x, ".6f")}'
                          for n, x in zip(names, v))
            lines.append(f'{{"t":{t[i]:.6f}{obj},"status":{int(status[i])}}}\n')
    out.write("".join(lines))


def cmd_stream(args: argparse.Namespace, out: TextIO) -> int:
    if args.duration is not None and not args.duration > 0:
        raise _Usage("--duration must be > 0")
    if args.count is not None and args.count <= 0:
        raise _Usage("--count must be > 0")
    if args.tare < 0:
        raise _Usage("--tare must be >= 0")
    raw = args.units == "raw"
    n = overloads = tare_n = 0
    with ExitStack() as stack:
        s = _open(args, stack)
        dest = out if args.output == "-" else stack.enter_context(
            open(args.output, "w", encoding="utf-8", newline=""))
        if args.format == "csv":
            dest.write("t,fx,fy,fz,mx,my,mz,status\n")
        s.start()
        t0 = float(s._be.lib.lep_monotonic_seconds())
        end = t0 + args.duration if args.duration is not None else None
        try:
            if args.tare:
                s.tare(args.tare)
                tare_n = args.tare  # received, not written: they count in the rate
            while True:
                left = None if end is None else end - float(s._be.lib.lep_monotonic_seconds())
                if left is not None and left <= 0:
                    break
                if args.count is not None:
                    if n >= args.count:
                        break
                    want = min(args.count - n, 120)
                    rec = s.record(count=want) if left is None else s.record(
                        seconds=min(0.1, left))
                    if len(rec) > args.count - n:
                        rec = _cut(rec, args.count - n)
                else:
                    rec = s.record(seconds=0.1 if left is None else min(0.1, left))
                _write_rows(dest, args.format, rec.t - t0, rec.raw if raw else rec.si,
                            rec.status, raw)
                n += len(rec)
                overloads += int(rec.overload.sum())
        except (KeyboardInterrupt, _Terminated) as exc:
            # The batch in flight when the signal came is kept, not lost.
            rec = getattr(exc, "recording", None)
            if rec is not None and len(rec) and tare_n == args.tare:
                if args.count is not None and len(rec) > args.count - n:
                    rec = _cut(rec, args.count - n)
                _write_rows(dest, args.format, rec.t - t0, rec.raw if raw else rec.si,
                            rec.status, raw)
                n += len(rec)
                overloads += int(rec.overload.sum())
        finally:
            secs = float(s._be.lib.lep_monotonic_seconds()) - t0
            dest.flush()
            if not s.closed and s.streaming:
                try:
                    s.stop()
                except E.LeptrinoError:
                    pass
        st = s.stats
        errs = st.bcc_errors + st.frame_errors + st.invalid
        print(f"leptrino: stream: {n} samples in {secs:.2f} s "
              f"({((n + tare_n) / secs) if secs > 0 else 0:.1f} Hz), {errs} errors, "
              f"{overloads} overloads", file=sys.stderr)
    return EXIT_OK


def _cut(rec: Any, k: int) -> Any:
    from .values import Recording

    return Recording(rec.t[:k], rec.si[:k], rec.raw[:k], rec.status[:k], rec.seq[:k])


def cmd_plot(args: argparse.Namespace, out: TextIO) -> int:
    if not args.seconds > 0:
        raise _Usage("--seconds must be > 0")
    from .plot import plot_recording

    with ExitStack() as stack:
        s = _open(args, stack)
        if args.tare:
            s.tare(args.tare)
        rec = s.record(seconds=args.seconds)
        title = f"{s.product_info.model} {s.product_info.serial}" + (
            " (virtual sensor)" if args.sim else "")
    plot_recording(rec, args.output, title=title)
    print(f"wrote {args.output}: {len(rec)} samples over {args.seconds:g} s", file=out)
    return EXIT_OK


def _exit_code(exc: BaseException) -> int:
    if isinstance(exc, E.TimeoutError):
        return EXIT_TIMEOUT
    if isinstance(exc, E.DisconnectedError):
        return EXIT_DISCONNECTED
    if isinstance(exc, (E.SensorError, E.NakError)):
        return EXIT_SENSOR
    if isinstance(exc, (E.PortNotFoundError, E.NotATerminalError)):
        return EXIT_NOT_FOUND
    if isinstance(exc, E.BusyError):
        return EXIT_BUSY
    if isinstance(exc, E.PortPermissionError):
        return EXIT_PERMISSION
    return EXIT_FAIL


def main(argv: Optional[Sequence[str]] = None, out: TextIO = sys.stdout) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.version:
            from . import __version__, library_version

            be = get_backend(args.backend)
            print(f"leptrino (Python) {__version__}, libleptrino "
                  f"{library_version(args.backend)} via {be.name} ({be.path})", file=out)
            return EXIT_OK
        if not args.command:
            parser.print_help(sys.stderr)
            return EXIT_USAGE
        prev = signal.getsignal(signal.SIGTERM)

        def on_term(signum: int, frame: Any) -> None:
            raise _Terminated()

        try:
            signal.signal(signal.SIGTERM, on_term)
        except ValueError:  # not the main thread
            prev = None
        try:
            cmd = {"list": cmd_list, "info": cmd_info, "stream": cmd_stream,
                   "plot": cmd_plot}[args.command]
            return cmd(args, out)
        finally:
            if prev is not None:
                signal.signal(signal.SIGTERM, prev)
    except _Usage as exc:
        print(f"python -m leptrino {args.command}: {exc} (try --help)", file=sys.stderr)
        return EXIT_USAGE
    except (KeyboardInterrupt, _Terminated):
        return EXIT_OK
    except BrokenPipeError:
        return EXIT_OK
    except E.LeptrinoError as exc:
        print(f"python -m leptrino {args.command}: {exc}", file=sys.stderr)
        return _exit_code(exc)
    except ImportError as exc:
        print(f"python -m leptrino: {exc}", file=sys.stderr)
        return EXIT_FAIL
    except OSError as exc:
        print(f"python -m leptrino {args.command}: {exc}", file=sys.stderr)
        return EXIT_FAIL
