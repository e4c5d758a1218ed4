#!/usr/bin/env python3
"""An independent host for leptrino-sim, written from the protocol spec only.

Uses nothing of libleptrino: its own framing, BCC, stuffing and decoding,
its own terminal setup (termios), its own I/O (select). Starts the
leptrino-sim executable, takes the first line of its stdout as the port,
and questions the virtual sensor:

  python3 independent_host.py path/to/leptrino-sim

Exit status 0 when every check passes.
"""
from __future__ import annotations

import os
import select
import signal
import struct
import subprocess
import sys
import termios
import time
from typing import List, Optional, Tuple

DLE, STX, ETX, NAK = 0x10, 0x02, 0x03, 0x15

# Spec 5.2: published rated values (N, N, N, N m, N m, N m).
RATED = {
    "CFS018CA201U": (100, 100, 200, 1, 1, 1),
    "CFS034CA301U": (150, 150, 300, 4, 4, 4),
    "PFS055YA501U6": (500, 500, 500, 10, 10, 8),
    "PFS080YS102U6": (500, 500, 1000, 40, 40, 30),
}

failures: List[str] = []


def check(cond: bool, what: str) -> None:
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def bcc(msg: bytes) -> int:
    """Spec 2.3: XOR of the unstuffed message bytes and ETX."""
    x = ETX
    for b in msg:
        x ^= b
    return x


def frame(msg: bytes, corrupt_bcc: bool = False) -> bytes:
    """DLE STX, message with every DLE doubled, DLE ETX, BCC (never stuffed)."""
    body = msg.replace(bytes([DLE]), bytes([DLE, DLE]))
    check_byte = bcc(msg) ^ (0xFF if corrupt_bcc else 0)
    return bytes([DLE, STX]) + body + bytes([DLE, ETX, check_byte])


def command(code: int, data: bytes = b"") -> bytes:
    """Spec 3.1: Length, 0xFF, command, 0x00, data."""
    return bytes([4 + len(data), 0xFF, code, 0x00]) + data


class Decoder:
    """Turns received bytes into ('msg', bytes), ('nak', b'') or ('bad', reason)."""

    def __init__(self) -> None:
        self.state = "hunt"
        self.buf = bytearray()

    def feed(self, data: bytes) -> List[Tuple[str, bytes]]:
        out: List[Tuple[str, bytes]] = []
        for b in data:
            if self.state == "hunt":
                if b == DLE:
                    self.state = "hunt_dle"
            elif self.state == "hunt_dle":
                if b == STX:
                    self.state, self.buf = "body", bytearray()
                elif b == NAK:
                    out.append(("nak", b""))
                    self.state = "hunt"
                elif b != DLE:
                    self.state = "hunt"
            elif self.state == "body":
                if b == DLE:
                    self.state = "body_dle"
                else:
                    self.buf.append(b)
            elif self.state == "body_dle":
                if b == DLE:
                    self.buf.append(DLE)
                    self.state = "body"
                elif b == ETX:
                    self.state = "bcc"
                elif b == STX:
                    self.buf = bytearray()
                    self.state = "body"
                else:
                    out.append(("bad", b"escape"))
                    self.state = "hunt"
            elif self.state == "bcc":
                msg = bytes(self.buf)
                out.append(("msg", msg) if b == bcc(msg) else ("bad", b"bcc"))
                self.state = "hunt"
        return out


