#!/usr/bin/env python3
"""Generate test/vectors/frames.json and messages.json.

Written from the protocol text (spec/leptrino-protocol.md) alone: it imports
nothing from leptrino. Every BCC, stuffed frame and float byte pattern in the
vector files is computed here, and the spec's worked frames are checked
against the literal bytes printed in the spec.

    python3 test/vectors/gen_vectors.py          # rewrite the JSON files
    python3 test/vectors/gen_vectors.py --check  # fail if they are stale
"""

from __future__ import annotations

import argparse
import json
import math
import struct
import sys
from pathlib import Path
from typing import Any

DLE, STX, ETX, NAK = 0x10, 0x02, 0x03, 0x15
MAX_MESSAGE = 128
HERE = Path(__file__).resolve().parent


def hx(data: bytes) -> str:
    return " ".join(f"{b:02X}" for b in data)


def unhex(text: str) -> bytes:
    return bytes.fromhex(text)


# ---- frame codec (spec 2.3) -------------------------------------------------


def bcc(msg: bytes) -> int:
    """XOR of the unstuffed message bytes and ETX."""
    value = ETX
    for b in msg:
        value ^= b
    return value


def frame(msg: bytes, *, bad_bcc: bool = False) -> bytes:
    """DLE STX, message with every DLE doubled, DLE ETX, BCC (never stuffed)."""
    out = bytearray([DLE, STX])
    for b in msg:
        out.append(b)
        if b == DLE:
            out.append(DLE)
    out += bytes([DLE, ETX, bcc(msg) ^ (0x5A if bad_bcc else 0)])
    return bytes(out)


class RefDecoder:
    """Reference push decoder implementing the rules documented in README.md."""

    def __init__(self) -> None:
        self.events: list[dict[str, Any]] = []
        self.stats = dict(messages=0, naks=0, bcc_errors=0, escape_errors=0, overruns=0,
                          restarts=0, bytes_discarded=0)
        self.state = "idle"
        self.buf = bytearray()
        self.raw = 0
        self.shared = 0  # 0x10 BCC bytes that also served as the DLE of a DLE STX/NAK

    def _reject(self, error: str, counter: str, next_state: str) -> None:
        self.events.append({"type": "error", "error": error})
        self.stats[counter] += 1
        self.stats["bytes_discarded"] += self.raw
        self.raw = 0
        self.state = next_state

    def _begin(self) -> None:
        self.state = "msg"
        self.buf = bytearray()
        self.raw = 2

    def _nak(self) -> None:
        self.events.append({"type": "nak"})
        self.stats["naks"] += 1
        self.raw = 0
        self.state = "idle"

    def _append(self, b: int) -> None:
        if len(self.buf) >= MAX_MESSAGE:
            self._reject("too_long", "overruns", "skip")
        else:
            self.buf.append(b)

    def feed(self, data: bytes) -> None:
        for b in data:
            self._step(b)

    def _step(self, b: int) -> None:
        s = self.state
        st = self.stats
        if s == "idle":
            if b == DLE:
                self.state = "idle_dle"
            else:
                st["bytes_discarded"] += 1
        elif s == "idle_dle":
            if b == STX:
                self._begin()
            elif b == NAK:
                self._nak()
            elif b == DLE:
                st["bytes_discarded"] += 1  # the first DLE; this one may start a frame
            else:
                st["bytes_discarded"] += 2
                self.state = "idle"
        elif s == "msg":
            self.raw += 1
            if b == DLE:
                self.state = "msg_dle"
            else:
                self._append(b)
        elif s == "msg_dle":
            self.raw += 1
            if b == DLE:
                self.state = "msg"
                self._append(b)
            elif b == ETX:
                self.state = "bcc"
            elif b == STX:
                st["bytes_discarded"] += self.raw - 2
                st["restarts"] += 1
                self._begin()
            elif b == NAK:  # the partial frame is dropped, the NAK is kept
                st["bytes_discarded"] += self.raw - 2
                st["escape_errors"] += 1
                self._nak()
            else:
                self._reject("escape", "escape_errors", "idle")
        elif s == "bcc":
            want = bcc(bytes(self.buf))
            if b == DLE and want != DLE:
                # The BCC byte was lost (or hit): this DLE may open the next frame.
                self._reject("bcc", "bcc_errors", "idle_dle")
                return
            self.raw += 1
            if b != want:
                self._reject("bcc", "bcc_errors", "idle")
            else:
                self.events.append({"type": "message", "message": hx(bytes(self.buf))})
                st["messages"] += 1
                self.raw = 0
                # A BCC of 0x10 may also be the DLE of a following STX or NAK
                # (the real BCC was lost and happened to be 0x10, or the next DLE was lost).
                self.state = "bcc_dle" if b == DLE else "idle"
        elif s == "bcc_dle":
            if b == DLE:
                self.state = "idle_dle"
            elif b == STX:
                self.shared += 1
                self._begin()
                self.raw = 1  # the DLE belongs to the frame delivered before
            elif b == NAK:
                self.shared += 1
                self._nak()
            else:
                st["bytes_discarded"] += 1
                self.state = "idle"
        elif s == "skip":
            if b == DLE:
                self.state = "skip_dle"
            else:
                st["bytes_discarded"] += 1
        elif s == "skip_dle":
            if b == STX:
                self._begin()
            elif b == NAK:
                self._nak()
            else:
                st["bytes_discarded"] += 2
                self.state = {ETX: "skip_bcc", DLE: "skip"}.get(b, "idle")
        elif b == DLE:  # skip_bcc: a DLE may be the BCC or the next frame's DLE (BCC lost)
            self.state = "idle_dle"
        else:  # skip_bcc
            st["bytes_discarded"] += 1
            self.state = "idle"


