#!/usr/bin/env python3
"""Write seed corpora for the fuzz targets from the shared vectors.

    python3 test/fuzz/seeds.py OUTDIR    # OUTDIR/<target>/seed-NNNN for each target

Seeds: every wire frame and message of test/vectors (frames.json,
messages.json), in the input format of each target (see test/fuzz/*.c).
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
VECTORS = HERE.parent / "vectors"
DLE, STX, ETX = 0x10, 0x02, 0x03


def frame(msg: bytes) -> bytes:
    bcc = ETX
    out = bytearray([DLE, STX])
    for b in msg:
        bcc ^= b
        out.append(b)
        if b == DLE:
            out.append(DLE)
    return bytes(out + bytes([DLE, ETX, bcc]))


def main() -> int:
    out = Path(sys.argv[1])
    frames = json.loads((VECTORS / "frames.json").read_text())
    messages = json.loads((VECTORS / "messages.json").read_text())
    wires = [bytes.fromhex(v["wire"]) for v in frames["encode"]]
    wires += [bytes.fromhex(v["input"]) for v in frames["decode"]]
    msgs = [bytes.fromhex(v["message"]) for key in
            ("commands", "invalid_commands", "responses", "invalid_responses", "response_variants")
            for v in messages[key]]
    commands = [bytes.fromhex(v["message"]) for v in messages["commands"] + messages["invalid_commands"]]
    answers = [frame(bytes.fromhex(v["message"])) for v in
               messages["responses"] + messages["response_variants"]]
    seeds: dict[str, list[bytes]] = {
        "protocol": wires + answers,
        "message": [bytes([len(m)]) + m for m in msgs] + [b"".join(bytes([len(m)]) + m for m in msgs)],
        "device": [frame(c) for c in commands] + [b"".join(frame(c) for c in commands)],
        "client": [],
    }
    # Client: config byte, write-failure byte, then reads delivering 32 bytes each (0xFF).
    stream = b"".join(answers)
    chunks = [stream[i:i + 32] for i in range(0, len(stream), 32)]
    scripted = b"".join(b"\xff" + c for c in chunks)
    for cfg in (0x00, 0x21, 0x42, 0x63, 0x80, 0xC1, 0xE3):
        seeds["client"].append(bytes([cfg, 0]) + scripted)
    seeds["client"].append(bytes([0x40, 5]) + b"\x20\x80\x00\x00\x00" + scripted)
    for name, items in seeds.items():
        d = out / name
        d.mkdir(parents=True, exist_ok=True)
        for i, data in enumerate(items):
            (d / f"seed-{i:04d}").write_bytes(data)
    print(" ".join(f"{k}={len(v)}" for k, v in seeds.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