class Port:
    def __init__(self, path: str) -> None:
        self.fd = os.open(path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        attrs = termios.tcgetattr(self.fd)
        iflag, oflag, cflag, lflag, _, _, cc = attrs
        iflag = 0
        oflag = 0
        lflag = 0
        cflag = termios.CS8 | termios.CREAD | termios.CLOCAL
        speed = getattr(termios, "B460800", termios.B38400)
        cc[termios.VMIN] = 1
        cc[termios.VTIME] = 0
        termios.tcsetattr(self.fd, termios.TCSANOW, [iflag, oflag, cflag, lflag, speed, speed, cc])
        termios.tcflush(self.fd, termios.TCIOFLUSH)
        self.dec = Decoder()
        self.events: List[Tuple[str, bytes, float]] = []

    def close(self) -> None:
        os.close(self.fd)

    def send(self, data: bytes) -> None:
        view = memoryview(data)
        while view:
            select.select([], [self.fd], [], 1.0)
            n = os.write(self.fd, view)
            view = view[n:]

    def pump(self, timeout: float) -> None:
        r, _, _ = select.select([self.fd], [], [], timeout)
        if r:
            data = os.read(self.fd, 4096)
            now = time.monotonic()
            for kind, payload in self.dec.feed(data):
                self.events.append((kind, payload, now))

    def next_event(self, timeout: float = 1.0, skip_stream: bool = True) -> Optional[Tuple[str, bytes]]:
        end = time.monotonic() + timeout
        while True:
            while self.events:
                kind, payload, _ = self.events.pop(0)
                if skip_stream and kind == "msg" and len(payload) == 20 and payload[2] == 0x32:
                    continue
                return kind, payload
            left = end - time.monotonic()
            if left <= 0:
                return None
            self.pump(left)

    def ask(self, msg: bytes) -> Optional[bytes]:
        self.send(frame(msg))
        ev = self.next_event(5.0)
        return ev[1] if ev and ev[0] == "msg" else None


def start_sim(exe: str, args: List[str]) -> Tuple[subprocess.Popen, str]:
    proc = subprocess.Popen([exe] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert proc.stdout is not None
    line = proc.stdout.readline().decode().strip()
    return proc, line


def stop_sim(proc: subprocess.Popen) -> int:
    proc.send_signal(signal.SIGTERM)
    try:
        return proc.wait(timeout=5)
    except subprocess.TimeoutExpired:
        proc.kill()
        return -1


def session(exe: str, model: str, rate_field: bool) -> None:
    args = ["--model", model, "--serial", "31415926", "--firmware", "1.13"]
    if rate_field:
        args.append("--output-rate-field")
    proc, path = start_sim(exe, args)
    print(f"# leptrino-sim {' '.join(args)} -> {path}")
    check(path.startswith("/"), "first line of stdout is the port path")
    port = Port(path)
    try:
        # worked frames of the spec, from our own encoder
        check(frame(command(0x32)).hex() == "100204ff320010 03ca".replace(" ", ""),
              "own encoder reproduces the spec's start frame")
        check(frame(bytes.fromhex("08ffa60001000000")).hex() == "100208ffa6000100000010 0353".replace(" ", ""),
              "own encoder reproduces the spec's set-filter frame")

        r = port.ask(command(0x2A))
        want_len = 38 if rate_field else 32
        check(r is not None and len(r) == want_len and r[0] == want_len and r[1] == 0xFF
              and r[2] == 0x2A and r[3] == 0, f"product info: {want_len}-byte answer")
        if r:
            check(r[4:20].decode("ascii") == model.ljust(16), "product info: model, space padded")
            check(r[20:28] == b"31415926", "product info: serial")
            check(r[28:32] == b"1.13", "product info: firmware")
            if rate_field:
                check(r[32:38].decode("ascii").strip(" \0") == "1200", "product info: output rate 1200")

        r = port.ask(command(0x2B))
        check(r is not None and len(r) == 28 and r[:4] == bytes([0x1C, 0xFF, 0x2B, 0]), "rated: 28-byte answer")
        if r:
            vals = struct.unpack("<6f", r[4:28])
            check(vals == tuple(float(v) for v in RATED[model]), f"rated values of {model}: {vals}")

        r = port.ask(command(0xB6))
        check(r == bytes([0x08, 0xFF, 0xB6, 0, 0, 0, 0, 0]), "filter query: code 0, reserved zero")

        r = port.ask(command(0x30))
        check(r is not None and len(r) == 20 and r[:4] == bytes([0x14, 0xFF, 0x30, 0]), "handshake sample: 20 bytes")
        if r:
            raw = struct.unpack("<6h", r[4:16])
            check(all(abs(v) < 3000 for v in raw), f"handshake sample near the default 0.2 x rated: {raw}")
            check(r[19] == 0, "handshake sample: last reserved byte 0")

        # a bad BCC gets DLE NAK, and nothing else
        port.send(frame(command(0x2A), corrupt_bcc=True))
        ev = port.next_event(0.5)
        check(ev == ("nak", b""), "bad BCC answered by DLE NAK")
        check(port.next_event(0.2) is None, "nothing else after the NAK")

        r = port.ask(bytes([0x05, 0xFF, 0x2A, 0x00, 0x00]))
        check(r == bytes([0x04, 0xFF, 0x2A, 0x01]), "wrong length: result 0x01, no data")
        r = port.ask(command(0x55))
        check(r == bytes([0x04, 0xFF, 0x55, 0x02]), "unknown command: result 0x02")
        r = port.ask(command(0xA6, bytes([7, 0, 0, 0])))
        check(r == bytes([0x04, 0xFF, 0xA6, 0x03]), "filter code 7: result 0x03")
        r = port.ask(command(0xA6, bytes([1, 0, 0, 0])))
        check(r == bytes([0x04, 0xFF, 0xA6, 0x00]), "set filter 1: accepted")
        r = port.ask(command(0xB6))
        check(r is not None and r[4] == 0, "filter still 0 before a power cycle")
        # the power cycle takes effect when the sim's thread gets to it: ask
        # until it has (a loaded machine may take a while), at most 10 s
        proc.send_signal(signal.SIGUSR1)
        end = time.monotonic() + 10.0
        r = port.ask(command(0xB6))
        while (r is None or r[4] != 1) and time.monotonic() < end:
            time.sleep(0.05)
            r = port.ask(command(0xB6))
        check(r is not None and r[4] == 1, "filter 1 after SIGUSR1 (power cycle)")

        # continuous output
        port.events.clear()
        port.send(frame(command(0x32)))
        ev = port.next_event(5.0)
        check(ev == ("msg", bytes([0x04, 0xFF, 0x32, 0x00])), "start: answered 04 FF 32 00")
        data: List[Tuple[bytes, float]] = []
        bad = 0
        end = time.monotonic() + 3.0
        while time.monotonic() < end:
            port.pump(0.1)
            for kind, payload, t in port.events:
                if kind == "msg" and len(payload) == 20 and payload[:4] == bytes([0x14, 0xFF, 0x32, 0]):
                    data.append((payload, t))
                else:
                    bad += 1
            port.events.clear()
        check(bad == 0, "only well-formed data messages while streaming")
        seqs = [struct.unpack("<H", p[16:18])[0] for p, _ in data]
        gaps = sum(((b - a - 1) & 0xFFFF) for a, b in zip(seqs, seqs[1:]))
        check(seqs[:1] == [0] and gaps == 0, f"{len(seqs)} samples, sequence from 0 without gaps")
        if len(data) > 1:
            rate = (len(data) - 1) / (data[-1][1] - data[0][1])
            check(abs(rate - 1200) / 1200 < 0.03, f"stream rate {rate:.1f} Hz (1200 expected)")
        port.send(frame(command(0x33)))
        ev = port.next_event(5.0)
        check(ev == ("msg", bytes([0x04, 0xFF, 0x33, 0x00])), "stop: answered 04 FF 33 00 (data before it skipped)")
        check(port.next_event(0.1, skip_stream=False) is None, "silence after the stop")
    finally:
        port.close()
    rc = stop_sim(proc)
    check(rc == 0, "leptrino-sim exits 0 on SIGTERM")


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: independent_host.py path/to/leptrino-sim", file=sys.stderr)
        return 2
    exe = sys.argv[1]
    session(exe, "PFS055YA501U6", rate_field=False)
    session(exe, "CFS018CA201U", rate_field=True)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
