"""Offline decoding of captured bytes: leptrino.decode(data) and Decoder.

Runs the library's own frame decoder (lep_frame_decoder_*) and message codec
(lep_response_decode / lep_command_decode) over the bytes, so Python sees
exactly what the C client sees.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

from . import _constants as K
from ._backend import get_backend
from .sensor import product_info_from

DIRECTIONS = ("auto", "response", "command")


@dataclass(frozen=True)
class Event:
    """One event of the frame decoder.

    kind:   "message" (a frame with a good BCC), "nak" (DLE NAK) or
            "error" (a rejected frame: error is LEP_E_BCC, LEP_E_ESCAPE or
            LEP_E_TOO_LONG).
    offset: index just past the input byte that completed the event.
    For messages: data is the unstuffed message; direction is "response" or
    "command" (how it was decoded) or "" when it is valid as neither, then
    error holds why it failed as a response (LEP_E_LENGTH, ...). code/name is
    the command (answered); result/meaning the response's result code (a
    non-zero result is a valid response: error LEP_E_SENSOR is not set);
    fields the decoded content:
      product info: model, serial, firmware, output_rate, output_rate_hz,
                    has_output_rate
      rated:        rated (6 floats: Fx Fy Fz N, Mx My Mz N·m)
      filter query: filter; filter set command: filter
      sample/data:  raw (6 ints), status, reserved (leptrino-sim's sequence)
    """

    kind: str
    offset: int
    data: bytes = b""
    error: int = 0
    error_text: str = ""
    direction: str = ""
    code: Optional[int] = None
    name: str = ""
    result: Optional[int] = None
    meaning: str = ""
    stream: bool = False
    fields: Dict[str, Any] = field(default_factory=dict)


class Decoder:
    """Push decoder for a byte log: feed() any chunks, get the events.

    direction: "auto" (a response when valid as one, else a command: note
    that a bare acknowledgement such as 04 FF 32 00 is byte-for-byte the
    command it answers, and is reported as a response), "response" or
    "command"."""

    def __init__(self, direction: str = "auto", *, backend: Optional[str] = None) -> None:
        if direction not in DIRECTIONS:
            raise ValueError(f"direction must be one of {', '.join(DIRECTIONS)}")
        self._be = be = get_backend(backend)
        self.direction = direction
        self._dec = be.new("lep_frame_decoder")
        be.lib.lep_frame_decoder_init(self._dec)
        self._ev = be.new("lep_frame_event")
        self._resp = be.new("lep_response")
        self._cmd = be.new("lep_command")
        self._result = be.new_scalar("uint8_t")
        self._pos = 0

    @property
    def stats(self) -> Dict[str, int]:
        """Frame decoder counters: messages, naks, bcc_errors, escape_errors,
        overruns, restarts, bytes_discarded."""
        s = self._dec.stats
        return {name: int(getattr(s, name)) for name in (
            "messages", "naks", "bcc_errors", "escape_errors", "overruns", "restarts",
            "bytes_discarded")}

    @property
    def busy(self) -> bool:
        """True while inside a frame (the input ended mid-frame)."""
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
            if used == 0:  # never expected; guard against a loop
                break
            off += used
            ev = self._ev
            at = self._pos + off
            if ev.type == K.LEP_FRAME_MESSAGE:
                events.append(self._message(be.bytes_at(ev.msg, int(ev.len)), at))
            elif ev.type == K.LEP_FRAME_NAK:
                events.append(Event("nak", at))
            elif ev.type == K.LEP_FRAME_ERROR:
                err = int(ev.error)
                events.append(Event("error", at, error=err,
                                    error_text=be.text(lib.lep_strerror(err))))
        self._pos += len(data)
        return events

    def _message(self, msg: bytes, at: int) -> Event:
        be, lib = self._be, self._be.lib
        mbuf = be.bytes_in(msg)
        code = msg[2] if len(msg) >= 3 else None
        name = be.text(lib.lep_command_name(code)) if code is not None else ""
        rerr = 0
        if self.direction in ("auto", "response"):
            rc = int(lib.lep_response_decode(mbuf, len(msg), self._resp))
            if rc in (K.LEP_OK, K.LEP_E_SENSOR):
                return self._response(msg, at, name)
            rerr = rc
            if self.direction == "response":
                return Event("message", at, data=msg, error=rc,
                             error_text=be.text(lib.lep_strerror(rc)), code=code, name=name)
        rc = int(lib.lep_command_decode(mbuf, len(msg), self._cmd, self._result))
        if rc == K.LEP_OK:
            fields: Dict[str, Any] = {}
            if self._cmd.code == K.LEP_CMD_FILTER_SET:
                fields["filter"] = int(self._cmd.filter)
            return Event("message", at, data=msg, direction="command", code=int(self._cmd.code),
                         name=name, fields=fields)
        err = rerr or rc
        return Event("message", at, data=msg, error=err,
                     error_text=be.text(lib.lep_strerror(err)), code=code, name=name)

    def _response(self, msg: bytes, at: int, name: str) -> Event:
        be, r = self._be, self._resp
        code, result = int(r.code), int(r.result)
        fields: Dict[str, Any] = {}
        if result == 0:
            if r.stream or code == K.LEP_CMD_SAMPLE:
                s = r.u.sample
                fields = {"raw": [int(v) for v in s.raw], "status": int(s.status),
                          "reserved": int(s.reserved)}
            elif code == K.LEP_CMD_PRODUCT_INFO:
                info = product_info_from(be, r.u.info)
                fields = {"model": info.model, "serial": info.serial,
                          "firmware": info.firmware, "output_rate": info.output_rate,
                          "output_rate_hz": info.output_rate_hz,
                          "has_output_rate": info.has_output_rate}
            elif code == K.LEP_CMD_RATED:
                fields = {"rated": [float(v) for v in r.u.rated.axis]}
            elif code == K.LEP_CMD_FILTER_GET:
                fields = {"filter": int(r.u.filter)}
        return Event("message", at, data=msg, direction="response", code=code, name=name,
                     result=result, meaning=be.text(be.lib.lep_result_str(result)),
                     stream=bool(r.stream), fields=fields)


def decode(data: bytes, direction: str = "auto", *, backend: Optional[str] = None) -> List[Event]:
    """Decode a captured byte log into events (messages, NAKs, rejected frames).

    See Event for what each carries and Decoder for direction."""
    return Decoder(direction, backend=backend).feed(data)


def encode_command(code: int, filter: int = 0, *, backend: Optional[str] = None) -> bytes:
    """The wire frame of a command (code: LEP_CMD_*; filter for 0xA6)."""
    be = get_backend(backend)
    cmd = be.new("lep_command")
    cmd.code = code
    cmd.filter = filter
    out = be.bytes_out(K.LEP_MAX_FRAME)
    n = be.new_scalar("size_t")
    rc = int(be.lib.lep_command_frame(cmd, out, K.LEP_MAX_FRAME, n))
    if rc < 0:
        from .errors import error_for

        raise error_for(be, rc, f"encoding command 0x{code:02X}")
    return be.bytes_at(out, int(be.value(n)))
