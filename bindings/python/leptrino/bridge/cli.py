"""leptrino-bridge: Leptrino sensors as ROS 2 topics on Zenoh (rmw_zenoh), DDS, Foxglove and MCAP.

    leptrino-bridge --sim a --sim b                       # two virtual sensors, router on :7447
    leptrino-bridge --sensor left=/dev/ttyACM0 --connect tcp/192.0.2.10:7447
    leptrino-bridge --sim a --mcap out.mcap --duration 10 # no network at all
    leptrino-bridge --sim a --dds --foxglove              # ROS 2 on DDS, Foxglove live
    leptrino-bridge --sensor a=/dev/ttyACM0 --payload a=1.2,0,0,0.05 --limit fz=50,mz=2

Exit status: 0 after a clean stop (Ctrl-C, SIGTERM, --duration), 2 for a bad
argument or a sensor/file that cannot be opened.
"""

from __future__ import annotations

import argparse
import logging
import math
import os
import signal
import sys
from typing import Any, Dict, List, Optional, Sequence, Tuple

from . import rmw_zenoh as rz
from .node import AUDIT_LOGGER, NodeOptions, SensorSpec

PROG = "leptrino-bridge"


def _parse_sensor(text: str) -> SensorSpec:
    name, sep, port = text.partition("=")
    if not sep or not name or not port:
        raise argparse.ArgumentTypeError(f"{text!r}: expected NAME=PORT")
    try:
        return SensorSpec(name, port=port)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _parse_sim(text: str) -> SensorSpec:
    """NAME or NAME,option=value,... (the virtual sensor's options, as
    leptrino-sim names them, dashes or underscores). A value of several
    numbers keeps its commas: a,payload=1.2,0,0,0.05,gravity=0,0,-9.8."""
    name, *opts = text.split(",")
    sim: Dict[str, Any] = {}
    last = ""
    for o in opts:
        k, sep, v = o.partition("=")
        if not sep and last and isinstance(sim[last], str) and _is_number(k):
            sim[last] += "," + k  # the next number of the previous option's value
            continue
        if not k:
            raise argparse.ArgumentTypeError(f"{text!r}: empty option")
        last = k.strip().replace("-", "_")
        sim[last] = v if sep else True
    try:
        return SensorSpec(name, sim=sim)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def exit_code(e: BaseException) -> int:
    """The `leptrino` tool's exit code for what went wrong (docs/cli.md): a
    missing port is 6 in both, an existing output file 1, a bad value 2."""
    from .. import errors as E

    for kind, code in ((E.TimeoutError, 3), (E.DisconnectedError, 4), (E.SensorError, 5),
                       (E.NakError, 5), (E.PortNotFoundError, 6), (E.NotATerminalError, 6),
                       (E.BusyError, 7), (E.PortPermissionError, 8), (E.LeptrinoError, 1),
                       (ValueError, 2), (TypeError, 2), (OSError, 1)):
        if isinstance(e, kind):
            return code
    return 1


def _parse_rpy(text: str) -> List[float]:
    try:
        v = [float(x) for x in text.split(",")]
    except ValueError:
        v = []
    if len(v) != 3 or not all(math.isfinite(x) for x in v):
        raise argparse.ArgumentTypeError(f"{text!r}: expected R,P,Y in degrees")
    return [math.radians(x) for x in v]


def _numbers(text: str, n: int, what: str) -> List[float]:
    """n comma-separated finite numbers (as `leptrino stream`'s options take them)."""
    try:
        v = [float(x) for x in text.split(",")]
    except ValueError:
        v = []
    if len(v) != n or not all(math.isfinite(x) for x in v):
        raise argparse.ArgumentTypeError(f"{text!r}: expected {what}, {n} comma-separated "
                                         "numbers")
    return v


