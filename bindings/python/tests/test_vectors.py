"""The shared vectors (test/vectors/*.json) through the bindings, exactly."""

from __future__ import annotations

import json
import random
from pathlib import Path
from typing import Any, Dict, List

import pytest

import leptrino
from leptrino import _constants as K

ERRORS = {
    "arg": K.LEP_E_ARG,
    "buffer": K.LEP_E_BUFFER,
    "too_long": K.LEP_E_TOO_LONG,
    "bcc": K.LEP_E_BCC,
    "escape": K.LEP_E_ESCAPE,
    "length": K.LEP_E_LENGTH,
    "reserved": K.LEP_E_RESERVED,
    "unexpected": K.LEP_E_UNEXPECTED,
    "value": K.LEP_E_VALUE,
    "sensor": K.LEP_E_SENSOR,
}


def hx(s: str) -> bytes:
    return bytes.fromhex("".join(s.split()))


def load(root: Path, name: str) -> Dict[str, Any]:
    path = root / "test" / "vectors" / name
    if not path.is_file():
        pytest.skip(f"{path} is missing")
    return json.loads(path.read_text(encoding="utf-8"))


def as_vector_events(events: List[leptrino.Event]) -> List[Dict[str, Any]]:
    out: List[Dict[str, Any]] = []
    for e in events:
        if e.kind == "message":
            assert e.message is not None
            out.append({"type": "message", "message": e.message.data})
        elif e.kind == "nak":
            out.append({"type": "nak"})
        else:
            out.append({"type": "error", "error": e.error})
    return out


def expected_events(events: List[Dict[str, Any]]) -> List[Dict[str, Any]]:
    out: List[Dict[str, Any]] = []
    for e in events:
        if e["type"] == "message":
            out.append({"type": "message", "message": hx(e["message"])})
        elif e["type"] == "nak":
            out.append({"type": "nak"})
        else:
            out.append({"type": "error", "error": ERRORS[e["error"]]})
    return out


def test_frame_encode(backend: str, root: Path) -> None:
    v = load(root, "frames.json")
    assert v["encode"]
    for case in v["encode"]:
        msg, wire = hx(case["message"]), hx(case["wire"])
        assert leptrino.encode_frame(msg, backend=backend) == wire, case["name"]
        ev = leptrino.decode(wire, backend=backend)
        assert as_vector_events(ev) == [{"type": "message", "message": msg}], case["name"]


def test_frame_encode_errors(backend: str, root: Path) -> None:
    for case in load(root, "frames.json")["encode_errors"]:
        with pytest.raises(leptrino.LeptrinoError) as info:
            leptrino.encode_frame(hx(case["message"]), backend=backend)
        assert info.value.error == ERRORS[case["error"]], case["name"]


@pytest.mark.parametrize("chunking", ["whole", "bytewise", "random"])
def test_frame_decode(backend: str, root: Path, chunking: str) -> None:
    v = load(root, "frames.json")
    rng = random.Random(5)
    assert v["decode"]
    for case in v["decode"]:
        data = hx(case["input"])
        dec = leptrino.Decoder(backend=backend)
        events: List[leptrino.Event] = []
        if chunking == "whole":
            events = dec.feed(data)
        elif chunking == "bytewise":
            for i in range(len(data)):
                events += dec.feed(data[i:i + 1])
        else:
            i = 0
            while i < len(data):
                n = rng.randint(1, 12)
                events += dec.feed(data[i:i + n])
                i += n
        assert as_vector_events(events) == expected_events(case["events"]), case["name"]
        assert dec.stats == case["stats"], case["name"]
        assert not dec.busy, case["name"]


def test_commands(backend: str, root: Path) -> None:
    v = load(root, "messages.json")
    for case in v["commands"]:
        msg = hx(case["message"])
        filt = case.get("filter", 0)
        assert leptrino.encode_command(case["code"], filt, framed=False,
                                       backend=backend) == msg, case["name"]
        m = leptrino.decode_message(msg, "command", backend=backend)
        assert (m.direction, m.code, m.error) == ("command", case["code"], 0), case["name"]
        assert m.fields.get("filter", 0) == filt, case["name"]


def test_invalid_commands(backend: str, root: Path) -> None:
    for case in load(root, "messages.json")["invalid_commands"]:
        m = leptrino.decode_message(hx(case["message"]), "command", backend=backend)
        assert m.direction == "", case["name"]
        assert (m.error, m.result, m.code) == (
            ERRORS[case["error"]], case["result"], case["code"]), case["name"]


def test_command_encode_errors(backend: str, root: Path) -> None:
    for case in load(root, "messages.json")["command_encode_errors"]:
        with pytest.raises(leptrino.LeptrinoError) as info:
            leptrino.encode_command(case["code"], case.get("filter", 0), backend=backend)
        assert info.value.error == ERRORS[case["error"]], case["name"]


def test_responses(backend: str, root: Path) -> None:
    v = load(root, "messages.json")
    assert v["responses"]
    for case in v["responses"]:
        m = leptrino.decode_message(hx(case["message"]), "response", backend=backend)
        assert m.direction == "response", case["name"]
        assert m.error == ERRORS.get(case.get("error", ""), 0), case["name"]
        assert (m.code, m.result, m.stream) == (case["code"], case["result"], case["stream"]), \
            case["name"]
        want = {k: case[k] for k in ("info", "rated", "filter", "sample") if k in case}
        assert m.fields == want, case["name"]


def test_invalid_responses(backend: str, root: Path) -> None:
    for case in load(root, "messages.json")["invalid_responses"]:
        m = leptrino.decode_message(hx(case["message"]), "response", backend=backend)
        assert m.direction == "", case["name"]
        assert m.error == ERRORS[case["error"]], case["name"]


def test_si(backend: str, root: Path) -> None:
    for case in load(root, "messages.json")["si"]:
        got = leptrino.sample_to_si(case["raw"], case["rated"], backend=backend)
        assert list(got) == case["si"], case["name"]


def test_saturation(backend: str, root: Path) -> None:
    for case in load(root, "messages.json")["saturation"]:
        got = leptrino.saturation_mask(case["raw"], case["limit"], backend=backend)
        assert got == case["mask"], case["name"]


def test_decode_log_mixes_directions(backend: str) -> None:
    """A capture with commands, answers, a NAK and noise, decoded in order."""
    log = (leptrino.encode_command(0xA6, 1, backend=backend) + b"\x00\x10\x15"
           + leptrino.encode_frame(hx("04 FF A6 03"), backend=backend)
           + leptrino.encode_command(0x2B, backend=backend))
    ev = leptrino.decode(log, backend=backend)
    assert [e.kind for e in ev] == ["message", "nak", "message", "message"]
    m0, m2 = ev[0].message, ev[2].message
    assert m0 is not None and m2 is not None
    assert (m0.direction, m0.code, m0.fields) == ("command", 0xA6, {"filter": 1})
    assert (m2.direction, m2.result, m2.error) == ("response", 3, K.LEP_E_SENSOR)
    assert m2.meaning
    assert ev[-1].offset == len(log)
