"""A minimal scripted Leptrino sensor on a pseudo-terminal, written from the
protocol spec (frame: DLE STX, stuffed message, DLE ETX, BCC = XOR of the
message and ETX), for behaviours the virtual sensor does not offer: here, a
sensor that refuses the filter query (result 0x02), as some firmware does."""

from __future__ import annotations

import os
import select
import struct
import threading

DLE, STX, ETX = 0x10, 0x02, 0x03


def frame(message: bytes) -> bytes:
    bcc = ETX
    for b in message:
        bcc ^= b
    stuffed = message.replace(bytes([DLE]), bytes([DLE, DLE]))
    return bytes([DLE, STX]) + stuffed + bytes([DLE, ETX, bcc])


class FakeSensor:
    """Answers product info, rated values, stop and handshake samples; the
    filter query gets `filter_result` (0x02 undefined command by default)."""

    def __init__(self, filter_result: int = 0x02) -> None:
        self.filter_result = filter_result
        self.master, self.slave = os.openpty()
        self.port = os.ttyname(self.slave)
        self.commands: list[int] = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._serve, daemon=True)
        self._thread.start()

    def _answer(self, cmd: int) -> bytes:
        if cmd == 0x2A:
            data = b"PFS055YA501U6   " + b"00000042" + b"1.13"
            return bytes([4 + len(data), 0xFF, cmd, 0]) + data
        if cmd == 0x2B:
            data = struct.pack("<6f", 500, 500, 500, 10, 10, 8)
            return bytes([4 + len(data), 0xFF, cmd, 0]) + data
        if cmd == 0xB6:
            if self.filter_result != 0:
                return bytes([4, 0xFF, cmd, self.filter_result])
            return bytes([8, 0xFF, cmd, 0, 0, 0, 0, 0])
        if cmd == 0x30:
            data = struct.pack("<6hHBB", 100, -200, 300, -40, 50, -60, 0, 0, 0)
            return bytes([4 + len(data), 0xFF, cmd, 0]) + data
        if cmd == 0x33:
            return bytes([4, 0xFF, cmd, 0])
        return bytes([4, 0xFF, cmd, 0x02])

    def _serve(self) -> None:
        buf = bytearray()
        while not self._stop.is_set():
            ready, _, _ = select.select([self.master], [], [], 0.05)
            if not ready:
                continue
            try:
                buf += os.read(self.master, 4096)
            except OSError:
                continue
            while True:
                start = buf.find(bytes([DLE, STX]))
                if start < 0:
                    buf.clear()
                    break
                # The host's commands carry no 0x10 byte, so the first DLE ETX ends one.
                end = buf.find(bytes([DLE, ETX]), start + 2)
                if end < 0 or end + 3 > len(buf):
                    break
                message = bytes(buf[start + 2:end]).replace(bytes([DLE, DLE]), bytes([DLE]))
                del buf[:end + 3]
                if len(message) >= 4:
                    self.commands.append(message[2])
                    os.write(self.master, frame(self._answer(message[2])))

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=5)
        os.close(self.master)
        os.close(self.slave)