# ---- message helpers (spec 3-7) --------------------------------------------

CMD = {
    "product_info": 0x2A,
    "rated": 0x2B,
    "filter_get": 0xB6,
    "sample": 0x30,
    "start": 0x32,
    "stop": 0x33,
    "filter_set": 0xA6,
}


def command(code: int, filter_code: int | None = None) -> bytes:
    if code == CMD["filter_set"]:
        assert filter_code is not None
        return bytes([0x08, 0xFF, code, 0x00, filter_code, 0, 0, 0])
    return bytes([0x04, 0xFF, code, 0x00])


def response(code: int, result: int, data: bytes = b"") -> bytes:
    length = 4 + len(data)
    assert length <= MAX_MESSAGE
    return bytes([length, 0xFF, code, result]) + data


def text_field(text: str, width: int, pad: bytes = b" ") -> bytes:
    raw = text.encode("ascii")
    assert len(raw) <= width
    return raw + pad * (width - len(raw))


def raw_info(model: bytes, serial: bytes, firmware: bytes, rate: bytes | None = None) -> bytes:
    """Product-info data from exact field bytes (for padding variants and defects)."""
    assert (len(model), len(serial), len(firmware)) == (16, 8, 4)
    data = model + serial + firmware
    if rate is not None:
        assert len(rate) == 6
        data += rate
    return data


def info_data(model: str, serial: str, firmware: str, rate: str | None) -> bytes:
    data = text_field(model, 16) + text_field(serial, 8) + text_field(firmware, 4)
    if rate is not None:
        data += text_field(rate, 6)
    return data


def f32(value: float) -> bytes:
    packed = struct.pack("<f", value)
    assert struct.unpack("<f", packed)[0] == value or math.isnan(value), value
    return packed


def sample_data(raw: list[int], status: int = 0, reserved: int = 0, last: int = 0) -> bytes:
    assert len(raw) == 6
    return struct.pack("<6hHBB", *raw, reserved, status, last)


# ---- frames.json --------------------------------------------------------------

SPEC_WORKED = [
    ("product info command", "10 02 04 FF 2A 00 10 03 D2"),
    ("rated values command", "10 02 04 FF 2B 00 10 03 D3"),
    ("filter query command", "10 02 04 FF B6 00 10 03 4E"),
    ("handshake data command", "10 02 04 FF 30 00 10 03 C8"),
    ("start continuous command", "10 02 04 FF 32 00 10 03 CA"),
    ("stop continuous command", "10 02 04 FF 33 00 10 03 CB"),
    ("set filter 0x01 command", "10 02 08 FF A6 00 01 00 00 00 10 03 53"),
    ("data response (16, -16, 10000, -10000, 4112, 32000), status 0x04",
     "10 02 14 FF 30 00 10 10 00 F0 FF 10 10 27 F0 D8 10 10 10 10 00 7D 00 00 04 00 10 03 A1"),
]

SPEC_DATA_RAW = [16, -16, 10000, -10000, 4112, 32000]


def sample_with_bcc_0x10() -> bytes:
    """A handshake answer whose BCC byte is 0x10 (found by search, not by hand)."""
    for fx in range(0, 2000):
        msg = response(0x30, 0, sample_data([fx, 1, 2, 3, 4, 5]))
        if bcc(msg) == DLE:
            return msg
    raise AssertionError("no sample with BCC 0x10")