def _per_sensor(text: str) -> Tuple[Optional[str], str]:
    """"NAME=VALUES" -> (NAME, VALUES); "VALUES" (every sensor) -> (None, VALUES)."""
    name, sep, rest = text.partition("=")
    return (name, rest) if sep else (None, text)


def _parse_payload(text: str) -> Tuple[Optional[str], List[float]]:
    name, rest = _per_sensor(text)
    v = _numbers(rest, 4, "[NAME=]M,CX,CY,CZ (kg, m)")
    if v[0] < 0:
        raise argparse.ArgumentTypeError(f"{text!r}: the mass {v[0]:g} kg is negative")
    return name, v


def _parse_gravity(text: str) -> Tuple[Optional[str], List[float]]:
    name, rest = _per_sensor(text)
    v = _numbers(rest, 3, "[NAME=]GX,GY,GZ (m/s²)")
    if not any(v):
        raise argparse.ArgumentTypeError(f"{text!r}: gravity cannot be a zero vector")
    return name, v


def _limits(p: argparse.ArgumentParser, texts: List[str]) -> Optional[Tuple[float, ...]]:
    """The --limit options, parsed and merged by the library (lep_limits_add,
    as `leptrino stream` does): the axes of repeated options add up, and an
    axis limited twice is refused rather than one of its values dropped."""
    from ..payload import parse_limits

    if not texts:
        return None
    try:
        return parse_limits(*texts)
    except ValueError:
        p.error(f"--limit {' --limit '.join(texts)}: expected AXIS=VALUE,... with AXIS one of "
                "fx, fy, fz, mx, my, mz, each limited once, and VALUE > 0 (N, N m)")


