"""Figures of leptrino-bridge on this machine (loopback only, bounded).

    python bench/bridge_bench.py            # all figures (about 2 min)
    python bench/bridge_bench.py --cost     # one sensor: nobody / one subscriber (2.5 min)
    python bench/bridge_bench.py --quick    # a smoke run of both (about 25 s)

The virtual sensors run in this process (leptrino.Simulator, each on its
pty); the bridge runs as its own process (`python -m leptrino.bridge
--sensor NAME=PTY ...`) connected to a Zenoh router this process opens on
127.0.0.1, and a subscriber here receives every message. Measured:

- CPU of the bridge process per sensor (ns on a CPU from the scheduler's
  /proc/PID/task/TID/schedstat, over wall time), and by thread with its
  wake-ups: the bridge's reading thread (`read`: the session's read, the
  serialization, the puts), its diagnostics thread, zenoh's own runtime
  threads (tx sends, rx receives, ...);
- --cost: one sensor, nobody subscribed then one subscriber on
  NAME/wrench, phases interleaved, each kind's median and ratio to
  `leptrino stream` beside it, and how soon a new subscriber gets data;
- latency from a sample's arrival (its header stamp: the session's UTC time
  of the sample) to the subscriber's receipt, p50 and p99;
- the largest number of sensors bridged without loss: every sensor's
  sequence numbers contiguous at the subscriber, the measured rate within
  2 % of 1200 Hz, and at most 0.1 % of the samples reported lost by the
  session (the machine's load; reported beside).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import socket
import struct
import subprocess
import sys
import threading
import time
from typing import Any, Dict, List, Optional, Tuple

from leptrino.bridge.rmw_zenoh import parse_attachment


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _threads(pid: int) -> Dict[str, Tuple[int, int]]:
    """Per thread name of a process: (nanoseconds on a CPU, times it was put
    on a CPU), summed over the threads of that name, from
    /proc/PID/task/TID/schedstat (the scheduler's own accounting in ns, not
    clock ticks: a thread that runs 20 us at a time between ticks is
    counted too). Names as the threads set them with the number dropped:
    the bridge's (`read-NAME` -> "read", "diagnostics", "requests", "python"
    for the interpreter's main thread), zenoh's runtime ("tx", "rx", "net",
    "acc", "app"...). A thread that ended between two readings is lost to
    both; none do while the bridge runs."""
    out: Dict[str, Tuple[int, int]] = {}
    for tid in os.listdir(f"/proc/{pid}/task"):
        try:
            with open(f"/proc/{pid}/task/{tid}/comm") as f:
                name = f.read().strip().split("-")[0]
            with open(f"/proc/{pid}/task/{tid}/schedstat") as f:
                run_ns, _wait_ns, slices = (int(x) for x in f.read().split()[:3])
        except (OSError, ValueError):  # the thread ended meanwhile
            continue
        ns0, sl0 = out.get(name, (0, 0))
        out[name] = (ns0 + run_ns, sl0 + slices)
    return out


def _tick_seconds(pid: int) -> float:
    """User + system time of a process in clock ticks (/proc/PID/stat), as
    `top` and rusage count it: printed beside the schedstat figures only to
    show how far the two differ for processes that run in slices much
    shorter than a tick."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _cpu_ns(pid: int) -> int:
    """Nanoseconds on a CPU of a process's threads (schedstat, see _threads)."""
    return sum(ns for ns, _ in _threads(pid).values())


def _thread_delta(a: Dict[str, Tuple[int, int]], b: Dict[str, Tuple[int, int]],
                  dt: float) -> Dict[str, Tuple[float, float]]:
    """Per thread name between two readings: (share of a core, wake-ups/s)."""
    return {k: ((ns - a.get(k, (0, 0))[0]) / 1e9 / dt, (sl - a.get(k, (0, 0))[1]) / dt)
            for k, (ns, sl) in b.items()}


def _stamp_ns(payload: bytes) -> int:
    sec, nsec = struct.unpack_from("<iI", payload, 4)
    return int(sec) * 1_000_000_000 + int(nsec)