def frames_vectors() -> dict[str, Any]:
    spec_msgs = [command(CMD[k]) for k in
                 ("product_info", "rated", "filter_get", "sample", "start", "stop")]
    spec_msgs.append(command(CMD["filter_set"], 0x01))
    spec_msgs.append(response(0x30, 0, sample_data(SPEC_DATA_RAW, status=0x04)))
    encode: list[dict[str, Any]] = []
    for (name, wire_text), msg in zip(SPEC_WORKED, spec_msgs):
        wire = frame(msg)
        if hx(wire) != wire_text:
            raise AssertionError(f"spec worked frame mismatch: {name}: {hx(wire)} != {wire_text}")
        encode.append({"name": "spec: " + name, "message": hx(msg), "wire": wire_text})

    bcc10 = sample_with_bcc_0x10()
    assert frame(bcc10)[-1] == DLE and frame(bcc10)[-2:-1] == bytes([ETX])
    all10_sample = response(0x30, 0, sample_data([0x1010] * 6, status=0x10, reserved=0x1010))
    max_pattern = bytes([0x80, 0xFF, 0x30, 0x00]) + bytes((i * 7) & 0xFF for i in range(124))
    max_all10 = bytes([DLE] * MAX_MESSAGE)
    info38 = response(0x2A, 0, info_data("PFS080YS102U6", "00012345", "1.31", "1200"))
    info32 = response(0x2A, 0, info_data("PFS055YA501U6", "12345678", "1.13", None))
    extra = [
        ("BCC equal to 0x10 (the BCC byte is not stuffed)", bcc10),
        ("handshake answer full of 0x10", all10_sample),
        ("single byte 0x10", bytes([DLE])),
        ("data bytes 10 02, 10 03, 10 15 are stuffed, not control codes",
         response(0x30, 0, sample_data([0x0210, 0x0310, 0x1510, 0x1010, 0, 0]))),
        ("128-byte message (the maximum)", max_pattern),
        ("128 bytes of 0x10 (the longest frame: 261 bytes)", max_all10),
        ("38-byte product info (v1.31 form with output rate)", info38),
        ("32-byte product info (v1.13)", info32),
        ("result 0x04 state error", response(0x32, 0x04)),
        ("filter query answer, code 3", response(0xB6, 0, bytes([3, 0, 0, 0]))),
    ]
    for name, msg in extra:
        encode.append({"name": name, "message": hx(msg), "wire": hx(frame(msg))})
    assert len(frame(max_all10)) == 2 * MAX_MESSAGE + 5

    encode_errors = [
        {"name": "129-byte message", "message": hx(bytes([0x81, 0xFF, 0x30, 0x00]) + bytes(125)),
         "error": "too_long"},
        {"name": "empty message", "message": "", "error": "arg"},
    ]

    # Decoder streams: (name, input bytes, expected events written by hand).
    pi = command(0x2A)
    rated = command(0x2B)
    stop_ack = response(0x33, 0)
    sample = response(0x30, 0, sample_data(SPEC_DATA_RAW, status=0x04))
    stream_a = response(0x32, 0, sample_data([1, 2, 3, 4, 5, 6], reserved=1))
    stream_b = response(0x32, 0, sample_data([-1, -2, -3, -4, -5, -6], reserved=2))
    over129 = bytes([0x81, 0xFF, 0x30, 0x00]) + bytes(range(1, 125)) + b"\x7E"
    fake_inside = unhex("10 02 04 FF 2A 00 10 03 D2")  # a whole frame as message bytes
    # The 129th byte is 0x55; the rest holds a whole frame as data (stuffed on the wire).
    over_fake = bytes([0x00, 0xFF, 0x30, 0x00]) + bytes(124) + b"\x55" + fake_inside + b"\x01"
    over_fake = bytes([len(over_fake)]) + over_fake[1:]
    over_dle129 = bytes([0x81, 0xFF, 0x30, 0x00]) + bytes(124) + bytes([DLE])
    over_bcc10 = None
    for extra_byte in range(256):
        cand = bytes([0x81, 0xFF, 0x30, 0x00]) + bytes(124) + bytes([extra_byte])
        if bcc(cand) == DLE:
            over_bcc10 = cand
            break
    assert over_bcc10 is not None

    def msg_ev(m: bytes) -> dict[str, Any]:
        return {"type": "message", "message": hx(m)}

    nak_ev = {"type": "nak"}

    def err_ev(e: str) -> dict[str, Any]:
        return {"type": "error", "error": e}

    partial = frame(rated)[:5]  # 10 02 04 FF 2B
    streams: list[tuple[str, bytes, list[dict[str, Any]]]] = [
        ("one frame", frame(pi), [msg_ev(pi)]),
        ("garbage before a frame", unhex("00 FF 41 03 02 15") + frame(pi), [msg_ev(pi)]),
        ("stray DLE pairs before a frame",
         unhex("10 41 10 03 10 FF") + frame(pi), [msg_ev(pi)]),
        ("DLE DLE STX between frames starts a frame", unhex("10") + frame(pi), [msg_ev(pi)]),
        ("garbage after a frame", frame(pi) + unhex("55 AA 03"), [msg_ev(pi)]),
        ("DLE STX restart inside a frame", partial + frame(pi), [msg_ev(pi)]),
        ("restart right after DLE STX", unhex("10 02") + frame(pi), [msg_ev(pi)]),
        ("restart inside a frame after a stuffed DLE",
         unhex("10 02 14 FF 30 00 10 10") + frame(sample), [msg_ev(sample)]),
        ("bad BCC", frame(pi, bad_bcc=True), [err_ev("bcc")]),
        ("bad BCC then a good frame", frame(sample, bad_bcc=True) + frame(pi),
         [err_ev("bcc"), msg_ev(pi)]),
        ("illegal byte after DLE, then resync on the next frame",
         unhex("10 02 04 FF 10 41 2A 00 10 03 D2") + frame(rated),
         [err_ev("escape"), msg_ev(rated)]),
        ("DLE NAK inside a frame drops the partial frame and is delivered",
         unhex("10 02 04 FF 10 15") + frame(pi), [nak_ev, msg_ev(pi)]),
        ("DLE NAK inside an over-long frame is delivered",
         frame(over129)[:-3] + unhex("10 15") + frame(pi),
         [err_ev("too_long"), nak_ev, msg_ev(pi)]),
        ("over-long frame (129 bytes) then a good frame", frame(over129) + frame(pi),
         [err_ev("too_long"), msg_ev(pi)]),
        ("over-long frame whose stuffed 10 10 02 must not resync",
         frame(over_fake) + frame(rated), [err_ev("too_long"), msg_ev(rated)]),
        ("over-long frame whose 129th byte is a stuffed DLE", frame(over_dle129) + frame(pi),
         [err_ev("too_long"), msg_ev(pi)]),
        ("over-long frame with BCC 0x10 then a frame", frame(over_bcc10) + frame(pi),
         [err_ev("too_long"), msg_ev(pi)]),
        ("DLE STX inside an over-long frame starts a new frame",
         frame(over129)[:-3] + frame(pi), [err_ev("too_long"), msg_ev(pi)]),
        ("NAK alone", unhex("10 15"), [nak_ev]),
        ("NAK between messages", frame(stop_ack) + unhex("10 15") + frame(sample),
         [msg_ev(stop_ack), nak_ev, msg_ev(sample)]),
        ("NAK after garbage and a stray DLE", unhex("33 10 10 15"), [nak_ev]),
        ("back-to-back frames", frame(stream_a) + frame(stream_b) + frame(stream_a),
         [msg_ev(stream_a), msg_ev(stream_b), msg_ev(stream_a)]),
        ("frame whose BCC is 0x10 followed by a frame", frame(bcc10) + frame(pi),
         [msg_ev(bcc10), msg_ev(pi)]),
        ("two frames whose BCC is 0x10", frame(bcc10) + frame(bcc10),
         [msg_ev(bcc10), msg_ev(bcc10)]),
        ("longest frame (128 x 0x10) then NAK", frame(max_all10) + unhex("10 15"),
         [msg_ev(max_all10), nak_ev]),
        # Resync after a lost BCC byte (issue 8): the following frame is never lost.
        ("lost BCC: the next frame's DLE STX still starts it",
         frame(sample)[:-1] + frame(pi), [err_ev("bcc"), msg_ev(pi)]),
        ("lost BCC that would have been 0x10: both frames delivered",
         frame(bcc10)[:-1] + frame(pi), [msg_ev(bcc10), msg_ev(pi)]),
        ("lost BCC before a NAK", frame(sample)[:-1] + unhex("10 15") + frame(pi),
         [err_ev("bcc"), nak_ev, msg_ev(pi)]),
        ("lost BCC that would have been 0x10 before a NAK", frame(bcc10)[:-1] + unhex("10 15"),
         [msg_ev(bcc10), nak_ev]),
        ("BCC 0x10 then the next frame's DLE lost", frame(bcc10) + frame(pi)[1:],
         [msg_ev(bcc10), msg_ev(pi)]),
        ("BCC 0x10 then a stray byte", frame(bcc10) + unhex("41") + frame(pi),
         [msg_ev(bcc10), msg_ev(pi)]),
        ("BCC 0x10 then a stray DLE pair", frame(bcc10) + unhex("10 41") + frame(pi),
         [msg_ev(bcc10), msg_ev(pi)]),
        ("two lost BCCs in a row", frame(stream_a)[:-1] + frame(stream_b)[:-1] + frame(stream_a),
         [err_ev("bcc"), err_ev("bcc"), msg_ev(stream_a)]),
        ("lost BCC between frames whose BCC is 0x10",
         frame(bcc10) + frame(bcc10)[:-1] + frame(bcc10),
         [msg_ev(bcc10), msg_ev(bcc10), msg_ev(bcc10)]),
        ("lost BCC of an over-long frame", frame(over129)[:-1] + frame(pi),
         [err_ev("too_long"), msg_ev(pi)]),
        ("illegal byte after DLE inside an over-long frame", frame(over129)[:-3] + unhex("10 41")
         + frame(pi), [err_ev("too_long"), msg_ev(pi)]),
        ("every kind of event in one stream",
         unhex("FF") + frame(pi) + unhex("10 15") + partial + frame(rated, bad_bcc=True)
         + unhex("10 02 33 10 07") + frame(over129) + frame(bcc10) + frame(sample),
         [msg_ev(pi), nak_ev, err_ev("bcc"), err_ev("escape"), err_ev("too_long"),
          msg_ev(bcc10), msg_ev(sample)]),
    ]
    decode: list[dict[str, Any]] = []
    for name, data, events in streams:
        ref = RefDecoder()
        ref.feed(data)
        if ref.events != events:
            raise AssertionError(f"{name}: reference decoder gave {ref.events}, expected {events}")
        if ref.state not in ("idle", "bcc_dle"):
            raise AssertionError(f"{name}: stream must end between frames")
        accounted = ref.stats["bytes_discarded"] + 2 * ref.stats["naks"] - ref.shared + sum(
            len(frame(unhex(e["message"]))) for e in events if e["type"] == "message")
        if accounted != len(data):
            raise AssertionError(f"{name}: {accounted} bytes accounted of {len(data)}")
        decode.append({"name": name, "input": hx(data), "events": events, "stats": ref.stats})
    # The C tests feed all streams in a row to one decoder: that must give the
    # concatenated events and the summed counters.
    ref = RefDecoder()
    ref.feed(b"".join(data for _, data, _ in streams))
    if ref.events != [e for _, _, events in streams for e in events]:
        raise AssertionError("the streams in a row give other events than one by one")
    if ref.stats != {k: sum(v["stats"][k] for v in decode) for k in ref.stats}:
        raise AssertionError("the streams in a row give other counters than one by one")
    # Each encode vector is also a one-frame stream.
    return {
        "description": "Frame codec vectors (spec 2.3); schema in README.md",
        "encode": encode,
        "encode_errors": encode_errors,
        "decode": decode,
    }