def _positive(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        v = -1.0
    if not (v > 0 and math.isfinite(v)):
        raise argparse.ArgumentTypeError(f"{text!r}: expected a number > 0")
    return v


def _count(text: str) -> int:
    try:
        v = int(text)
    except ValueError:
        v = -1
    if v < 0:
        raise argparse.ArgumentTypeError(f"{text!r}: expected a whole number >= 0")
    return v


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog=PROG, description=__doc__.split("\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="Topics per sensor NAME: <ns>/NAME/wrench, <ns>/NAME/wrench_raw "
               "(geometry_msgs/msg/WrenchStamped), <ns>/NAME/diagnostics "
               "(diagnostic_msgs/msg/DiagnosticArray, 1 Hz, and at once when a --limit "
               "episode begins or ends); services <ns>/NAME/tare and <ns>/NAME/untare "
               "(std_srvs/srv/Trigger); input <ns>/NAME/gravity "
               "(geometry_msgs/msg/Vector3Stamped, m/s² in the sensor frame) on every "
               "transport. See docs/bridge.md.")
    s = p.add_argument_group("sensors")
    s.add_argument("--sensor", action="append", type=_parse_sensor, default=[],
                   metavar="NAME=PORT", help="a sensor on a serial port (repeatable)")
    s.add_argument("--sim", action="append", type=_parse_sim, default=[],
                   metavar="NAME[,OPT=VAL...]",
                   help="a virtual sensor, with leptrino-sim's options (repeatable)")
    s.add_argument("--frame-id", action="append", default=[], metavar="NAME=FRAME",
                   help="header.frame_id of a sensor's messages (default: its NAME)")
    s.add_argument("--tare", type=_count, default=0, metavar="N",
                   help="zero on the mean of the first N samples after the start")
    s.add_argument("--retare", type=_count, default=100, metavar="N",
                   help="samples the tare service averages (default 100)")
    s.add_argument("--read-only", action="store_true",
                   help="publish only: no tare/untare service or command topic and no gravity "
                        "input on any transport (nobody on the network can change a sensor)")
    s.add_argument("--lowpass", type=float, default=0.0, metavar="HZ",
                   help="the session's low-pass cut-off on `wrench` (0: off)")
    s.add_argument("--rotate", type=_parse_rpy, default=None, metavar="R,P,Y",
                   help="express `wrench` in a frame rotated by roll, pitch, yaw (degrees)")
    s.add_argument("--latency", type=float, default=0.002, metavar="S",
                   help="how long the session may hold samples back (default 0.002)")
    s.add_argument("--payload", action="append", type=_parse_payload, default=[],
                   metavar="[NAME=]M,CX,CY,CZ",
                   help="a tool on sensor NAME (without NAME=: on every sensor): mass kg, "
                        "centre of mass m in the sensor frame; its weight is removed from "
                        "`wrench` (not from `wrench_raw`) at the gravity of --gravity and of "
                        "the NAME/gravity topic (repeatable)")
    s.add_argument("--gravity", action="append", type=_parse_gravity, default=[],
                   metavar="[NAME=]GX,GY,GZ",
                   help="initial gravity in sensor NAME's frame (without NAME=: every "
                        "sensor's), m/s² (default 0,0,-9.80665: the z axis up; repeatable)")
    s.add_argument("--limit", action="append", default=[], metavar="AXIS=V,...",
                   help="limits on `wrench` (compensated), N and N m, for every sensor, e.g. "
                        "fz=50,mz=2: an episode beyond one is a WARN in diagnostics "
                        "(repeatable: the axes add up; an axis limited twice is refused)")
    z = p.add_argument_group("zenoh")
    z.add_argument("--connect", action="append", default=[], metavar="ENDPOINT",
                   help="connect to this endpoint, e.g. tcp/127.0.0.1:7447 (repeatable; "
                        "default: a router on tcp/127.0.0.1:7447)")
    z.add_argument("--listen", action="append", default=[], metavar="ENDPOINT",
                   help="listen on this endpoint (peer mode; repeatable)")
    z.add_argument("--mode", choices=("peer", "client"), default=None,
                   help="Zenoh mode (default peer)")
    z.add_argument("--scout", action="store_true", help="enable multicast scouting (off)")
    z.add_argument("--zenoh-config", metavar="FILE", default=None,
                   help="a Zenoh configuration file (JSON5: TLS, user/password, access "
                        "control...); the options above apply on top, and one that "
                        "contradicts a value the file sets is an error")
    z.add_argument("--zenoh", action="store_true",
                   help="Zenoh with its defaults beside --dds/--foxglove/--mcap")
    z.add_argument("--no-zenoh", action="store_true",
                   help="no Zenoh (implied by --mcap, --dds or --foxglove without "
                        "--zenoh/--connect/--listen/--scout)")
    z.add_argument("--domain", type=_count, default=None, metavar="ID",
                   help="ROS domain id (default: $ROS_DOMAIN_ID, else 0)")
    z.add_argument("--namespace", default="/", metavar="NS", help="ROS namespace (default /)")
    d = p.add_argument_group("DDS (ROS 2 on Fast DDS or Cyclone DDS)")
    d.add_argument("--dds", action="store_true",
                   help="publish on DDS as a ROS 2 node (domain --domain; through rclpy "
                        "when it imports, else Cyclone DDS: --dds-impl)")
    d.add_argument("--dds-impl", choices=("auto", "rclpy", "cyclone"), default="auto",
                   help="how --dds is served: rclpy (the ROS 2 rmw rclpy loads, "
                        "rmw_fastrtps_cpp by default: every ROS 2 client answered), cyclone "
                        "(the cyclonedds package: no ROS needed, but rmw_fastrtps' service "
                        "calls cannot be answered; use the command topics), auto (default: "
                        "rclpy when it imports, else cyclone)")
    d.add_argument("--dds-interface", metavar="ADDR", default=None,
                   help="DDS on this interface address only, no multicast, ADDR as its peer "
                        "(e.g. 127.0.0.1)")
    d.add_argument("--ros-distro", choices=("humble", "jazzy", "kilted", "rolling"),
                   default="jazzy",
                   help="layout of the node announcement (ros_discovery_info): humble "
                        "(24-byte Gid) or jazzy and later (16 bytes; default)")
    f = p.add_argument_group("Foxglove live")
    f.add_argument("--foxglove", nargs="?", const="127.0.0.1:8765", default=None,
                   metavar="[HOST:]PORT",
                   help="serve the topics and the tare services to Foxglove over WebSocket "
                        "(default 127.0.0.1:8765; 0.0.0.0:8765 for other hosts)")
    o = p.add_argument_group("output and run")
    o.add_argument("--mcap", metavar="FILE", help="record the same messages to a ROS 2 MCAP file")
    o.add_argument("--overwrite", action="store_true",
                   help="replace an existing --mcap file (the name `leptrino stream` uses)")
    o.add_argument("--force", dest="overwrite", action="store_true", help=argparse.SUPPRESS)
    o.add_argument("--duration", type=_positive, default=None, metavar="S",
                   help="stop after S seconds (default: run until Ctrl-C or SIGTERM)")
    o.add_argument("-v", "--verbose", action="store_true")
    return p


def main(argv: Optional[Sequence[str]] = None) -> int:
    p = build_parser()
    a = p.parse_args(argv)
    logging.basicConfig(level=logging.INFO if a.verbose else logging.WARNING,
                        format=f"{PROG}: %(message)s")
    # who changed a sensor, and read-only: said even without --verbose
    logging.getLogger(AUDIT_LOGGER).setLevel(logging.INFO)
    specs: List[SensorSpec] = list(a.sensor) + list(a.sim)
    if not specs:
        p.error("no sensors: give --sensor NAME=PORT or --sim NAME")
    by_name = {s.name: s for s in specs}
    for f in a.frame_id:
        name, sep, frame = f.partition("=")
        if not sep or name not in by_name or not frame:
            p.error(f"--frame-id {f!r}: expected NAME=FRAME for a sensor given")
        by_name[name].frame_id = frame
    for option, given in (("payload", a.payload), ("gravity", a.gravity)):
        # every sensor's first, then the named ones', whatever their order
        for name, v in sorted(given, key=lambda nv: nv[0] is not None):
            if name is not None and name not in by_name:
                p.error(f"--{option} {name}=...: no sensor named {name!r}")
            for spec in ([by_name[name]] if name is not None else specs):
                setattr(spec, option, v)
    domain = a.domain
    if domain is None:
        env = os.environ.get("ROS_DOMAIN_ID", "0") or "0"
        if not env.isdigit():
            p.error(f"ROS_DOMAIN_ID={env!r} is not a number")
        domain = int(env)
    try:
        namespace = rz.normalize_namespace(a.namespace)
    except ValueError as e:
        p.error(str(e))
    wants_net = bool(a.zenoh or a.connect or a.listen or a.scout or a.zenoh_config)
    if a.no_zenoh and wants_net:
        p.error("--no-zenoh with --zenoh/--connect/--listen/--scout/--zenoh-config")
    others = a.mcap is not None or a.dds or a.foxglove is not None
    zopts = None
    if not a.no_zenoh and (wants_net or not others):
        from .bridge import ZenohOptions

        zopts = ZenohOptions(mode=a.mode, connect=a.connect, listen=a.listen, scout=a.scout,
                             config_file=a.zenoh_config)
        if a.zenoh_config is not None:
            try:
                zopts.config()
            except ValueError as e:
                p.error(str(e))
    if not others and zopts is None:
        p.error("--no-zenoh needs --mcap FILE, --dds or --foxglove")
    dds_opts = None
    if a.dds_interface is not None and not a.dds:
        p.error("--dds-interface needs --dds")
    if a.dds:
        from .dds import DdsOptions, config_xml

        try:
            config_xml(a.dds_interface)
        except ValueError:
            p.error(f"--dds-interface {a.dds_interface!r}: expected an IP address")
        dds_opts = DdsOptions(interface=a.dds_interface, distro=a.ros_distro, impl=a.dds_impl)
    elif a.dds_impl != "auto":
        p.error("--dds-impl needs --dds")
    fox = None
    if a.foxglove is not None:
        from .foxglove_out import parse_address

        try:
            fox = parse_address(a.foxglove)
        except ValueError as e:
            p.error(str(e))
    opts = NodeOptions(domain=domain, namespace=namespace, tare_samples=a.retare or 100,
                       tare_at_start=a.tare, lowpass_hz=a.lowpass, rotation=a.rotate,
                       latency_s=a.latency, limits=_limits(p, a.limit),
                       read_only=a.read_only)

    dds_impl = ""
    if dds_opts is not None:
        from .dds import choose_impl

        try:
            dds_impl = choose_impl(dds_opts)[0]
        except ValueError as e:
            print(f"{PROG}: {e}", file=sys.stderr)
            return 2
    for wanted, module, package in ((dds_impl == "cyclone", "cyclonedds", "cyclonedds"),
                                    (a.foxglove is not None, "foxglove", "foxglove-sdk")):
        if wanted:
            try:
                __import__(module)
            except ImportError:
                print(f"{PROG}: {'--dds' if module == 'cyclonedds' else '--foxglove'} needs "
                      f"the {package} package (Python >= 3.10): "
                      "pip install \"leptrino[bridge]\"", file=sys.stderr)
                return 2

    from ..errors import LeptrinoError
    from .bridge import Bridge

    try:
        bridge = Bridge(specs, opts, zopts, a.mcap, a.overwrite, dds_opts=dds_opts, foxglove=fox)
    except (LeptrinoError, OSError, ValueError, TypeError) as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return exit_code(e)
    except Exception as e:  # zenoh.ZError: a bad endpoint, a port in use
        print(f"{PROG}: zenoh: {e}", file=sys.stderr)
        return 2

    def on_signal(signum: int, frame: Any) -> None:
        bridge.stop()

    old = {sig: signal.signal(sig, on_signal) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        bridge.start()
        names = ", ".join(s.name for s in specs)
        reached = False
        if bridge.session is not None:
            print(f"{PROG}: zenoh session {bridge.zid}, domain {domain}, namespace "
                  f"{namespace}: {names}", file=sys.stderr)
            reached = bool(bridge.reachable())
            if not reached:
                where = ", ".join(zopts.connect) if zopts and zopts.connect else (
                    f"--zenoh-config {zopts.config_file}" if zopts and zopts.config_file else
                    "tcp/127.0.0.1:7447" if zopts and not zopts.scout else "scouting")
                print(f"{PROG}: warning: no Zenoh router or peer reachable ({where}): nobody "
                      "can receive the topics until one is (start `ros2 run rmw_zenoh_cpp "
                      "rmw_zenohd`, or give --connect / --listen / --scout)", file=sys.stderr)
        if bridge.dds is not None:
            how = (f"{bridge.dds_impl}" if bridge.dds_impl != "cyclone" else
                   f"cyclone, {a.ros_distro} node announcement")
            print(f"{PROG}: DDS domain {domain} through {how} ({bridge.dds_why}), "
                  f"namespace {namespace}: {names}", file=sys.stderr)
        if bridge.foxglove is not None:
            print(f"{PROG}: Foxglove: ws://{bridge.foxglove.host}:{bridge.foxglove.port}",
                  file=sys.stderr)
        bridge.wait(a.duration)
        if bridge.session is not None and not reached and bridge.reachable():
            reached = True
        if bridge.session is not None and not reached:
            print(f"{PROG}: warning: no Zenoh router or peer was reached during the run: "
                  "nothing published was received", file=sys.stderr)
    finally:
        bridge.close()
        for sig, h in old.items():
            signal.signal(sig, h)
    if bridge.mcap is not None:
        print(f"{PROG}: {bridge.mcap.path}: {bridge.mcap.messages} messages", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
