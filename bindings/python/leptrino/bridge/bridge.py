"""The bridge: a Zenoh session and/or an MCAP file, and one SensorNode per sensor."""

from __future__ import annotations

import itertools
import json
import logging
import os
import threading
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, List, Optional, Tuple

from .mcap_out import FileExistsRefused, McapRecorder, McapTransport
from .threadname import name_this_thread
from .node import AUDIT_LOGGER, NodeOptions, SensorNode, SensorSpec
from .transport import Transport

if TYPE_CHECKING:
    from .dds import DdsOptions
    from .foxglove_out import FoxgloveTransport
    from .zenoh_transport import ZenohTransport

log = logging.getLogger("leptrino.bridge")


@dataclass
class ZenohOptions:
    """How the Zenoh session is opened. Multicast scouting stays off unless
    scout; with no endpoints a peer connects to a router on
    tcp/127.0.0.1:7447, as rmw_zenoh's sessions do. mode None: peer.

    config_file: a Zenoh configuration file (JSON5, as zenoh documents it:
    TLS, authentication, access control...) read first. The bridge's defaults
    then fill in only what it leaves out (mode peer, scouting off, no
    listening, and the router on tcp/127.0.0.1:7447 when it sets no endpoint
    at all); mode, connect, listen and scout, when given, apply on top, and
    one that contradicts a value the file sets is a ValueError."""

    mode: Optional[str] = None
    connect: List[str] = field(default_factory=list)
    listen: List[str] = field(default_factory=list)
    scout: bool = False
    config_file: Optional[str] = None

    def config(self) -> Any:
        import zenoh

        if self.mode not in (None, "peer", "client"):
            raise ValueError(f"mode {self.mode!r}: peer or client")
        if self.config_file is not None:
            return self._from_file(zenoh)
        mode = self.mode or "peer"
        conf = zenoh.Config()
        conf.insert_json5("mode", json.dumps(mode))
        connect = self.connect or (["tcp/127.0.0.1:7447"] if not self.scout else [])
        conf.insert_json5("connect/endpoints", json.dumps(connect))
        if mode == "peer":
            conf.insert_json5("listen/endpoints", json.dumps(self.listen))
        elif self.listen:
            raise ValueError("--listen needs --mode peer (a client does not listen)")
        conf.insert_json5("scouting/multicast/enabled", json.dumps(bool(self.scout)))
        return conf

    def _from_file(self, zenoh: Any) -> Any:
        path = str(self.config_file)
        if not os.path.isfile(path):
            raise ValueError(f"--zenoh-config {path}: no such file")
        try:
            conf = zenoh.Config.from_file(path)
        except Exception as e:  # zenoh.ZError: JSON5 syntax, unknown key, bad value
            raise ValueError(f"--zenoh-config {path}: {str(e).strip()}") from None
        default = zenoh.Config()

        def set_by_file(key: str) -> Any:
            """The file's value of key, or None where it leaves Zenoh's default."""
            v = json.loads(conf.get_json(key))
            return None if v == json.loads(default.get_json(key)) or v == [] else v

        def conflict(flag: str, key: str, value: Any) -> ValueError:
            return ValueError(f"{flag} contradicts {key} = {json.dumps(value)} in --zenoh-config "
                              f"{path}: set it in one place")

        f_mode = set_by_file("mode")
        if self.mode is not None and f_mode is not None and f_mode != self.mode:
            raise conflict(f"--mode {self.mode}", "mode", f_mode)
        mode = self.mode or f_mode or "peer"
        if mode not in ("peer", "client"):
            raise ValueError(f"--zenoh-config {path}: mode {mode!r}: the bridge is a peer or a "
                             "client")
        conf.insert_json5("mode", json.dumps(mode))
        f_scout = set_by_file("scouting/multicast/enabled")
        if self.scout and f_scout is False:
            raise conflict("--scout", "scouting.multicast.enabled", f_scout)
        conf.insert_json5("scouting/multicast/enabled",
                          json.dumps(bool(self.scout or f_scout)))
        f_eps = {}
        for kind, given in (("connect", self.connect), ("listen", self.listen)):
            f_eps[kind] = set_by_file(f"{kind}/endpoints")
            if given and f_eps[kind] is not None and f_eps[kind] != given:
                raise conflict(f"--{kind} {' '.join(given)}", f"{kind}.endpoints", f_eps[kind])
        if self.listen and mode == "client":
            raise ValueError("--listen needs --mode peer (a client does not listen)")
        if self.connect:
            conf.insert_json5("connect/endpoints", json.dumps(self.connect))
        elif f_eps["connect"] is None and f_eps["listen"] is None and not self.listen \
                and not self.scout and not f_scout:
            conf.insert_json5("connect/endpoints", json.dumps(["tcp/127.0.0.1:7447"]))
        if f_eps["listen"] is None and mode == "peer":
            conf.insert_json5("listen/endpoints", json.dumps(self.listen))
        return conf


def open_session(zopts: ZenohOptions) -> Any:
    import zenoh

    return zenoh.open(zopts.config())


