"""Offline codec: decode captured bytes, encode frames and commands.

Thin wrappers over the library's own frame codec (lep_frame_decoder_*,
lep_frame_encode) and message codec (lep_response_decode, lep_command_decode,
lep_command_encode), so Python sees exactly what the C client sees.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

from . import _constants as K
from ._backend import get_backend
from .errors import error_for

DIRECTIONS = ("auto", "response", "command")


@dataclass(frozen=True)
class Message:
    """A decoded message (Length .. end of Data, unstuffed).

    direction: "response" or "command" (how it was decoded), "" when it is
      valid as neither (error then says why it failed).
    code:      message[2], the command (answered); 0 when shorter than 3 bytes.
    error:     0; LEP_E_SENSOR for a well-formed response with a non-zero
               result; else why decoding failed (LEP_E_LENGTH, ...).
    result:    a response's result code; for a rejected command, the result
               code a sensor answers it with (1, 2 or 3). None otherwise.
    fields:    the decoded content, as in test/vectors/messages.json:
               "info" {model, serial, firmware, output_rate, has_output_rate,
               output_rate_hz}, "rated" [6 floats], "filter" code, or "sample"
               {raw [6], reserved, status}; a filter-set command: "filter".
    """

    data: bytes
    direction: str
    code: int
    name: str
    error: int = 0
    error_text: str = ""
    result: Optional[int] = None
    meaning: str = ""
    stream: bool = False
    fields: Dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class Event:
    """One event of the frame decoder.

    kind:    "message" (a frame with a good BCC: see message), "nak" (DLE NAK),
             or "error" (a rejected frame; error is LEP_E_BCC, LEP_E_ESCAPE or
             LEP_E_TOO_LONG, error_text its description).
    offset:  index just past the input byte that completed the event.
    """

    kind: str
    offset: int
    message: Optional[Message] = None
    error: int = 0
    error_text: str = ""


class _Codec:
    """Scratch C structures for one backend."""

    def __init__(self, be: Any) -> None:
        self.be = be
        self.resp = be.new("lep_response")
        self.cmd = be.new("lep_command")
        self.result = be.new_scalar("uint8_t")

    def message(self, msg: bytes, direction: str) -> Message:
        be, lib = self.be, self.be.lib
        mbuf = be.bytes_in(msg)
        code = msg[2] if len(msg) >= 3 else 0
        name = be.text(lib.lep_command_name(code))
        rerr = 0
        if direction in ("auto", "response"):
            rc = int(lib.lep_response_decode(mbuf, len(msg), self.resp))
            if rc in (K.LEP_OK, K.LEP_E_SENSOR):
                return self._response(msg, rc)
            rerr = rc
            if direction == "response":
                return Message(msg, "", code, name, rc, be.text(lib.lep_strerror(rc)))
        rc = int(lib.lep_command_decode(mbuf, len(msg), self.cmd, self.result))
        ccode = int(self.cmd.code)
        if rc == K.LEP_OK:
            fields: Dict[str, Any] = {}
            if ccode == K.LEP_CMD_FILTER_SET:
                fields["filter"] = int(self.cmd.filter)
            return Message(msg, "command", ccode, name, fields=fields)
        if direction == "command":
            return Message(msg, "", ccode, name, rc, be.text(lib.lep_strerror(rc)),
                           result=int(be.value(self.result)))
        return Message(msg, "", code, name, rerr, be.text(lib.lep_strerror(rerr)))

    def _response(self, msg: bytes, rc: int) -> Message:
        be, r = self.be, self.resp
        code, result = int(r.code), int(r.result)
        fields: Dict[str, Any] = {}
        if rc == K.LEP_OK:
            if r.stream or code == K.LEP_CMD_SAMPLE:
                s = r.u.sample
                fields["sample"] = {"raw": [int(v) for v in s.raw],
                                    "reserved": int(s.reserved), "status": int(s.status)}
            elif code == K.LEP_CMD_PRODUCT_INFO:
                i = r.u.info
                fields["info"] = {
                    "model": be.text(i.model),
                    "serial": be.text(i.serial),
                    "firmware": be.text(i.firmware),
                    "output_rate": be.text(i.output_rate),
                    "has_output_rate": bool(i.has_output_rate),
                    "output_rate_hz": int(i.output_rate_hz),
                }
            elif code == K.LEP_CMD_RATED:
                fields["rated"] = [float(v) for v in r.u.rated.axis]
            elif code == K.LEP_CMD_FILTER_GET:
                fields["filter"] = int(r.u.filter)
        lib = be.lib
        return Message(
            msg, "response", code, be.text(lib.lep_command_name(code)),
            rc, be.text(lib.lep_strerror(rc)) if rc else "",
            result=result, meaning=be.text(lib.lep_result_str(result)),
            stream=bool(r.stream), fields=fields,
        )


def _check_direction(direction: str) -> None:
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {', '.join(DIRECTIONS)}, not {direction!r}")


class Decoder:
    """Push decoder for a byte log: feed() any chunks, get the events.

    The events do not depend on how the input is split. direction says how
    messages are decoded: "auto" (a response when valid as one, else a
    command; note that an acknowledgement such as 04 FF 32 00 is byte for
    byte the command it answers, and is reported as a response), "response"
    or "command"."""

    def __init__(self, direction: str = "auto", *, backend: Optional[str] = None) -> None:
        _check_direction(direction)
        self._be = be = get_backend(backend)
        self.direction = direction
        self._codec = _Codec(be)
        self._dec, self._dec_mem = be.new_opaque("lep_frame_decoder")
        be.lib.lep_frame_decoder_init(self._dec)
        self._ev = be.new("lep_frame_event")
        self._pos = 0

    @property
    def stats(self) -> Dict[str, int]:
        """Frame decoder counters (lep_frame_stats): messages, naks, bcc_errors,
        escape_errors, overruns, restarts, bytes_discarded."""
        s = self._be.new("lep_frame_stats")
        self._be.lib.lep_frame_decoder_get_stats(self._dec, s)
        return {name: int(getattr(s, name)) for name in (
            "messages", "naks", "bcc_errors", "escape_errors", "overruns", "restarts",
            "bytes_discarded")}

    @property
    def busy(self) -> bool:
        """True while inside a frame (the input so far ends mid-frame)."""
        return bool(self._be.lib.lep_frame_decoder_busy(self._dec))

    def feed(self, data: bytes) -> List[Event]:
        be, lib = self._be, self._be.lib
        data = bytes(data)
        buf = be.bytes_in(data)
        events: List[Event] = []
        off = 0
        while off < len(data):
            used = int(lib.lep_frame_decoder_feed(self._dec, be.offset(buf, off),
                                                  len(data) - off, self._ev))
            if used <= 0:  # the contract says it always consumes; never loop forever
                raise RuntimeError("lep_frame_decoder_feed consumed nothing")
            off += used
            ev, at = self._ev, self._pos + off
            if ev.type == K.LEP_FRAME_MESSAGE:
                msg = be.bytes_at(ev.msg, int(ev.len)) if ev.len else b""
                events.append(Event("message", at, self._codec.message(msg, self.direction)))
            elif ev.type == K.LEP_FRAME_NAK:
                events.append(Event("nak", at))
            elif ev.type == K.LEP_FRAME_ERROR:
                err = int(ev.error)
                events.append(Event("error", at, error=err,
                                    error_text=be.text(lib.lep_strerror(err))))
        self._pos += len(data)
        return events


def decode(data: bytes, direction: str = "auto", *, backend: Optional[str] = None) -> List[Event]:
    """Decode a captured byte log into events (messages, NAKs, rejected frames).

    See Event, Message, and Decoder for direction."""
    return Decoder(direction, backend=backend).feed(data)


def decode_message(msg: bytes, direction: str = "auto", *,
                   backend: Optional[str] = None) -> Message:
    """Decode one unstuffed message (Length .. end of Data)."""
    _check_direction(direction)
    return _Codec(get_backend(backend)).message(bytes(msg), direction)


def encode_frame(msg: bytes, *, backend: Optional[str] = None) -> bytes:
    """Frame an unstuffed message for the wire (DLE STX, stuffing, DLE ETX, BCC).
    ProtocolError (error LEP_E_TOO_LONG) over 128 bytes; LeptrinoError for empty."""
    be = get_backend(backend)
    msg = bytes(msg)
    out = be.bytes_out(K.LEP_MAX_FRAME)
    n = be.new_scalar("size_t")
    rc = int(be.lib.lep_frame_encode(be.bytes_in(msg), len(msg), out, K.LEP_MAX_FRAME, n))
    if rc < 0:
        raise error_for(be, rc, f"framing a {len(msg)}-byte message")
    return bytes(be.bytes_at(out, int(be.value(n))))


def encode_command(code: int, filter: int = 0, *, framed: bool = True,
                   backend: Optional[str] = None) -> bytes:
    """A command (code: 0x2A, 0x2B, 0xB6, 0x30, 0x32, 0x33, or 0xA6 with filter),
    as a wire frame, or as the unstuffed message with framed=False."""
    be = get_backend(backend)
    cmd = be.new("lep_command")
    cmd.code = int(code) & 0xFF
    cmd.filter = int(filter) & 0xFF
    out = be.bytes_out(K.LEP_MAX_FRAME)
    n = be.new_scalar("size_t")
    fn = be.lib.lep_command_frame if framed else be.lib.lep_command_encode
    rc = int(fn(cmd, out, K.LEP_MAX_FRAME, n))
    if rc < 0:
        raise error_for(be, rc, f"encoding command 0x{int(code) & 0xFF:02X}")
    return bytes(be.bytes_at(out, int(be.value(n))))


def sample_to_si(raw: Sequence[int], rated: Sequence[float], *,
                 backend: Optional[str] = None) -> Tuple[float, ...]:
    """raw * rated / 10000 per axis (N, N·m), computed by lep_sample_to_si."""
    be = get_backend(backend)
    s, r, si = be.new("lep_sample"), be.new("lep_rated"), be.doubles(K.LEP_AXES)
    for i in range(K.LEP_AXES):
        s.raw[i] = int(raw[i])
        r.axis[i] = float(rated[i])
    be.lib.lep_sample_to_si(s, r, si)
    return tuple(float(si[i]) for i in range(K.LEP_AXES))


def saturation_mask(raw: Sequence[int], limit: int = K.LEP_SATURATION_V113, *,
                    backend: Optional[str] = None) -> int:
    """Bit i set when |raw[i]| >= limit (32000 for v1.13, 15000 for later firmware)."""
    be = get_backend(backend)
    s = be.new("lep_sample")
    for i in range(K.LEP_AXES):
        s.raw[i] = int(raw[i])
    return int(be.lib.lep_sample_saturated(s, int(limit)))
