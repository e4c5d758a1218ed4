"""Figures of leptrino-bridge on this machine (loopback only, bounded).

    python bench/bridge_bench.py            # all figures (about 2 min)
    python bench/bridge_bench.py --quick    # a smoke run (about 20 s)

The virtual sensors run in this process (leptrino.Simulator, each on its
pty); the bridge runs as its own process (`python -m leptrino.bridge
--sensor NAME=PTY ...`) connected to a Zenoh router this process opens on
127.0.0.1, and a subscriber here receives every message. Measured:

- CPU of the bridge process per sensor (user + system time / wall time),
  and by thread: the Python threads (reading, serializing, publishing)
  against zenoh's own runtime threads (tx sends, rx receives, ...);
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
import os
import socket
import struct
import subprocess
import sys
import threading
import time
from typing import Any, Dict, List, Optional

from leptrino.bridge.rmw_zenoh import parse_attachment


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _cpu_seconds(pid: int) -> float:
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _thread_cpu(pid: int) -> Dict[str, float]:
    """CPU seconds of a process's threads by name: "python" for the
    interpreter's threads (the reading threads, the sessions' reads and the
    serialization in them), zenoh's runtime threads by their own names with
    the number dropped ("tx", "rx", "net", "acc", ...)."""
    out: Dict[str, float] = {}
    for tid in os.listdir(f"/proc/{pid}/task"):
        try:
            with open(f"/proc/{pid}/task/{tid}/stat") as f:
                text = f.read()
        except OSError:  # the thread ended meanwhile
            continue
        name = text[text.index("(") + 1:text.rindex(")")].split("-")[0]
        fields = text.rsplit(")", 1)[1].split()
        out[name] = out.get(name, 0.0) + (int(fields[11]) + int(fields[12])) / os.sysconf(
            "SC_CLK_TCK")
    return out


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
        c0, t0 = _cpu_seconds(child.pid), time.monotonic()
        th0 = _thread_cpu(child.pid)
        r0 = sum(_cpu_seconds(r.pid) for r in refs)
        time.sleep(seconds)
        c1, t1 = _cpu_seconds(child.pid), time.monotonic()
        th1 = _thread_cpu(child.pid)
        r1 = sum(_cpu_seconds(r.pid) for r in refs)
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
    cpu = (c1 - c0) / (t1 - t0)
    ref_cpu = (r1 - r0) / (t1 - t0)

    def pct(p: float) -> float:
        return lat[min(len(lat) - 1, int(p * len(lat)))] / 1e6 if lat else float("nan")

    threads = {k: (v - th0.get(k, 0.0)) / (t1 - t0) for k, v in th1.items()
               if v - th0.get(k, 0.0) > 0}
    return {"sensors": n, "cpu_total": cpu, "cpu_per_sensor": cpu / n, "threads": threads,
            "stream_cpu_per_sensor": ref_cpu / n,
            "ratio": cpu / ref_cpu if ref_cpu > 0 else float("inf"),
            "dds_messages": sum(dds_counts.values()), "foxglove_messages": fox_count,
            "latency_p50_ms": pct(0.50), "latency_p99_ms": pct(0.99),
            "messages": sum(len(v) for v in seqs.values()), "contiguous": contiguous,
            "lost": lost, "gaps": gaps, "rates": rates, "no_loss": ok}


def cost(seconds: float, zenoh_mod: Any, latency_s: str = "0.002") -> List[Dict[str, Any]]:
    """One sensor over Zenoh beside `leptrino stream` on another virtual
    sensor, in one run, in three phases of `seconds` each: nobody subscribed
    (no subscriber anywhere: the bridge publishes nothing), one subscriber on
    NAME/wrench only, nobody again. CPU of each process, the bridge's by thread."""
    import leptrino

    ep = f"tcp/127.0.0.1:{_free_port()}"
    conf = zenoh_mod.Config()
    conf.insert_json5("mode", '"router"')
    conf.insert_json5("listen/endpoints", json.dumps([ep]))
    conf.insert_json5("scouting/multicast/enabled", "false")
    router = zenoh_mod.open(conf)
    domain = 1 + os.getpid() % 99
    sim, ref_sim = leptrino.Simulator(), leptrino.Simulator()
    got = [0]
    out: List[Dict[str, Any]] = []
    child = ref = None
    try:
        child = subprocess.Popen(
            [sys.executable, "-m", "leptrino.bridge", "--connect", ep, "--latency", latency_s,
             "--domain", str(domain), "--sensor", f"s0={sim.port}"],
            stderr=subprocess.PIPE, text=True)
        ref = subprocess.Popen(_stream_args([ref_sim.port], latency_s),
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        time.sleep(3.0)
        for phase in ("nobody subscribed", "one subscriber on s0/wrench",
                      "the subscriber gone"):
            sub = None
            if phase == "the subscriber gone":
                time.sleep(1.0)  # its undeclaration reaches the bridge
            if phase == "one subscriber on s0/wrench":
                sub = router.declare_subscriber(f"{domain}/s0/wrench/**",
                                                lambda _s: got.__setitem__(0, got[0] + 1))
                time.sleep(1.0)
            g0 = got[0]
            c0, r0, t0 = _cpu_seconds(child.pid), _cpu_seconds(ref.pid), time.monotonic()
            th0 = _thread_cpu(child.pid)
            time.sleep(seconds)
            c1, r1, t1 = _cpu_seconds(child.pid), _cpu_seconds(ref.pid), time.monotonic()
            th1 = _thread_cpu(child.pid)
            dt = t1 - t0
            out.append({"phase": phase, "bridge": (c1 - c0) / dt, "stream": (r1 - r0) / dt,
                        "ratio": (c1 - c0) / max(r1 - r0, 1e-9),
                        "messages_per_s": (got[0] - g0) / dt,
                        "threads": {k: (th1.get(k, 0.0) - th0.get(k, 0.0)) / dt
                                    for k in th1}})
            if sub is not None:
                sub.undeclare()
    finally:
        for proc in (child, ref):
            if proc is not None:
                proc.terminate()
                proc.communicate(timeout=20)
        sim.stop()
        ref_sim.stop()
        router.close()
    return out


def main(argv: Optional[List[str]] = None) -> int:
    import zenoh

    p = argparse.ArgumentParser(prog="python bench/bridge_bench.py")
    p.add_argument("--quick", action="store_true", help="a smoke run: 1 and 2 sensors, 3 s")
    p.add_argument("--seconds", type=float, default=10.0)
    p.add_argument("--max-sensors", type=int, default=16)
    p.add_argument("--latency", default="0.002", help="the bridge's --latency")
    p.add_argument("--all", action="store_true",
                   help="also DDS (with a Cyclone DDS reader) and Foxglove (with a client)")
    p.add_argument("--cost", action="store_true",
                   help="one sensor: nobody subscribed, one subscriber on NAME/wrench, nobody "
                        "again, beside `leptrino stream` (the targets: 1.2x and 2x)")
    p.add_argument("--dds-reader", metavar="DOMAIN,N,SECONDS", help=argparse.SUPPRESS)
    a = p.parse_args(argv)
    if a.cost or a.quick:
        print(f"cost of one sensor over Zenoh beside `leptrino stream` (load average "
              f"{os.getloadavg()[0]:.1f}, --latency {a.latency}):")
        for r in cost(3.0 if a.quick else a.seconds, __import__("zenoh"), a.latency):
            print(f"  {r['phase']}: bridge {100 * r['bridge']:.1f} % of a core, `leptrino "
                  f"stream` {100 * r['stream']:.1f} %, ratio {r['ratio']:.2f}, "
                  f"{r['messages_per_s']:.0f} messages/s received; threads (% of a core) "
                  + ", ".join(f"{k} {100 * v:.1f}" for k, v in sorted(r["threads"].items())
                              if v >= 0.0005), flush=True)
        if a.cost:
            return 0
    if a.dds_reader:
        d, n_, secs_ = a.dds_reader.split(",")
        return dds_reader(int(d), int(n_), float(secs_))
    secs = 3.0 if a.quick else a.seconds
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