class _Sink:
    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.seqs: Dict[str, List[int]] = {}
        self.latency_ns: List[int] = []
        self.diag: Dict[str, bytes] = {}

    def __call__(self, sample: Any) -> None:
        now = time.time_ns()
        key = str(sample.key_expr)
        payload = bytes(sample.payload.to_bytes())
        seq = parse_attachment(bytes(sample.attachment.to_bytes()))[0]
        with self.lock:
            self.seqs.setdefault(key, []).append(seq)
            if "/wrench/" in key:
                self.latency_ns.append(now - _stamp_ns(payload))
            elif "/diagnostics/" in key:
                self.diag[key] = payload


def _diag_values(payload: bytes) -> Dict[str, str]:
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    msg: Any = ts.deserialize_cdr(payload, "diagnostic_msgs/msg/DiagnosticArray")
    return {v.key: v.value for v in msg.status[0].values}


#: Ports one `leptrino stream` takes (its CLI_MAX_SENSORS).
STREAM_MAX_SENSORS = 8


def _stream_args(ports: List[str], latency_s: str) -> List[str]:
    """`leptrino stream` writing CSV for the same kind of sensors, as the
    reference the bridge's cost is compared with."""
    from leptrino._tools import program_path

    args = [str(program_path("leptrino")), "stream", *ports, "--reconnect", "--latency",
            str(max(0, int(round(float(latency_s) * 1000)))), "-o", os.devnull]
    return args


def dds_reader(domain: int, n: int, seconds: float) -> int:
    """A Cyclone DDS reader of every sN/wrench and sN/wrench_raw (a child
    process of the benchmark, on 127.0.0.1): counts the samples, prints them
    as JSON after seconds."""
    from cyclonedds.core import Qos
    from cyclonedds.domain import Domain, DomainParticipant
    from cyclonedds.qos import Policy
    from cyclonedds.sub import DataReader
    from cyclonedds.topic import Topic

    from leptrino.bridge.dds import _Types, config_xml

    dom = Domain(domain, config_xml("127.0.0.1"))
    p = DomainParticipant(domain)
    T = _Types(16)
    qos = Qos(Policy.Reliability.Reliable(0), Policy.History.KeepAll,
              Policy.DataRepresentation(use_cdrv0_representation=True))
    readers = {f"s{i}/{t}": DataReader(p, Topic(p, f"rt/s{i}/{t}", T.WrenchStamped), qos=qos)
               for i in range(n) for t in ("wrench", "wrench_raw")}
    counts = {k: 0 for k in readers}
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        for k, r in readers.items():
            counts[k] += len(r.take(1000))
        time.sleep(0.05)
    print(json.dumps(counts), flush=True)
    del dom
    return 0


class _FoxgloveCounter:
    """A Foxglove WebSocket client in a thread: subscribes to every wrench
    channel and counts the messages."""

    def __init__(self, port: int) -> None:
        self.port = port
        self.count = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        import asyncio

        asyncio.run(self._client())

    async def _client(self) -> None:
        import asyncio

        import websockets

        for _ in range(100):  # the server starts with the bridge
            try:
                ws = await websockets.connect(
                    f"ws://127.0.0.1:{self.port}",
                    subprotocols=[websockets.Subprotocol("foxglove.sdk.v1")], max_size=None)
                break
            except OSError:
                await asyncio.sleep(0.1)
        else:
            return
        subscribed: set = set()
        async with ws:
            while not self._stop.is_set():
                try:
                    msg = await asyncio.wait_for(ws.recv(), 0.2)
                except asyncio.TimeoutError:
                    continue
                if isinstance(msg, str):
                    op = json.loads(msg)
                    if op.get("op") == "advertise":
                        subs = [{"id": c["id"], "channelId": c["id"]} for c in op["channels"]
                                if "wrench" in c["topic"] and c["id"] not in subscribed]
                        subscribed.update(s["id"] for s in subs)
                        await ws.send(json.dumps({"op": "subscribe", "subscriptions": subs}))
                elif msg[0] == 1:
                    self.count += 1

    def stop(self) -> int:
        self._stop.set()
        self._thread.join(5)
        return self.count


