"""One sensor on the network: a ROS 2 node with its topics and services.

A SensorNode opens a leptrino.Sensor (the library's session does the tare,
the low-pass, the rotation, the reconnects, the health and the timestamps)
and runs one thread that reads the session in batches and turns each batch,
in one C call (wrench_batch.py), into two geometry_msgs/WrenchStamped
messages per sample (`wrench`: the session's processed values;
`wrench_raw`: the raw counts in N and N·m), handed to the outputs: Zenoh
publishers in rmw_zenoh's layout, an MCAP file, DDS writers, Foxglove
channels. The bridge calls publish_diagnostics() once a second, and the
tare/untare services and command topics call tare()/untare() from the
transports' threads (the session allows that beside the reading thread).
A tool's weight is removed by the session (SensorSpec.payload, gravity from
the `gravity` input: gravity_in.py); limit episodes (NodeOptions.limits)
show in the diagnostics, published at once when one begins or ends.
"""

from __future__ import annotations

import functools
import logging
import math
import threading
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

from .. import _constants as K
from .._backend import get_backend
from ..errors import LeptrinoError
from ..sensor import Sensor
from . import cdr
from . import rmw_zenoh as rz
from .gravity_in import VECTOR3_STAMPED, GravityInput
from .commands import CommandRunner
from .ratelog import RateLimitedLog
from .threadname import name_this_thread
from .transport import Endpoint, NodeRef, Publisher, Request, Transport
from .wrench_batch import WrenchBatch

log = logging.getLogger("leptrino.bridge")
#: The log of what changes a sensor from the network (tare/untare: what, who,
#: when) and of read-only mode, at INFO; the command line shows it always.
AUDIT_LOGGER = "leptrino.bridge.requests"
audit = logging.getLogger(AUDIT_LOGGER)

WRENCH = "geometry_msgs/msg/WrenchStamped"
#: How often the reading thread takes the session's events while data flows
#: (they feed the counters and the log; the session queues them meanwhile).
EVENTS_PERIOD_S = 0.1
DIAGNOSTICS = "diagnostic_msgs/msg/DiagnosticArray"
#: The session's latency budget while nobody listens to `wrench` or `wrench_raw`
#: on any transport (s): fewer wake-ups; limit events and a tare's end are then
#: seen up to this much later, and a new subscriber's first message comes up to
#: this much later. Each wake-up costs far more than the samples it brings
#: (docs/bridge.md, "from the scheduler's accounting": 0.05 -> 0.1 s took the
#: idle reading thread from 0.52 to 0.25 % of a core).
IDLE_LATENCY_S = 0.1
TRIGGER = "std_srvs/srv/Trigger"


@dataclass
class SensorSpec:
    """What to bridge: a name (the node name, the topics' prefix), a serial
    port or virtual sensor options, and the frame_id of its messages."""

    name: str
    port: Optional[str] = None
    sim: Optional[Dict[str, Any]] = None
    frame_id: str = ""
    payload: Optional[Sequence[float]] = None  # mass kg, centre of mass m (sensor frame)
    gravity: Sequence[float] = (0.0, 0.0, -9.80665)  # initial gravity, m/s², sensor frame

    def __post_init__(self) -> None:
        rz.check_name(self.name, "sensor name")
        if (self.port is None) == (self.sim is None):
            raise ValueError(f"sensor {self.name}: give a port or virtual sensor options")
        if not self.frame_id:
            self.frame_id = self.name


@dataclass
class NodeOptions:
    """Per-sensor processing (done by the session) and ROS naming."""

    domain: int = 0
    namespace: str = "/"
    tare_samples: int = 100  # the tare service averages this many samples
    tare_at_start: int = 0  # tare over the first N samples of the stream
    lowpass_hz: float = 0.0
    rotation: Optional[Sequence[float]] = None  # roll, pitch, yaw (rad)
    latency_s: float = 0.002  # how long the session may hold samples back
    limits: Optional[Sequence[float]] = None  # fx..mz, N and N·m, 0 = none (set_limits)
    qos_depth: int = 10
    timeout_s: float = 0.5
    data_timeout_s: float = 1.0
    #: serve and subscribe to nothing that changes a sensor (no tare/untare
    #: service or command topic, no gravity input) on any transport
    read_only: bool = False


AXES = ("fx", "fy", "fz", "mx", "my", "mz")


