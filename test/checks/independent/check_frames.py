#!/usr/bin/env python3
"""Check libleptrino's frames with an independent decoder.

Runs emit_frames (its path the last argument, after an emulator such as wine
when one is given), which prints one frame per line as "<name>\\t<hex>". Each
frame is decoded here by an implementation written from the protocol text alone
(stdlib only, nothing imported from the repository): DLE STX start, DLE DLE
unstuffing, DLE ETX end, BCC = XOR of the message bytes and ETX, the BCC byte
raw after DLE ETX; then the Length field and the reserved byte are checked, and
the message is compared with the one built here from the spec's tables for the
same inputs.
"""

from __future__ import annotations

import struct
import subprocess
import sys

DLE, STX, ETX = 0x10, 0x02, 0x03


class FrameError(Exception):
    pass


def decode_frame(wire: bytes) -> bytes:
    """Strictly decode exactly one frame; return the unstuffed message."""
    if len(wire) < 5 or wire[0] != DLE or wire[1] != STX:
        raise FrameError("does not start with DLE STX")
    msg = bytearray()
    i = 2
    while True:
        if i >= len(wire):
            raise FrameError("no DLE ETX")
        b = wire[i]
        if b != DLE:
            msg.append(b)
            i += 1
            continue
        if i + 1 >= len(wire):
            raise FrameError("DLE at the end")
        nxt = wire[i + 1]
        if nxt == DLE:
            msg.append(DLE)
            i += 2
        elif nxt == ETX:
            i += 2
            break
        else:
            raise FrameError(f"illegal byte {nxt:02X} after DLE at offset {i}")
    if i != len(wire) - 1:
        raise FrameError(f"{len(wire) - i} bytes after DLE ETX, expected exactly the BCC")
    check = ETX
    for b in msg:
        check ^= b
    if wire[i] != check:
        raise FrameError(f"BCC {wire[i]:02X}, computed {check:02X}")
    if not 1 <= len(msg) <= 128:
        raise FrameError(f"message of {len(msg)} bytes")
    if msg[0] != len(msg):
        raise FrameError(f"Length field {msg[0]} but {len(msg)} bytes")
    if msg[1] != 0xFF:
        raise FrameError(f"reserved byte {msg[1]:02X}, expected FF")
    return bytes(msg)


def cmd(code: int) -> bytes:
    return bytes([0x04, 0xFF, code, 0x00])


def rsp(code: int, result: int = 0, data: bytes = b"") -> bytes:
    return bytes([4 + len(data), 0xFF, code, result]) + data


def text(s: str, width: int) -> bytes:
    return s.encode("ascii").ljust(width, b" ")


def floats(values: list[float]) -> bytes:
    return struct.pack("<6f", *values)


def sample(raw: list[int], reserved: int = 0, status: int = 0) -> bytes:
    return struct.pack("<6hHBB", *raw, reserved, status, 0)


SPEC_RAW = [16, -16, 10000, -10000, 4112, 32000]