def run(n: int, seconds: float, zenoh_mod: Any, extra: Optional[List[str]] = None,
        latency_s: str = "0.002", all_transports: bool = False) -> Dict[str, Any]:
    """Bridge n virtual sensors for seconds, with `leptrino stream` on n
    others beside it in the same run; the figures as a dict. all_transports:
    DDS (a Cyclone DDS reader in a child process) and Foxglove (a WebSocket
    client here) beside Zenoh."""
    import leptrino

    ep = f"tcp/127.0.0.1:{_free_port()}"
    conf = zenoh_mod.Config()
    conf.insert_json5("mode", '"router"')
    conf.insert_json5("listen/endpoints", json.dumps([ep]))
    conf.insert_json5("scouting/multicast/enabled", "false")
    router = zenoh_mod.open(conf)
    sink = _Sink()
    domain = 1 + os.getpid() % 99
    sub = router.declare_subscriber(f"{domain}/**", sink)
    sims = [leptrino.Simulator() for _ in range(n)]
    ref_sims = [leptrino.Simulator() for _ in range(n)]
    child = reader = None
    refs: List[subprocess.Popen] = []
    fox: Optional[_FoxgloveCounter] = None
    try:
        args = [sys.executable, "-m", "leptrino.bridge", "--connect", ep,
                "--latency", latency_s, "--domain", str(domain)]
        if all_transports:
            fport = _free_port()
            args += ["--dds", "--dds-interface", "127.0.0.1", "--foxglove", f"127.0.0.1:{fport}"]
            reader = subprocess.Popen(
                [sys.executable, os.path.abspath(__file__), "--dds-reader",
                 f"{domain},{n},{seconds + 6}"], stdout=subprocess.PIPE, text=True)
            fox = _FoxgloveCounter(fport)
        for i, sim in enumerate(sims):
            args += ["--sensor", f"s{i}={sim.port}"]
        child = subprocess.Popen(args + (extra or []), stderr=subprocess.PIPE, text=True)
        ports = [s.port for s in ref_sims]
        for i in range(0, n, STREAM_MAX_SENSORS):  # `leptrino stream` takes up to 8 ports
            refs.append(subprocess.Popen(
                _stream_args(ports[i:i + STREAM_MAX_SENSORS], latency_s),
                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True))
        time.sleep(3.0)  # start-up, discovery, the first diagnostics
        with sink.lock:
            sink.latency_ns.clear()
        th0, t0 = _threads(child.pid), time.monotonic()
        r0 = sum(_cpu_ns(r.pid) for r in refs)
        time.sleep(seconds)
        th1, t1 = _threads(child.pid), time.monotonic()
        r1 = sum(_cpu_ns(r.pid) for r in refs)
        dead = [r.args for r in refs + [child] if r.poll() is not None]
        if dead:
            raise RuntimeError(f"ended during the measurement: {dead}")
        time.sleep(1.2)  # one more diagnostics message
        with sink.lock:
            lat = sorted(sink.latency_ns)
            seqs = {k: list(v) for k, v in sink.seqs.items()}
            diag = dict(sink.diag)
        dds_counts: Dict[str, int] = {}
        if reader is not None:
            out, _ = reader.communicate(timeout=seconds + 30)
            dds_counts = json.loads(out.strip().splitlines()[-1]) if out.strip() else {}
            reader = None
        fox_count = fox.stop() if fox is not None else 0
    finally:
        for proc in [child, reader, *refs]:
            if proc is None:
                continue
            proc.terminate()
            try:
                proc.communicate(timeout=20)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.communicate(timeout=10)
        for sim in sims + ref_sims:
            sim.stop()
        sub.undeclare()
        router.close()
    contiguous = all(v == list(range(v[0], v[0] + len(v))) for v in seqs.values())
    lost = gaps = 0
    rates: List[float] = []
    for payload in diag.values():
        kv = _diag_values(payload)
        lost += int(kv["lost"])
        gaps += int(kv["gaps"])
        rates.append(float(kv["measured_rate_hz"]))
    n_wrench = sum(1 for k in seqs if "/wrench/" in k)
    received = sum(len(v) for k, v in seqs.items() if "/wrench/" in k)
    # Loss: a message the bridge published and the subscriber did not get
    # (sequence numbers), or the bridge not keeping up (rate). Samples the
    # session reports lost between the sensor and the bridge (a busy shared
    # machine delays the virtual sensors' threads too) are reported and
    # tolerated up to 0.1 %.
    ok = (contiguous and n_wrench == n and len(rates) == n
          and all(abs(r - 1200) < 24 for r in rates) and lost <= 0.001 * max(received, 1))
    threads = _thread_delta(th0, th1, t1 - t0)
    cpu = sum(c for c, _ in threads.values())
    ref_cpu = (r1 - r0) / 1e9 / (t1 - t0)

    def pct(p: float) -> float:
        return lat[min(len(lat) - 1, int(p * len(lat)))] / 1e6 if lat else float("nan")

    return {"sensors": n, "cpu_total": cpu, "cpu_per_sensor": cpu / n,
            "threads": {k: c for k, (c, _) in threads.items() if c > 0},
            "stream_cpu_per_sensor": ref_cpu / n,
            "ratio": cpu / ref_cpu if ref_cpu > 0 else float("inf"),
            "dds_messages": sum(dds_counts.values()), "foxglove_messages": fox_count,
            "latency_p50_ms": pct(0.50), "latency_p99_ms": pct(0.99),
            "messages": sum(len(v) for v in seqs.values()), "contiguous": contiguous,
            "lost": lost, "gaps": gaps, "rates": rates, "no_loss": ok}