def axis_names(bits: int) -> str:
    """"fz,mz" for the axes whose bits are set; "" for none."""
    return ",".join(a for i, a in enumerate(AXES) if bits >> i & 1)


class Topic:
    """One topic of a node on every transport: its publishers; a batch goes
    to those with someone listening, the others count it as skipped."""

    __slots__ = ("name", "ros_type", "pubs", "skipped")

    def __init__(self, name: str, ros_type: str, pubs: Sequence[Tuple[str, Publisher]]) -> None:
        self.name = name
        self.ros_type = ros_type
        self.pubs = list(pubs)  # (transport name, publisher)
        self.skipped: Dict[str, int] = {t: 0 for t, _ in pubs}

    @property
    def listening(self) -> bool:
        """Whether any transport has someone listening now."""
        for _, p in self.pubs:
            if p.listening:
                return True
        return False

    def skip(self, n: int) -> None:
        """n messages nobody listens to on any transport (not serialized)."""
        for t in self.skipped:
            self.skipped[t] += n

    def send(self, payload: bytes, stamp_ns: int) -> None:
        self.send_batch((payload,), (stamp_ns,))

    def send_batch(self, payloads: Sequence[bytes], stamps: Sequence[int]) -> None:
        """Publish a batch where someone listens: one time of publication."""
        now = time.time_ns()
        for t, p in self.pubs:
            if p.listening:
                p.publish(payloads, stamps, now)
            else:
                self.skipped[t] += len(payloads)

    def close(self) -> None:
        for _, p in self.pubs:
            try:
                p.close()
            except Exception:  # the transport may be closing
                pass
        self.pubs = []


#: The answer to a tare or untare that comes while another is being served.
BUSY = "busy: another tare or untare is being served; ask again"


@dataclass
class Counters:
    """What the node itself saw (the session's health has the sensor's side)."""

    samples: int = 0
    read_errors: int = 0
    last_error: str = ""
    events: Dict[str, int] = field(default_factory=dict)
    tare_requests: int = 0
    tare_busy: int = 0  # tare/untare requests refused: another was being served
    rejected_requests: int = 0  # malformed service requests (DDS, Zenoh) ignored
    last_sample_mono: float = 0.0
    limit_axes: int = 0  # bit i: axis i beyond its limit in the current episode
    last_limit_axes: int = 0  # the axes of the last episode begun
    last_request: str = ""  # the last tare/untare from the network: what, who, when, result
    lock: threading.Lock = field(default_factory=threading.Lock, repr=False, compare=False)

    def bump(self, name: str, n: int = 1) -> None:
        """Add n to a counter that several threads update (under the lock)."""
        with self.lock:
            setattr(self, name, getattr(self, name) + n)