class Bridge:
    """Sensors to Zenoh (rmw_zenoh layout), DDS (ROS 2 on DDS), Foxglove live and/or MCAP.

    zenoh_opts None: no network at all. mcap_path: record there (refusing
    an existing file unless force). Construction opens everything (and undoes
    it on a failure); start() starts the streams and the 1 Hz diagnostics;
    close() stops every stream, undeclares, closes the session and finishes
    the MCAP file. Also a context manager.
    """

    def __init__(self, sensors: List[SensorSpec], node_opts: Optional[NodeOptions] = None,
                 zenoh_opts: Optional[ZenohOptions] = None, mcap_path: Optional[str] = None,
                 force: bool = False, diagnostics_period_s: float = 1.0,
                 dds_opts: Optional[DdsOptions] = None,
                 foxglove: Optional[Tuple[str, int]] = None) -> None:
        if not sensors:
            raise ValueError("no sensors: give --sensor NAME=PORT or --sim NAME")
        names = [s.name for s in sensors]
        dup = {n for n in names if names.count(n) > 1}
        if dup:
            raise ValueError(f"sensor names must differ: {', '.join(sorted(dup))}")
        if zenoh_opts is None and mcap_path is None and dds_opts is None and foxglove is None:
            raise ValueError("nothing to do: no Zenoh, DDS, Foxglove or MCAP output")
        self.opts = node_opts or NodeOptions()
        self.period = diagnostics_period_s
        self.session: Any = None
        self.zenoh: Optional[ZenohTransport] = None
        self.mcap: Optional[McapRecorder] = None
        #: the DDS transport (dds.DdsTransport or rclpy_transport.RclpyTransport)
        self.dds: Optional[Transport] = None
        #: which one runs ("rclpy (rmw_fastrtps_cpp)", "cyclone"), and why it was chosen
        self.dds_impl = ""
        self.dds_why = ""
        self.foxglove: Optional[FoxgloveTransport] = None
        #: every transport, in the order the nodes declare on them
        self.transports: List[Transport] = []
        self.nodes: List[SensorNode] = []
        self._stop = threading.Event()
        self._diag: Optional[threading.Thread] = None
        if mcap_path is not None and not force and os.path.lexists(mcap_path):
            raise FileExistsRefused(f"{mcap_path}: already exists; not overwritten (choose another "
                                    "name, or --overwrite)")
        ids = itertools.count(100)
        if self.opts.read_only:
            logging.getLogger(AUDIT_LOGGER).info(
                "read-only: no tare/untare service, command topic or gravity input is "
                "declared on any transport")
        try:
            # the sensors first: a sensor that cannot be opened leaves no file
            for spec in sensors:
                self.nodes.append(SensorNode(spec, self.opts))
            if zenoh_opts is not None:
                from .zenoh_transport import ZenohTransport

                self.session = open_session(zenoh_opts)
                self.zenoh = ZenohTransport(self.session, self.opts.domain)
                self.transports.append(self.zenoh)
            if foxglove is not None:  # the port is taken now: a failure leaves no file
                from .foxglove_out import FoxgloveTransport

                self.foxglove = FoxgloveTransport(*foxglove, inputs=not self.opts.read_only)
                self.transports.append(self.foxglove)
            if dds_opts is not None:
                from .dds import choose_impl

                impl, self.dds_why = choose_impl(dds_opts)
                if impl == "rclpy":
                    from .rclpy_transport import RclpyTransport

                    rt = RclpyTransport(self.opts.domain, dds_opts.interface)
                    self.dds, self.dds_impl = rt, rt.impl
                else:
                    from .dds import DdsTransport

                    self.dds, self.dds_impl = DdsTransport(self.opts.domain, dds_opts), "cyclone"
                log.info("DDS: %s (%s)", self.dds_impl, self.dds_why)
                self.transports.append(self.dds)
            if mcap_path is not None:  # last: whatever failed before, no file was made
                self.mcap = McapRecorder(mcap_path, force)
                self.transports.append(McapTransport(self.mcap))
            for i, node in enumerate(self.nodes):
                node.declare(i, lambda: next(ids), self.transports)
            for t in self.transports:
                t.ready()
        except BaseException:
            self.close()
            raise

    def __enter__(self) -> Bridge:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def reachable(self) -> List[str]:
        """The Zenoh routers and peers this session is connected to now (ids);
        empty: nobody can receive what the bridge publishes."""
        return self.zenoh.reachable() if self.zenoh is not None else []

    @property
    def zid(self) -> str:
        return str(self.session.zid()) if self.session is not None else ""

    def start(self) -> None:
        for n in self.nodes:
            n.start()
        self._diag = threading.Thread(target=self._diagnostics, name="bridge-diagnostics",
                                      daemon=True)
        self._diag.start()

    def _diagnostics(self) -> None:
        name_this_thread("diagnostics")
        next_t = time.monotonic() + self.period
        while not self._stop.wait(max(0.0, next_t - time.monotonic())):
            next_t += self.period
            for n in self.nodes:
                try:
                    n.publish_diagnostics()
                except Exception as e:  # one sensor's trouble must not stop the others'
                    log.warning("%s: diagnostics: %s", n.spec.name, e)

    def wait(self, duration: Optional[float] = None) -> None:
        """Block until stop() (e.g. from a signal handler) or duration s."""
        self._stop.wait(duration)

    def stop(self) -> None:
        """Ask everything to stop (safe from a signal handler or another thread)."""
        self._stop.set()

    def close(self) -> None:
        """Stop the streams, undeclare, close the session, finish the MCAP. Idempotent."""
        self._stop.set()
        if self._diag is not None:
            self._diag.join(3.0)
            self._diag = None
        for n in self.nodes:
            n.stop()
        for n in self.nodes:
            n.close()
        self.nodes = []
        if not self.transports and self.session is not None:  # opened, not yet a transport
            try:
                self.session.close()
            except Exception:
                pass
        for t in reversed(self.transports):
            try:
                t.close()
            except Exception as e:
                log.warning("%s: close: %s", t.name, e)
        self.transports = []
        self.session = self.zenoh = self.dds = self.foxglove = None