def expected() -> dict[str, bytes]:
    e: dict[str, bytes] = {
        "cmd_product_info": cmd(0x2A),
        "cmd_rated": cmd(0x2B),
        "cmd_filter_get": cmd(0xB6),
        "cmd_sample": cmd(0x30),
        "cmd_start": cmd(0x32),
        "cmd_stop": cmd(0x33),
        "rsp_info_32": rsp(0x2A, 0, text("PFS055YA501U6", 16) + text("12345678", 8)
                           + text("1.13", 4)),
        "rsp_info_38": rsp(0x2A, 0, text("PFS080YS102U6", 16) + text("00012345", 8)
                           + text("1.31", 4) + text("1200", 6)),
        "rsp_rated_pfs055": rsp(0x2B, 0, floats([500, 500, 500, 10, 10, 8])),
        "rsp_rated_cfs018": rsp(0x2B, 0, floats([100, 100, 200, 1, 1, 1])),
        "rsp_rated_fractions": rsp(0x2B, 0, floats([0.5, 2.25, 1234.5, 0.125, 3.75, 1e-3])),
        "rsp_sample_spec": rsp(0x30, 0, sample(SPEC_RAW, 0, 0x04)),
        "rsp_sample_dle": rsp(0x30, 0, sample([0x1010] * 6, 0x1010, 0x10)),
        "rsp_sample_bcc10": rsp(0x30, 0, sample([201, 1, 2, 3, 4, 5])),
        "rsp_sample_ctl": rsp(0x30, 0, sample([0x0210, 0x0310, 0x1510, 0x1010, 0, 0])),
        "rsp_stream_ext": rsp(0x32, 0, sample([32000, -32000, -1, 1, 15000, -15000], 0xBEEF, 7)),
        "rsp_start_ack": rsp(0x32),
        "rsp_stop_ack": rsp(0x33),
        "rsp_filter_set_ack": rsp(0xA6),
        "rsp_result_1": rsp(0x2A, 1),
        "rsp_result_2": rsp(0x2B, 2),
        "rsp_result_3": rsp(0xA6, 3),
        "rsp_result_4": rsp(0x32, 4),
        "dev_stream_spec": rsp(0x32, 0, sample(SPEC_RAW, 7, 0)),
    }
    for f in range(4):
        e[f"cmd_filter_set_{f}"] = bytes([0x08, 0xFF, 0xA6, 0x00, f, 0, 0, 0])
        e[f"rsp_filter_{f}"] = rsp(0xB6, 0, bytes([f, 0, 0, 0]))
    return e


# Spec worked frames, to hold this decoder itself to the spec's bytes.
SPEC_WORKED = {
    "cmd_product_info": "10 02 04 FF 2A 00 10 03 D2",
    "cmd_rated": "10 02 04 FF 2B 00 10 03 D3",
    "cmd_filter_get": "10 02 04 FF B6 00 10 03 4E",
    "cmd_sample": "10 02 04 FF 30 00 10 03 C8",
    "cmd_start": "10 02 04 FF 32 00 10 03 CA",
    "cmd_stop": "10 02 04 FF 33 00 10 03 CB",
    "cmd_filter_set_1": "10 02 08 FF A6 00 01 00 00 00 10 03 53",
    "rsp_sample_spec": "10 02 14 FF 30 00 10 10 00 F0 FF 10 10 27 F0 D8 10 10 10 10 00 7D 00 00"
                       " 04 00 10 03 A1",
}


def main() -> int:
    if len(sys.argv) < 2:
        print("usage: check_frames.py [EMULATOR...] <emit_frames executable>", file=sys.stderr)
        return 2
    run = subprocess.run(sys.argv[1:], capture_output=True, text=True, check=False)
    if run.returncode != 0:
        print(f"emit_frames failed ({run.returncode}): {run.stderr}", file=sys.stderr)
        return 1
    want = expected()
    seen: set[str] = set()
    errors: list[str] = []
    for line in run.stdout.splitlines():
        if not line.strip():
            continue
        name, _, hexpart = line.partition("\t")
        try:
            wire = bytes.fromhex(hexpart)
        except ValueError:
            errors.append(f"{name}: not hex: {hexpart!r}")
            continue
        if name in seen:
            errors.append(f"{name}: emitted twice")
        seen.add(name)
        try:
            msg = decode_frame(wire)
        except FrameError as exc:
            errors.append(f"{name}: rejected: {exc}: {hexpart}")
            continue
        if name not in want:
            errors.append(f"{name}: no expected message for this name")
        elif msg != want[name]:
            errors.append(f"{name}: message {msg.hex(' ').upper()}, expected "
                          f"{want[name].hex(' ').upper()}")
        if name in SPEC_WORKED and wire != bytes.fromhex(SPEC_WORKED[name]):
            errors.append(f"{name}: wire differs from the spec's worked frame")
        if name == "rsp_sample_bcc10" and wire[-1] != DLE:
            errors.append(f"{name}: BCC is {wire[-1]:02X}; this case needs 0x10")
    for name in sorted(set(want) - seen):
        errors.append(f"{name}: not emitted")
    for err in errors:
        print("FAIL " + err)
    print(f"{len(seen)} frames decoded independently, {len(errors)} problems")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