class SensorNode:
    """A sensor, its ROS 2 node (liveliness), topics and services.

    Construction opens the sensor (raises what leptrino.Sensor raises);
    declare() declares the node, topics and services on the outputs; start()
    starts the stream and the reading thread; stop() ends the thread; close()
    stops the stream, undeclares and closes the sensor.
    """

    def __init__(self, spec: SensorSpec, opts: NodeOptions) -> None:
        self.spec = spec
        self.opts = opts
        self.counters = Counters()
        self._refusal_log = RateLimitedLog()  # malformed requests: one line per 5 s at most
        self._stop = threading.Event()
        self._thread: Optional[threading.Thread] = None
        self._lock = threading.Lock()  # tare/untare from service threads
        # requests from the network: one served at a time (in this thread), the others
        # answered busy at once, on every transport
        self._requests: Optional[CommandRunner] = None
        self._gate = threading.Lock()
        self._in_flight = False
        self._transports: List[Transport] = []
        self.node_ref: Optional[NodeRef] = None
        self.wrench: Optional[Topic] = None
        self.wrench_raw: Optional[Topic] = None
        self.diagnostics: Optional[Topic] = None
        self.sensor = Sensor(
            spec.port, opts.timeout_s, sim=spec.sim, tare=opts.tare_at_start,
            lowpass=opts.lowpass_hz, rotation=opts.rotation, degrees=False, reconnect=True,
            latency=opts.latency_s, data_timeout=opts.data_timeout_s)
        try:
            self._batch = WrenchBatch(get_backend(self.sensor.backend), self.sensor.rated,
                                     spec.frame_id)
            self.gravity = self._set_load()
        except ValueError:
            self.sensor.close()
            raise
        self._diag_lock = threading.Lock()  # diagnostics from two threads
        self._tare_done = threading.Event()  # set when the reading thread reads a TARE event
        self._tare_wanted = False

    def _set_load(self) -> GravityInput:
        """Payload, initial gravity and limits into the session (ValueError
        for values it refuses); the gravity input that changes gravity later."""
        spec, s = self.spec, self.sensor
        g = tuple(float(x) for x in spec.gravity)
        if len(g) != 3 or not all(map(math.isfinite, g)) or g == (0.0, 0.0, 0.0):
            raise ValueError(f"sensor {spec.name}: gravity {spec.gravity}: three finite "
                             "numbers, not all zero, expected")
        s.set_gravity(g)
        s.set_payload(spec.payload)
        s.set_limits(self.opts.limits)
        return GravityInput(spec.name, s.set_gravity, g)

    def declare(self, node_id: int, next_entity_id: Callable[[], int],
                transports: Sequence[Transport]) -> None:
        """Declare the node, its topics (`wrench`, `wrench_raw`,
        `diagnostics`), its services (`tare`, `untare`) and its input
        (`gravity`) on each transport; read-only: no service or input at all."""
        spec, opts = self.spec, self.opts
        ns = rz.normalize_namespace(opts.namespace)
        node = NodeRef(ns, spec.name, node_id)
        self.node_ref = node
        self._transports = list(transports)

        def endpoint(topic: str, ros_type: str) -> Endpoint:
            return Endpoint(node, rz.fully_qualified(ns, spec.name, topic), ros_type,
                            next_entity_id(), opts.qos_depth)

        for t in transports:
            t.declare_node(node)

        def topic(name: str, ros_type: str) -> Topic:
            ep = endpoint(name, ros_type)
            return Topic(ep.name, ros_type, [(t.name, t.advertise(ep)) for t in transports])

        self.wrench = topic("wrench", WRENCH)
        self.wrench_raw = topic("wrench_raw", WRENCH)
        self.diagnostics = topic("diagnostics", DIAGNOSTICS)
        if opts.read_only:
            return
        interactive = [t for t in transports if t.interactive]
        if interactive:
            self._requests = CommandRunner(f"bridge-{spec.name}-requests", 1)
        for which in ("tare", "untare"):
            ep = endpoint(which, TRIGGER)
            for t in interactive:
                t.serve(ep, functools.partial(self.on_request, which))
        ep = endpoint("gravity", VECTOR3_STAMPED)
        for t in interactive:
            t.take(ep, self._gravity_handler(t.name))

    # -- life cycle ----------------------------------------------------------
    def start(self) -> None:
        """Start the stream and the reading thread (after declare())."""
        if self.wrench is None:
            raise RuntimeError("declare() first")
        self.sensor.start()
        self._thread = threading.Thread(target=self._run, name=f"bridge-{self.spec.name}",
                                        daemon=True)
        self._thread.start()

    def stop(self, timeout: float = 5.0) -> None:
        """Ask the thread to end and wait for it (up to timeout s)."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout)

    def close(self) -> None:
        """Withdraw the topics, stop the request thread; stop and close the
        sensor (the transports, shared by the nodes, are the bridge's to close)."""
        self._stop.set()
        if self._requests is not None:
            self._requests.stop()
            self._requests = None
        for t in self.wrench, self.wrench_raw, self.diagnostics:
            if t is not None:
                t.close()
        try:
            if not self.sensor.closed and self.sensor.streaming:
                self.sensor.stop()
        except LeptrinoError:
            pass
        self.sensor.close()

    @property
    def alive(self) -> bool:
        return self._thread is not None and self._thread.is_alive()

    # -- data ----------------------------------------------------------------
    def _run(self) -> None:
        """Read the session in batches (Sensor.read_batch); while anyone
        listens to `wrench` or `wrench_raw` on a transport, each batch is
        serialized in one C call and published topic by topic (no Python
        object per sample but the payloads the transports take); while
        nobody does, it is only counted (skipped)."""
        name_this_thread(f"read-{self.spec.name}")
        sensor = self.sensor
        wb = self._batch
        buf = wb.arrays
        t_mono = wb.t_mono
        wrench, wrench_raw, c = self.wrench, self.wrench_raw, self.counters
        assert wrench is not None and wrench_raw is not None
        timeout = max(0.001, self.opts.timeout_s)
        # While nobody listens to the wrench topics nothing is waiting for a sample:
        # the session may hold them longer (fewer wake-ups); back to the latency
        # asked for at the first batch after someone listens again.
        busy_latency = self.opts.latency_s
        idle_latency = max(busy_latency, IDLE_LATENCY_S)
        idle = False
        failing = False
        silent_since = next_events = time.monotonic()
        while not self._stop.is_set():
            try:
                rc = sensor.read_batch(buf, timeout)
            except LeptrinoError:  # closed under us
                break
            n = buf.n
            now = time.monotonic()
            if n:
                if failing:
                    log.warning("%s: data again", self.spec.name)
                    failing = False
                lw, lr = wrench.listening, wrench_raw.listening
                listening = lw or lr
                came = listening and idle
                if listening == idle:
                    idle = not listening
                    try:
                        sensor.latency = idle_latency if idle else busy_latency
                    except (LeptrinoError, ValueError) as e:
                        log.debug("%s: latency: %s", self.spec.name, e)
                if came:
                    # This batch was held while nobody listened (up to the idle budget):
                    # skipped, not sent at once to the listener that came since (a
                    # reliable KEEP_LAST(10) writer would drop all but its last 10 for
                    # a reader that falls behind the burst: samples missing mid-stream).
                    wrench.skip(n)
                    wrench_raw.skip(n)
                elif listening:
                    w, r, stamps = wb.encode(lw, lr)
                    if lw:
                        wrench.send_batch(w, stamps)
                    else:
                        wrench.skip(n)
                    if lr:
                        wrench_raw.send_batch(r, stamps)
                    else:
                        wrench_raw.skip(n)
                else:
                    wrench.skip(n)
                    wrench_raw.skip(n)
                c.samples += n
                c.last_sample_mono = t_mono[n - 1]
                silent_since = now
            # after the batch is counted: a limit event's diagnostics (published at once)
            # must see the samples that came with it, not "no data"; while a tare is
            # served, every batch (its end is the TARE event)
            if not n or now >= next_events or self._tare_wanted:
                self._take_events(sensor.take_events())
                next_events = now + EVENTS_PERIOD_S
            if n:
                continue
            if rc == K.LEP_E_END:
                break
            if rc == K.LEP_E_TIMEOUT and now - silent_since < self.opts.data_timeout_s:
                continue
            # The session reconnects inside its reads; until it is back each
            # read fails or times out. Count it, say it once, go on.
            c.read_errors += 1
            c.last_error = sensor.status_text(rc) if rc != K.LEP_E_TIMEOUT else "no data"
            if not failing:
                log.warning("%s: %s (the session keeps trying)", self.spec.name, c.last_error)
                failing = True
            if rc < 0 and rc != K.LEP_E_TIMEOUT:
                self._stop.wait(0.05)

    def _take_events(self, evs: Sequence[Any]) -> None:
        for ev in evs:
            self.counters.events[ev.type] = self.counters.events.get(ev.type, 0) + 1
            if ev.type == "tare":
                self._tare_done.set()
            elif ev.type in ("disconnected", "reconnected"):
                log.warning("%s: %s", self.spec.name, ev.type)
            elif ev.type in ("limit_exceeded", "limit_cleared"):
                self._limit_event(ev)

    def _limit_event(self, ev: Any) -> None:
        """A limit episode begins or ends: the diagnostics say it at once
        (stamped with the event's time), so that a short episode is seen
        and recorded (MCAP) even between two periodic diagnostics."""
        c = self.counters
        if ev.type == "limit_exceeded":
            c.limit_axes = c.last_limit_axes = int(ev.axes)
            log.info("%s: beyond limit: %s", self.spec.name, axis_names(ev.axes))
        else:
            c.limit_axes = 0
        self.publish_diagnostics(int(ev.t_utc * 1e9))

    # -- diagnostics -----------------------------------------------------------
    def diagnostic_status(self) -> cdr.DiagStatus:
        """This sensor's DiagnosticStatus, from the session's health and tare."""
        h = self.sensor.health
        offsets = self.sensor.tare_offsets
        c = self.counters
        now = time.monotonic()
        silent = c.last_sample_mono == 0.0 or now - c.last_sample_mono > 1.0
        if silent:
            level, msg = cdr.ERROR, "no data (disconnected or stalled)"
        elif c.limit_axes:
            level, msg = cdr.WARN, f"beyond limit: {axis_names(c.limit_axes)}"
        elif h.shortfall:
            level, msg = cdr.WARN, "rate below nominal"
        else:
            level, msg = cdr.OK, "streaming"
        info = self.sensor.product_info
        values = [
            ("measured_rate_hz", f"{h.measured_hz:.2f}"),
            ("recent_rate_hz", f"{h.recent_hz:.2f}"),
            ("nominal_rate_hz", f"{h.nominal_hz:.2f}"),
            ("received", str(h.received)),
            ("published", str(c.samples)),
            ("lost", str(h.lost)),
            ("gaps", str(h.gaps)),
            ("max_gap_s", f"{h.max_gap_s:.4f}"),
            ("errors", str(h.errors)),
            ("overloads", str(h.overloads)),
            ("disconnects", str(h.disconnects)),
            ("reconnects", str(h.reconnects)),
            ("tared", "true" if any(offsets) else "false"),
            ("read_only", "true" if self.opts.read_only else "false"),
            ("tare_requests", str(c.tare_requests)),
            ("tare_busy", str(c.tare_busy)),
            ("last_request", c.last_request),
        ]
        values += [(f"tare_offset_{a}", f"{v:g}") for a, v in
                   zip(("fx", "fy", "fz", "mx", "my", "mz"), offsets)]
        values.append(("rejected_requests", str(c.rejected_requests)))
        for topic in self.wrench, self.wrench_raw, self.diagnostics:
            if topic is not None:  # messages nobody listened to: not serialized nor sent
                values += [(f"skipped_{t}_{topic.name.rsplit('/', 1)[-1]}", str(n))
                           for t, n in topic.skipped.items()]
        if self.node_ref is not None:
            for t in self._transports:
                values += t.diagnostics(self.node_ref)
        values += self._load_values(h)
        values += [("model", info.model), ("serial", info.serial),
                   ("firmware", info.firmware), ("port", self.sensor.port)]
        return (level, f"leptrino: {self.spec.name}", msg, info.serial or self.spec.name,
                values)

    def _load_values(self, h: Any) -> List[Tuple[str, str]]:
        """Payload, gravity input and limits, for the diagnostics."""
        c, p = self.counters, self.spec.payload
        limits = [float(v) for v in (self.opts.limits or [0.0] * K.LEP_AXES)]
        return [
            ("payload", "none" if not p else
             f"{float(p[0]):g} kg at {float(p[1]):g} {float(p[2]):g} {float(p[3]):g} m"),
            *self.gravity.values(),
            ("limits", ",".join(f"{a}={v:g}" for a, v in zip(AXES, limits) if v > 0) or "none"),
            ("beyond_limit", axis_names(c.limit_axes)),
            ("limit_episodes", str(h.limit_episodes)),
            ("last_limit_axes", axis_names(c.last_limit_axes)),
        ]

    def publish_diagnostics(self, stamp_ns: Optional[int] = None) -> None:
        """One DiagnosticArray (stamped now, or at stamp_ns); from the
        bridge's 1 Hz thread and from the reading thread at a limit event."""
        ns = time.time_ns() if stamp_ns is None else stamp_ns
        sec, nsec = divmod(ns, 1_000_000_000)
        topic = self.diagnostics
        if topic is not None and not topic.listening:
            topic.skip(1)  # nobody listens on any transport: not even made
            return
        with self._diag_lock:
            payload = cdr.encode_diagnostic_array(sec, nsec, self.spec.frame_id,
                                                  [self.diagnostic_status()])
            if self.diagnostics is not None:
                self.diagnostics.send(payload, ns)

    # -- services ------------------------------------------------------------
    def tare(self, requester: str = "") -> Tuple[bool, str]:
        """Tare over opts.tare_samples samples of the running stream; waits
        (at most 3 s) for the average and returns (success, message); at once
        (False, "busy: ...") while another tare or untare is being served.
        requester: who asked, from the transport (see _record_request)."""
        t_ns = time.time_ns()
        if not self._serve_one("tare", requester):
            return False, BUSY
        try:
            self.counters.bump("tare_requests")
            result = self._tare_locked()
        finally:
            self._lock.release()
        self._record_request("tare", requester, t_ns, result)
        return result

    def _tare_locked(self) -> Tuple[bool, str]:
        if not self.alive:
            return False, "the sensor is not streaming"
        self._tare_done.clear()
        self._tare_wanted = True  # the reading thread takes the events every batch
        try:
            try:
                self.sensor.tare(self.opts.tare_samples, wait=False)
            except (LeptrinoError, ValueError) as e:
                return False, f"tare failed: {e}"
            # its end is the session's TARE event, read by the reading thread (an
            # event of an earlier untare, read meanwhile, is not it: taring still)
            end = time.monotonic() + 3.0
            while self._tare_done.wait(max(0.0, end - time.monotonic())) and \
                    self.sensor.taring:
                self._tare_done.clear()
            if self.sensor.taring:
                return False, "tare started but no samples came within 3 s"
        finally:
            self._tare_wanted = False
        try:
            offs = ", ".join(f"{v:g}" for v in self.sensor.tare_offsets)
        except LeptrinoError as e:  # the bridge is closing the sensor meanwhile
            return False, f"tare not finished: {e}"
        return True, f"tared over {self.opts.tare_samples} samples; offsets (counts): {offs}"

    def untare(self, requester: str = "") -> Tuple[bool, str]:
        """Remove the tare; (False, "busy: ...") while a tare is being served."""
        t_ns = time.time_ns()
        if not self._serve_one("untare", requester):
            return False, BUSY
        try:
            self.sensor.untare()
            result = True, "tare removed"
        except LeptrinoError as e:
            result = False, f"untare failed: {e}"
        finally:
            self._lock.release()
        self._record_request("untare", requester, t_ns, result)
        return result

    def _serve_one(self, what: str, requester: str) -> bool:
        """Take the node's lock for a tare or untare, or refuse at once: one is
        served at a time and the others answered, not queued, so a flood of
        requests cannot hold every transport's threads 3 s each. A refusal is
        counted (tare_busy) and logged at most every 5 s, not recorded."""
        if self._lock.acquire(blocking=False):
            return True
        self.counters.bump("tare_busy")
        self._refusal_log.warning("%s/%s by %s refused: busy with another", self.spec.name, what,
                                  requester or "the bridge")
        return False

    def _record_request(self, what: str, requester: str, t_ns: int,
                        result: Tuple[bool, str]) -> None:
        """A tare/untare from the network (requester given): logged (INFO)
        with its time and requester, kept in the diagnostics' last_request,
        and the diagnostics published at once (stamped then), so that the
        MCAP file and every transport have it as an event."""
        if not requester:
            return
        when = time.strftime("%Y-%m-%dT%H:%M:%S", time.gmtime(t_ns // 1_000_000_000))
        when += f".{t_ns // 1_000_000 % 1000:03d}Z"
        text = f"{what} by {requester} at {when}: {'done' if result[0] else 'failed'}"
        with self.counters.lock:
            self.counters.last_request = text
        audit.info("%s: %s (%s)", self.spec.name, text, result[1])
        try:
            self.publish_diagnostics(t_ns)
        except Exception as e:  # the outputs may be closing
            log.warning("%s: diagnostics: %s", self.spec.name, e)

    def _gravity_handler(self, transport: str) -> Callable[[bytes, str], None]:
        def on_payload(payload: bytes, refuse: str) -> None:
            self.gravity.receive(payload, transport, refuse)
        return on_payload

    def on_request(self, which: str, req: Request) -> None:
        """A tare or untare request from a transport (its thread): a request
        that cannot be read is counted and refused; while another is served
        it is answered busy at once (counted); else served in this node's
        request thread, then answered."""
        why = req.error
        if not why:
            try:
                cdr.check_encapsulation(req.payload)
            except ValueError as e:
                why = str(e)
        if why:
            self._refusal_log.warning("%s/%s: request refused: %s", self.spec.name, which, why)
            self._rejected_request()
            req.refuse(why)
            return
        who = req.requester
        with self._gate:
            busy, self._in_flight = self._in_flight, True
        runner = self._requests
        if not busy and (runner is None or not runner.submit(
                f"{self.spec.name}/{which}", lambda: self._serve(which, req))):
            with self._gate:
                self._in_flight = False
            busy = True
        if busy:
            self.counters.bump("tare_busy")
            self._refusal_log.warning("%s/%s by %s refused: busy with another",
                                      self.spec.name, which, who or "the bridge")
            req.reply(cdr.encode_trigger_response(False, BUSY))

    def _serve(self, which: str, req: Request) -> str:
        try:
            ok, message = self.tare(req.requester) if which == "tare" else \
                self.untare(req.requester)
        finally:
            with self._gate:
                self._in_flight = False
        req.reply(cdr.encode_trigger_response(ok, message))
        return message

    def _rejected_request(self) -> None:
        self.counters.bump("rejected_requests")  # (the caller logs, rate-limited)