NOBODY = "nobody subscribed"
ONE = "one subscriber on s0/wrench"


def cost(seconds: float, rounds: int, zenoh_mod: Any,
         latency_s: str = "0.002") -> List[Dict[str, Any]]:
    """One sensor over Zenoh beside `leptrino stream` on another virtual
    sensor of the same kind, in one run: phases of `seconds` each,
    interleaved `rounds` times (nobody subscribed, one subscriber on
    NAME/wrench only, nobody, one...), so that the load of a shared machine
    drifting meanwhile falls on both kinds alike. Per phase: the CPU of
    each process and the bridge's by thread (schedstat: ns on a CPU and
    wake-ups), the messages received; with a subscriber, how long after
    its declaration its first message came."""
    import leptrino

    ep = f"tcp/127.0.0.1:{_free_port()}"
    conf = zenoh_mod.Config()
    conf.insert_json5("mode", '"router"')
    conf.insert_json5("listen/endpoints", json.dumps([ep]))
    conf.insert_json5("scouting/multicast/enabled", "false")
    router = zenoh_mod.open(conf)
    domain = 1 + os.getpid() % 99
    sim, ref_sim = leptrino.Simulator(), leptrino.Simulator()
    lock = threading.Lock()
    got = [0]
    first: List[Optional[float]] = [None]

    def on_sample(_s: Any) -> None:
        with lock:
            if first[0] is None:
                first[0] = time.monotonic()
            got[0] += 1

    out: List[Dict[str, Any]] = []
    child = ref = None
    try:
        child = subprocess.Popen(
            [sys.executable, "-m", "leptrino.bridge", "--connect", ep, "--latency", latency_s,
             "--domain", str(domain), "--sensor", f"s0={sim.port}"],
            stderr=subprocess.PIPE, text=True)
        ref = subprocess.Popen(_stream_args([ref_sim.port], latency_s),
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        time.sleep(3.0)  # start-up, the router's discovery of the bridge
        for phase in [NOBODY, ONE] * rounds:
            sub = None
            first_ms = float("nan")
            if phase == ONE:
                with lock:
                    first[0] = None
                t_decl = time.monotonic()
                sub = router.declare_subscriber(f"{domain}/s0/wrench/**", on_sample)
            time.sleep(1.0)  # a subscriber's declaration or undeclaration reaches the bridge
            if sub is not None:
                with lock:
                    if first[0] is not None:
                        first_ms = 1000.0 * (first[0] - t_decl)
            g0 = got[0]
            th0, r0, t0 = _threads(child.pid), _threads(ref.pid), time.monotonic()
            k0 = _tick_seconds(child.pid), _tick_seconds(ref.pid)
            time.sleep(seconds)
            th1, r1, t1 = _threads(child.pid), _threads(ref.pid), time.monotonic()
            k1 = _tick_seconds(child.pid), _tick_seconds(ref.pid)
            dt = t1 - t0
            threads = _thread_delta(th0, th1, dt)
            stream = _thread_delta(r0, r1, dt)
            bridge_cpu = sum(c for c, _ in threads.values())
            stream_cpu = sum(c for c, _ in stream.values())
            out.append({"phase": phase, "bridge": bridge_cpu, "stream": stream_cpu,
                        "ratio": bridge_cpu / max(stream_cpu, 1e-9),
                        "bridge_wakeups": sum(w for _, w in threads.values()),
                        "stream_wakeups": sum(w for _, w in stream.values()),
                        "messages_per_s": (got[0] - g0) / dt, "first_message_ms": first_ms,
                        "load": os.getloadavg()[0], "threads": threads,
                        "ticks": ((k1[0] - k0[0]) / dt, (k1[1] - k0[1]) / dt)})
            if sub is not None:
                sub.undeclare()
        for proc in (child, ref):
            if proc.poll() is not None:
                raise RuntimeError(f"ended during the measurement: {proc.args}")
    finally:
        for proc in (child, ref):
            if proc is not None:
                proc.terminate()
                proc.communicate(timeout=20)
        sim.stop()
        ref_sim.stop()
        router.close()
    return out


def _median(xs: List[float]) -> float:
    v = sorted(x for x in xs if not math.isnan(x))
    if not v:
        return float("nan")
    m = len(v) // 2
    return v[m] if len(v) % 2 else (v[m - 1] + v[m]) / 2


def _fmt_threads(threads: Dict[str, Tuple[float, float]]) -> str:
    return ", ".join(f"{k} {100 * c:.2f} ({w:.0f}/s)" for k, (c, w) in
                     sorted(threads.items(), key=lambda kv: -kv[1][0]) if c >= 0.00005 or w >= 1)


def print_cost(phases: List[Dict[str, Any]]) -> None:
    """Each phase, then the medians of each kind of phase."""
    for i, r in enumerate(phases, 1):
        print(f"  {i}. {r['phase']} (load {r['load']:.1f}): bridge {100 * r['bridge']:.2f} % "
              f"of a core ({r['bridge_wakeups']:.0f} wake-ups/s), `leptrino stream` "
              f"{100 * r['stream']:.2f} % ({r['stream_wakeups']:.0f}/s), ratio "
              f"{r['ratio']:.2f}, {r['messages_per_s']:.0f} messages/s received"
              + (f", first message {r['first_message_ms']:.0f} ms after the subscriber's "
                 "declaration" if r["phase"] == ONE else ""), flush=True)
        print(f"     threads (% of a core, wake-ups/s): {_fmt_threads(r['threads'])}; "
              f"in clock ticks instead: bridge {100 * r['ticks'][0]:.1f} %, stream "
              f"{100 * r['ticks'][1]:.1f} %")
    print("  medians:")
    for kind in (NOBODY, ONE):
        rs = [r for r in phases if r["phase"] == kind]
        if not rs:
            continue
        names = sorted({k for r in rs for k in r["threads"]})
        med = {k: (_median([r["threads"].get(k, (0.0, 0.0))[0] for r in rs]),
                   _median([r["threads"].get(k, (0.0, 0.0))[1] for r in rs])) for k in names}
        ratios = ", ".join(f"{r['ratio']:.2f}" for r in rs)
        print(f"  {kind} ({len(rs)} phase{'s' if len(rs) > 1 else ''}): bridge {100 * _median([r['bridge'] for r in rs]):.2f}"
              f" % of a core, `leptrino stream` {100 * _median([r['stream'] for r in rs]):.2f} %,"
              f" ratio {_median([r['ratio'] for r in rs]):.2f} (per phase {ratios})"
              + (f"; first message {_median([r['first_message_ms'] for r in rs]):.0f} ms after "
                 "the subscriber's declaration" if kind == ONE else ""))
        print(f"     threads (% of a core, wake-ups/s): {_fmt_threads(med)}", flush=True)


def main(argv: Optional[List[str]] = None) -> int:
    import zenoh

    p = argparse.ArgumentParser(prog="python bench/bridge_bench.py")
    p.add_argument("--quick", action="store_true", help="a smoke run: 1 and 2 sensors, 3 s")
    p.add_argument("--seconds", type=float, default=None,
                   help="s per run (default 10), with --cost per phase (default 20)")
    p.add_argument("--max-sensors", type=int, default=16)
    p.add_argument("--latency", default="0.002", help="the bridge's --latency")
    p.add_argument("--all", action="store_true",
                   help="also DDS (with a Cyclone DDS reader) and Foxglove (with a client)")
    p.add_argument("--cost", action="store_true",
                   help="one sensor beside `leptrino stream`: nobody subscribed and one "
                        "subscriber on NAME/wrench, interleaved --rounds times (the targets: "
                        "1.2x and 2x)")
    p.add_argument("--rounds", type=int, default=3,
                   help="with --cost: how many times each kind of phase runs (default 3)")
    p.add_argument("--dds-reader", metavar="DOMAIN,N,SECONDS", help=argparse.SUPPRESS)
    a = p.parse_args(argv)
    if a.rounds < 1 or (a.seconds is not None and a.seconds <= 0):
        p.error("--rounds and --seconds: positive numbers")
    if a.cost or a.quick:
        phase_s = 2.0 if a.quick else (a.seconds or 20.0)
        rounds = 1 if a.quick else a.rounds
        print(f"cost of one sensor over Zenoh beside `leptrino stream` ({os.cpu_count()} CPUs, "
              f"load average {os.getloadavg()[0]:.1f}, --latency {a.latency}, {rounds} x "
              f"{phase_s:g} s per kind of phase, interleaved; CPU from schedstat):", flush=True)
        print_cost(cost(phase_s, rounds, zenoh, a.latency))
        if a.cost:
            return 0
    if a.dds_reader:
        d, n_, secs_ = a.dds_reader.split(",")
        return dds_reader(int(d), int(n_), float(secs_))
    secs = 3.0 if a.quick else (a.seconds or 10.0)
    extra: List[str] = []
    print(f"leptrino-bridge figures: {os.cpu_count()} CPUs, load average "
          f"{os.getloadavg()[0]:.1f}, {secs:g} s per run, --latency {a.latency} (the bridge "
          f"and `leptrino stream`), transports: "
          f"{'Zenoh + DDS + Foxglove' if a.all else 'Zenoh'}")
    results: List[Dict[str, Any]] = []
    counts = [1, 2] if a.quick else [1, 2, 4, 6, 8, 10, 12, 14, 16]
    best = 0
    for n in counts:
        if n > a.max_sensors:
            break
        r = run(n, secs, zenoh, extra, a.latency, a.all)
        results.append(r)
        print(f"  {n:2d} sensors: CPU {100 * r['cpu_total']:5.1f} % "
              f"({100 * r['cpu_per_sensor']:4.1f} % per sensor; `leptrino stream` CSV beside it "
              f"{100 * r['stream_cpu_per_sensor']:4.1f} % per sensor, ratio "
              f"{r['ratio']:.2f}), latency p50 "
              f"{r['latency_p50_ms']:.2f} ms p99 {r['latency_p99_ms']:.2f} ms, "
              f"{r['messages']} messages, lost {r['lost']}, gaps {r['gaps']}, "
              f"contiguous {r['contiguous']}, rates {[round(x) for x in r['rates']]}, "
              f"threads (% of a core) "
              f"{', '.join(f'{k} {100 * v:.1f}' for k, v in sorted(r['threads'].items()))}"
              + (f", DDS reader {r['dds_messages']}, Foxglove client {r['foxglove_messages']}"
                 if a.all else "") +
              f" -> {'no loss' if r['no_loss'] else 'LOSS'}", flush=True)
        if not r["no_loss"]:
            break
        best = n
    print(f"largest number of sensors bridged without loss (of those tried): {best}")
    # a figure, not a test: fail only when nothing came through at all
    return 0 if results and results[0]["messages"] > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