# ---- messages.json ----------------------------------------------------------

PRESETS = [
    ("CFS018CA201U", [100.0, 100.0, 200.0, 1.0, 1.0, 1.0]),
    ("CFS034CA301U", [150.0, 150.0, 300.0, 4.0, 4.0, 4.0]),
    ("PFS055YA501U6", [500.0, 500.0, 500.0, 10.0, 10.0, 8.0]),
    ("PFS080YS102U6", [500.0, 500.0, 1000.0, 40.0, 40.0, 30.0]),
]


def messages_vectors() -> dict[str, Any]:
    commands: list[dict[str, Any]] = []
    for name, code in CMD.items():
        if code == CMD["filter_set"]:
            for f in range(4):
                commands.append({"name": f"filter_set {f}", "message": hx(command(code, f)),
                                 "code": code, "filter": f})
        else:
            commands.append({"name": name, "message": hx(command(code)), "code": code})

    def bad_cmd(name: str, msg: str, error: str, result: int, code: int) -> dict[str, Any]:
        return {"name": name, "message": msg, "error": error, "result": result, "code": code}

    invalid_commands = [
        bad_cmd("empty", "", "length", 1, 0),
        bad_cmd("two bytes", "04 FF", "length", 1, 0),
        bad_cmd("three bytes", "04 FF 2A", "length", 1, 0x2A),
        bad_cmd("Length field 5, message 4 bytes", "05 FF 2A 00", "length", 1, 0x2A),
        bad_cmd("Length field 3, message 4 bytes", "03 FF 2B 00", "length", 1, 0x2B),
        bad_cmd("product info with a data byte", "05 FF 2A 00 00", "length", 1, 0x2A),
        bad_cmd("stop with four data bytes", "08 FF 33 00 00 00 00 00", "length", 1, 0x33),
        bad_cmd("filter set without data", "04 FF A6 00", "length", 1, 0xA6),
        bad_cmd("filter set one byte short", "07 FF A6 00 01 00 00", "length", 1, 0xA6),
        bad_cmd("filter set one byte long", "09 FF A6 00 01 00 00 00 00", "length", 1, 0xA6),
        bad_cmd("unknown code 0x40", "04 FF 40 00", "unexpected", 2, 0x40),
        bad_cmd("unknown code 0x00", "04 FF 00 00", "unexpected", 2, 0x00),
        bad_cmd("unknown code 0x31", "04 FF 31 00", "unexpected", 2, 0x31),
        bad_cmd("filter code 4", "08 FF A6 00 04 00 00 00", "value", 3, 0xA6),
        bad_cmd("filter code 0xFF", "08 FF A6 00 FF 00 00 00", "value", 3, 0xA6),
        bad_cmd("reserved byte 1 not 0xFF", "04 00 2A 00", "reserved", 3, 0x2A),
        bad_cmd("reserved byte 3 not 0x00", "04 FF 30 01", "reserved", 3, 0x30),
        bad_cmd("filter set reserved tail not zero", "08 FF A6 00 01 00 00 01", "reserved", 3,
                0xA6),
        bad_cmd("filter set reserved byte 5 not zero", "08 FF A6 00 01 01 00 00", "reserved", 3,
                0xA6),
        bad_cmd("filter set reserved byte 6 not zero", "08 FF A6 00 01 00 01 00", "reserved", 3,
                0xA6),
    ]
    command_encode_errors = [
        {"name": "unknown code", "code": 0x40, "error": "unexpected"},
        {"name": "filter code 4", "code": 0xA6, "filter": 4, "error": "value"},
        {"name": "filter code 0xFF", "code": 0xA6, "filter": 255, "error": "value"},
    ]

    responses: list[dict[str, Any]] = []

    def add(name: str, msg: bytes, **fields: Any) -> None:
        entry: dict[str, Any] = {"name": name, "message": hx(msg), "code": msg[2],
                                 "result": msg[3], "stream": False}
        entry.update(fields)
        responses.append(entry)

    def info(model: str, serial: str, fw: str, rate: str | None, hz: int) -> dict[str, Any]:
        return {"model": model, "serial": serial, "firmware": fw,
                "output_rate": rate if rate is not None else "",
                "has_output_rate": rate is not None, "output_rate_hz": hz}

    for model, serial, fw, rate, hz in [
        ("PFS055YA501U6", "12345678", "1.13", None, 0),
        ("CFS034CA301U", "00000000", "0100", None, 0),
        ("ABCDEFGHIJKLMNOP", "99999999", "ABCD", None, 0),
        ("PFS080YS102U6", "00012345", "1.31", "1200", 1200),
        ("CFS018CA201U", "20230001", "1.31", "1000", 1000),
        ("PFS055YA501U6", "00000042", "1.31", "N/A", 0),
        ("PFS055YA501U6", "00000043", "1.31", " 1200", 1200),
        ("PFS055YA501U6", "00000044", "1.31", "1200Hz", 0),
        ("PFS055YA501U6", "00000045", "1.31", "12 00", 0),
    ]:
        label = "38-byte" if rate is not None else "32-byte"
        add(f"product info {label} {model}" + (f" rate {rate}" if rate else ""),
            response(0x2A, 0, info_data(model, serial, fw, rate)),
            info=info(model, serial, fw, rate, hz))
    for model, values in PRESETS:
        add(f"rated values {model}", response(0x2B, 0, b"".join(f32(v) for v in values)),
            rated=values)
    fractional = [0.5, 2.25, 1234.5, 0.125, 3.75, 1e-3]
    fractional = [struct.unpack("<f", struct.pack("<f", v))[0] for v in fractional]
    add("rated values with fractions (float32-exact numbers)",
        response(0x2B, 0, b"".join(f32(v) for v in fractional)), rated=fractional)
    for f in range(4):
        add(f"filter query answer code {f}", response(0xB6, 0, bytes([f, 0, 0, 0])), filter=f)

    def smp(raw: list[int], status: int = 0, reserved: int = 0) -> dict[str, Any]:
        return {"raw": raw, "reserved": reserved, "status": status}

    add("handshake sample (spec worked frame)",
        response(0x30, 0, sample_data(SPEC_DATA_RAW, status=0x04)),
        sample=smp(SPEC_DATA_RAW, 0x04))
    add("handshake sample at rest", response(0x30, 0, sample_data([0] * 6)), sample=smp([0] * 6))
    add("handshake sample with sequence number and all status bits",
        response(0x30, 0, sample_data([1, -1, 32000, -32000, 15000, -15000], 0x07, 0xBEEF)),
        sample=smp([1, -1, 32000, -32000, 15000, -15000], 0x07, 0xBEEF))
    add("start ack", response(0x32, 0))
    add("stop ack", response(0x33, 0))
    add("filter set ack", response(0xA6, 0))
    add("continuous data message",
        response(0x32, 0, sample_data([100, -200, 9999, -1, 0, 4112], 0x00, 0x0102)),
        stream=True, sample=smp([100, -200, 9999, -1, 0, 4112], 0x00, 0x0102))
    add("continuous data message, overloaded and saturated",
        response(0x32, 0, sample_data([32000, -32000, 12000, 0, 0, 0], 0x04, 0xFFFF)),
        stream=True, sample=smp([32000, -32000, 12000, 0, 0, 0], 0x04, 0xFFFF))
    for code, result, what in [
        (0x2A, 1, "length error"), (0x2B, 2, "undefined command"), (0xA6, 3, "invalid value"),
        (0x32, 4, "state error (start while streaming)"), (0xA6, 4, "state error (filter set)"),
        (0x33, 1, "length error on stop"), (0x30, 2, "undefined command on sample"),
        (0xB6, 3, "invalid value on filter query"),
    ]:
        add(f"sensor result {result}: {what}", response(code, result), error="sensor")

    def bad(name: str, msg: bytes | str, error: str) -> dict[str, Any]:
        text = msg if isinstance(msg, str) else hx(msg)
        return {"name": name, "message": text, "error": error}

    rated_ok = [500.0, 500.0, 500.0, 10.0, 10.0, 8.0]

    def rated_with(index: int, pattern: bytes) -> bytes:
        data = bytearray(b"".join(f32(v) for v in rated_ok))
        data[4 * index:4 * index + 4] = pattern
        return response(0x2B, 0, bytes(data))

    info32 = response(0x2A, 0, info_data("PFS055YA501U6", "12345678", "1.13", None))
    smp_ok = response(0x30, 0, sample_data(SPEC_DATA_RAW, status=0x04))
    invalid_responses = [
        bad("empty", "", "length"),
        bad("three bytes", "04 FF 2A", "length"),
        bad("Length field 5, message 4 bytes", "05 FF 33 00", "length"),
        bad("Length field 4, message 5 bytes", "04 FF 33 00 00", "length"),
        bad("product info 31 bytes", bytes([31]) + info32[1:31], "length"),
        bad("product info 33 bytes", bytes([33]) + info32[1:] + b" ", "length"),
        bad("product info without data", response(0x2A, 0), "length"),
        bad("rated values 27 bytes", bytes([27]) + rated_with(0, f32(500.0))[1:27], "length"),
        bad("rated values without data", response(0x2B, 0), "length"),
        bad("filter query without data", response(0xB6, 0), "length"),
        bad("sample 19 bytes", bytes([19]) + smp_ok[1:19], "length"),
        bad("sample without data", response(0x30, 0), "length"),
        bad("start answer with 8 bytes", response(0x32, 0, bytes(4)), "length"),
        bad("stop answer with sample data", response(0x33, 0, sample_data([0] * 6)), "length"),
        bad("filter set ack with data", response(0xA6, 0, bytes([1, 0, 0, 0])), "length"),
        bad("reserved byte 1 not 0xFF", "04 00 33 00", "reserved"),
        bad("reserved byte 1 not 0xFF (sample)", bytes([0x14, 0xFE]) + smp_ok[2:], "reserved"),
        bad("non-zero result with data (filter)", response(0xB6, 3, bytes([1, 0, 0, 0])),
            "length"),
        bad("non-zero result with data (sample)",
            response(0x30, 4, sample_data(SPEC_DATA_RAW)), "length"),
        bad("rated NaN", rated_with(2, bytes.fromhex("0000C07F")), "value"),
        bad("rated +Inf", rated_with(0, bytes.fromhex("0000807F")), "value"),
        bad("rated -Inf", rated_with(5, bytes.fromhex("000080FF")), "value"),
        bad("rated negative", rated_with(3, f32(-10.0)), "value"),
        bad("rated zero", rated_with(1, f32(0.0)), "value"),
        bad("rated negative zero", rated_with(4, bytes.fromhex("00000080")), "value"),
        bad("filter code 4", response(0xB6, 0, bytes([4, 0, 0, 0])), "value"),
        bad("filter reserved byte not zero", response(0xB6, 0, bytes([1, 0, 1, 0])), "reserved"),
        bad("filter reserved byte 5 not zero", response(0xB6, 0, bytes([1, 1, 0, 0])), "reserved"),
        bad("filter reserved byte 7 not zero", response(0xB6, 0, bytes([1, 0, 0, 1])), "reserved"),
        bad("sample raw 32001 (beyond the v1.13 saturation)",
            response(0x30, 0, sample_data([0, 0, 32001, 0, 0, 0])), "value"),
        bad("sample raw -32001", response(0x30, 0, sample_data([0, 0, 0, 0, 0, -32001])), "value"),
        bad("stream raw 32767", response(0x32, 0, sample_data([32767, 0, 0, 0, 0, 0])), "value"),
        bad("stream raw -32768", response(0x32, 0, sample_data([0, -32768, 0, 0, 0, 0])), "value"),
        bad("product info with an escape sequence in the model",
            response(0x2A, 0, raw_info(b"PFS\x1b[2J055      ", b"12345678", b"1.13")), "value"),
        bad("product info with a NUL inside the model",
            response(0x2A, 0, raw_info(b"PFS\x00055YA501U6  ", b"12345678", b"1.13")), "value"),
        bad("product info with a NUL inside the serial",
            response(0x2A, 0, raw_info(b"PFS055YA501U6   ", b"1234\x00567", b"1.13")), "value"),
        bad("product info with a byte >= 0x80 in the firmware",
            response(0x2A, 0, raw_info(b"PFS055YA501U6   ", b"12345678", b"1.\xb33")), "value"),
        bad("product info with DEL in the serial",
            response(0x2A, 0, raw_info(b"PFS055YA501U6   ", b"1234567\x7f", b"1.13")), "value"),
        bad("product info with a control byte in the output rate",
            response(0x2A, 0, raw_info(b"PFS080YS102U6   ", b"00012345", b"1.31", b"12\r00 ")),
            "value"),
        bad("product info with a newline at the end of the model",
            response(0x2A, 0, raw_info(b"PFS055YA501U6\n  ", b"12345678", b"1.13")), "value"),
        bad("unknown code", "04 FF 40 00", "unexpected"),
        bad("unknown code with a result", "04 FF 40 02", "unexpected"),
    ]
    for entry in invalid_responses:
        m = unhex(entry["message"])
        if entry["error"] != "length" and len(m) >= 1:
            assert m[0] == len(m), entry  # only the intended defect

    # Firmware variants (protocol notes): accepted when decoding; encoding the
    # decoded fields gives the canonical v1.13 bytes (space padding, last byte 0).
    variants: list[dict[str, Any]] = []

    def variant(name: str, msg: bytes, canonical: bytes, last_reserved: int = 0,
                **fields: Any) -> None:
        entry: dict[str, Any] = {"name": name, "message": hx(msg), "canonical": hx(canonical),
                                 "code": msg[2], "result": msg[3], "stream": False,
                                 "last_reserved": last_reserved}
        entry.update(fields)
        variants.append(entry)

    for last in (0x01, 0x80, 0xFF):
        variant(f"continuous data, last reserved byte 0x{last:02X} (v1.31)",
                response(0x32, 0, sample_data([100, -200, 9999, -1, 0, 4112], 0x20, 7, last)),
                response(0x32, 0, sample_data([100, -200, 9999, -1, 0, 4112], 0x20, 7)),
                last_reserved=last, stream=True,
                sample=smp([100, -200, 9999, -1, 0, 4112], 0x20, 7))
    variant("handshake sample, last reserved byte 0x5A",
            response(0x30, 0, sample_data(SPEC_DATA_RAW, 0x04, 0, 0x5A)),
            response(0x30, 0, sample_data(SPEC_DATA_RAW, 0x04)), last_reserved=0x5A,
            sample=smp(SPEC_DATA_RAW, 0x04))
    canonical_info = response(0x2A, 0, info_data("PFS055YA501U6", "1234567", "1.13", None))
    for pad, what in ((b" ", "a space"), (b"\x00", "a NUL")):
        variant(f"seven-digit serial padded with {what}",
                response(0x2A, 0, raw_info(b"PFS055YA501U6   ", b"1234567" + pad, b"1.13")),
                canonical_info, info=info("PFS055YA501U6", "1234567", "1.13", None, 0))
    variant("text fields padded with NULs",
            response(0x2A, 0, info_data("PFS080YS102U6", "00012345", "1.31", None)
                     .replace(b" ", b"\x00")),
            response(0x2A, 0, info_data("PFS080YS102U6", "00012345", "1.31", None)),
            info=info("PFS080YS102U6", "00012345", "1.31", None, 0))
    variant("padding mixing spaces and NULs, empty firmware field",
            response(0x2A, 0, raw_info(b"CFS034CA301U\x00 \x00 ", b"0000001 ", b"\x00\x00\x00\x00",
                                        b"1200\x00\x00")),
            response(0x2A, 0, info_data("CFS034CA301U", "0000001", "", "1200")),
            info=info("CFS034CA301U", "0000001", "", "1200", 1200))

    si = []
    for model, values in PRESETS:
        raw = [10000, -10000, 5000, 1, -1, 32000]
        si.append({"name": f"{model} full scale, half, one count, saturated", "rated": values,
                   "raw": raw, "si": [r * v / 10000.0 for r, v in zip(raw, values)]})
    saturation = [
        {"name": "v1.13 limit", "raw": [32000, -32000, 31999, -31999, 32767, -32768],
         "limit": 32000, "mask": 0b110011},
        {"name": "later firmware limit", "raw": [15000, -15000, 14999, -14999, 0, 32000],
         "limit": 15000, "mask": 0b100011},
        {"name": "at rest", "raw": [0, 0, 0, 0, 0, 0], "limit": 15000, "mask": 0},
    ]
    return {
        "description": "Message codec vectors (spec 3-7); schema in README.md",
        "commands": commands,
        "invalid_commands": invalid_commands,
        "command_encode_errors": command_encode_errors,
        "responses": responses,
        "invalid_responses": invalid_responses,
        "response_variants": variants,
        "si": si,
        "saturation": saturation,
    }


def dump(obj: Any) -> str:
    return json.dumps(obj, indent=1, ensure_ascii=True) + "\n"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="fail if the files differ")
    ap.add_argument("--out", type=Path, default=HERE, help="output directory")
    args = ap.parse_args()
    files = {"frames.json": dump(frames_vectors()), "messages.json": dump(messages_vectors())}
    stale = []
    for name, text in files.items():
        path = args.out / name
        if args.check:
            if not path.exists() or path.read_text() != text:
                stale.append(name)
        else:
            path.write_text(text)
    if stale:
        print("stale: " + ", ".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
