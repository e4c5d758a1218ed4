"""ctypes backend: declarations of the libleptrino subset and the helpers the
high-level code uses (allocation, strings, pointers).

Every function gets exact argtypes/restype; tests/test_declarations.py checks
them, and the structure layouts, against include/leptrino/*.h.
"""

from __future__ import annotations

import ctypes
from ctypes import (
    POINTER,
    Structure,
    Union,
    c_bool,
    c_char,
    c_char_p,
    c_double,
    c_float,
    c_int,
    c_int16,
    c_size_t,
    c_uint,
    c_uint8,
    c_uint16,
    c_uint32,
    c_uint64,
)
from typing import Any, Dict, List, Optional, Tuple

from . import _loader


class lep_frame_event(Structure):
    _fields_ = [
        ("type", c_int),
        ("error", c_int),
        ("msg", POINTER(c_uint8)),
        ("len", c_size_t),
    ]


class lep_frame_stats(Structure):
    _fields_ = [
        ("messages", c_uint32),
        ("naks", c_uint32),
        ("bcc_errors", c_uint32),
        ("escape_errors", c_uint32),
        ("overruns", c_uint32),
        ("restarts", c_uint32),
        ("bytes_discarded", c_uint32),
    ]


class lep_frame_decoder(Structure):
    """Opaque here: allocated as lep_frame_decoder_sizeof() bytes."""


class lep_command(Structure):
    _fields_ = [("code", c_uint8), ("filter", c_uint8)]


class lep_product_info(Structure):
    _fields_ = [
        ("model", c_char * 17),
        ("serial", c_char * 9),
        ("firmware", c_char * 5),
        ("output_rate", c_char * 7),
        ("has_output_rate", c_bool),
        ("output_rate_hz", c_uint32),
    ]


class lep_rated(Structure):
    _fields_ = [("axis", c_float * 6)]


class lep_sample(Structure):
    _fields_ = [
        ("raw", c_int16 * 6),
        ("reserved", c_uint16),
        ("status", c_uint8),
    ]


class _lep_response_u(Union):
    _fields_ = [
        ("info", lep_product_info),
        ("rated", lep_rated),
        ("filter", c_uint8),
        ("sample", lep_sample),
    ]


class lep_response(Structure):
    _fields_ = [
        ("code", c_uint8),
        ("result", c_uint8),
        ("stream", c_bool),
        ("u", _lep_response_u),
    ]


class lep_client(Structure):
    """Opaque here: allocated as lep_client_sizeof() bytes."""


class lep_client_stats(Structure):
    _fields_ = [
        ("messages", c_uint32),
        ("bcc_errors", c_uint32),
        ("frame_errors", c_uint32),
        ("bytes_discarded", c_uint32),
        ("naks", c_uint32),
        ("retries", c_uint32),
        ("unexpected", c_uint32),
        ("invalid", c_uint32),
        ("timeouts", c_uint32),
        ("samples", c_uint32),
        ("resent_after_timeout", c_uint32),
        ("resent_confirmed", c_uint32),
        ("recoveries", c_uint32),
        ("reserved_nonzero", c_uint32),
        ("stalls", c_uint32),
    ]


class lep_serial(Structure):
    """Opaque (serial.h)."""


class lep_serial_info(Structure):
    _fields_ = [
        ("low_latency", c_bool),
        ("ftdi_latency_ms", c_int),
        ("ftdi_lowered", c_bool),
    ]


class lep_port_info(Structure):
    _fields_ = [
        ("path", c_char * 256),
        ("by_id", c_char * 256),
        ("description", c_char * 128),
        ("vid", c_uint16),
        ("pid", c_uint16),
        ("likely_sensor", c_bool),
    ]


class lep_sim(Structure):
    """Opaque (sim.h)."""


class lep_sim_options(Structure):
    _fields_ = [
        ("model", c_char * 32),
        ("serial", c_char * 16),
        ("firmware", c_char * 8),
        ("output_rate_field", c_bool),
        ("rate_hz", c_double),
        ("filter", c_uint8),
        ("seed", c_uint64),
        ("amplitude", c_double),
        ("noise", c_double),
        ("constant", c_bool),
        ("replay_csv", c_char * 512),
        ("overload_every_s", c_double),
        ("overload_duration_s", c_double),
        ("p_nak", c_double),
        ("p_corrupt", c_double),
        ("p_garbage", c_double),
        ("p_drop", c_double),
        ("stall_ms", c_int),
        ("stall_after_s", c_double),
        ("hangup_after_s", c_double),
        ("reopen_after_ms", c_int),
        ("start_streaming", c_bool),
        ("link", c_char * 512),
        ("payload", c_double * 4),
        ("gravity", c_double * 3),
    ]


class lep_sim_option_info(Structure):
    _fields_ = [
        ("name", c_char_p),
        ("type", c_int),
        ("arg", c_char_p),
        ("help", c_char_p),
        ("default_text", c_char_p),
        ("min", c_double),
        ("max", c_double),
        ("min_exclusive", c_bool),
    ]


class lep_sim_stats(Structure):
    _fields_ = [
        ("samples_sent", c_uint64),
        ("samples_dropped", c_uint64),
        ("commands", c_uint64),
        ("naks", c_uint64),
        ("bytes_corrupted", c_uint64),
        ("hangups", c_uint64),
        ("streaming", c_bool),
        ("filter", c_uint8),
        ("filter_pending", c_uint8),
        ("hung_up", c_bool),
        ("sequence", c_uint16),
        ("responses", c_uint64),
        ("faked_naks", c_uint64),
        ("samples_skipped", c_uint64),
        ("samples_blocked", c_uint64),
        ("garbage_bytes", c_uint64),
        ("bytes_received", c_uint64),
        ("reopens", c_uint64),
        ("power_cycles", c_uint64),
        ("stalls", c_uint64),
    ]


class lep_record_batch(Structure):
    _fields_ = [
        ("cap", c_size_t),
        ("n", c_size_t),
        ("t", POINTER(c_double)),
        ("si", POINTER(c_double)),
        ("raw", POINTER(c_int16)),
        ("status", POINTER(c_uint8)),
        ("seq", POINTER(c_uint16)),
    ]


class lep_payload(Structure):
    _fields_ = [("mass_kg", c_double), ("com_m", c_double * 3)]


class lep_payload_fit(Structure):
    _fields_ = [
        ("payload", lep_payload),
        ("force_bias_N", c_double * 3),
        ("torque_bias_Nm", c_double * 3),
        ("residual", c_double * 6),
        ("spread", c_double),
        ("poses", c_size_t),
    ]


class lep_session(Structure):
    """Opaque (session.h)."""


class lep_session_options(Structure):
    _fields_ = [
        ("port", c_char_p),
        ("use_sim", c_bool),
        ("sim", lep_sim_options),
        ("timeout_ms", c_int),
        ("sync_quiet_ms", c_int),
        ("data_timeout_ms", c_int),
        ("gap_periods", c_double),
        ("nominal_hz", c_double),
        ("reconnect", c_bool),
        ("reconnect_min_ms", c_int),
        ("reconnect_max_ms", c_int),
        ("reconnect_give_up_ms", c_int),
        ("latency_ms", c_int),
        ("tare_samples", c_uint),
        ("lowpass_hz", c_double),
        ("decimate", c_uint),
        ("rotation", c_double * 9),
        ("shift_m", c_double * 3),
        ("duration_s", c_double),
        ("count", c_uint64),
        ("payload", lep_payload),
        ("gravity", c_double * 3),
        ("limit", c_double * 6),
    ]


class lep_session_batch(Structure):
    _fields_ = [
        ("cap", c_size_t),
        ("n", c_size_t),
        ("t_mono", POINTER(c_double)),
        ("t_utc", POINTER(c_double)),
        ("raw", POINTER(c_int16)),
        ("zeroed", POINTER(c_double)),
        ("si", POINTER(c_double)),
        ("status", POINTER(c_uint8)),
        ("flags", POINTER(c_uint8)),
        ("seq", POINTER(c_uint16)),
    ]


class lep_session_event(Structure):
    _fields_ = [
        ("type", c_int),
        ("sample", c_uint64),
        ("t_mono", c_double),
        ("t_utc", c_double),
        ("gap_from", c_double),
        ("gap_to", c_double),
        ("lost", c_uint32),
        ("error", c_int),
        ("axes", c_uint8),
        ("status", c_uint8),
        ("tare", c_double * 6),
        ("wrench", c_double * 6),
    ]


class lep_session_health(Structure):
    _fields_ = [
        ("elapsed_s", c_double),
        ("nominal_hz", c_double),
        ("measured_hz", c_double),
        ("recent_hz", c_double),
        ("shortfall", c_bool),
        ("received", c_uint64),
        ("delivered", c_uint64),
        ("lost", c_uint64),
        ("gaps", c_uint64),
        ("errors", c_uint64),
        ("overloads", c_uint64),
        ("disconnects", c_uint64),
        ("reconnects", c_uint64),
        ("events_dropped", c_uint64),
        ("max_gap_s", c_double),
        ("client", lep_client_stats),
    ]


class lep_session_metadata(Structure):
    _fields_ = [
        ("info", lep_product_info),
        ("protocol", c_char * 24),
        ("rated", lep_rated),
        ("sensor_filter", c_int),
        ("sensor_filter_label", c_char * 24),
        ("nominal_hz", c_double),
        ("lowpass_hz", c_double),
        ("lowpass_name", c_char * 48),
        ("lowpass_delay_s", c_double),
        ("decimate", c_uint),
        ("rotation", c_double * 9),
        ("shift_m", c_double * 3),
        ("tared", c_bool),
        ("tare", c_double * 6),
        ("start_utc", c_double),
        ("start_mono", c_double),
        ("port", c_char * 256),
        ("sim", c_bool),
        ("library_version", c_char * 16),
        ("payload", lep_payload),
        ("gravity", c_double * 3),
        ("limit", c_double * 6),
    ]


class lep_output_options(Structure):
    _fields_ = [
        ("format", c_int),
        ("time", c_int),
        ("columns", c_uint),
        ("t0_mono", c_double),
        ("overwrite", c_bool),
    ]


class lep_output(Structure):
    """Opaque (output.h)."""


#: C struct name -> ctypes class (for allocation and the declaration check).
STRUCTS: Dict[str, Any] = {
    cls.__name__: cls
    for cls in (
        lep_frame_event,
        lep_frame_stats,
        lep_frame_decoder,
        lep_command,
        lep_product_info,
        lep_rated,
        lep_sample,
        lep_response,
        lep_client,
        lep_client_stats,
        lep_serial,
        lep_serial_info,
        lep_port_info,
        lep_sim,
        lep_sim_options,
        lep_sim_option_info,
        lep_sim_stats,
        lep_record_batch,
        lep_session,
        lep_session_options,
        lep_session_batch,
        lep_session_event,
        lep_session_health,
        lep_session_metadata,
        lep_output_options,
        lep_output,
        lep_payload,
        lep_payload_fit,
    )
}

#: Types allocated by the library (or as bytes): no fields declared here.
OPAQUE = ("lep_frame_decoder", "lep_client", "lep_serial", "lep_sim", "lep_session", "lep_output")

_u8p = POINTER(c_uint8)
_P = POINTER

#: name -> (restype, argtypes), exactly as in the headers.
FUNCTIONS: Dict[str, Tuple[Any, List[Any]]] = {
    # error.h, leptrino.h
    "lep_strerror": (c_char_p, [c_int]),
    "lep_result_str": (c_char_p, [c_uint8]),
    "lep_version": (c_char_p, []),
    # frame.h
    "lep_bcc": (c_uint8, [_u8p, c_size_t]),
    "lep_frame_encode": (c_int, [_u8p, c_size_t, _u8p, c_size_t, _P(c_size_t)]),
    "lep_frame_decoder_sizeof": (c_size_t, []),
    "lep_frame_decoder_init": (None, [_P(lep_frame_decoder)]),
    "lep_frame_decoder_feed": (
        c_size_t,
        [_P(lep_frame_decoder), _u8p, c_size_t, _P(lep_frame_event)],
    ),
    "lep_frame_decoder_busy": (c_bool, [_P(lep_frame_decoder)]),
    "lep_frame_decoder_get_stats": (None, [_P(lep_frame_decoder), _P(lep_frame_stats)]),
    # message.h
    "lep_command_encode": (c_int, [_P(lep_command), _u8p, c_size_t, _P(c_size_t)]),
    "lep_command_decode": (c_int, [_u8p, c_size_t, _P(lep_command), _u8p]),
    "lep_response_decode": (c_int, [_u8p, c_size_t, _P(lep_response)]),
    "lep_command_frame": (c_int, [_P(lep_command), _u8p, c_size_t, _P(c_size_t)]),
    "lep_sample_to_si": (None, [_P(lep_sample), _P(lep_rated), _P(c_double)]),
    "lep_sample_saturated": (c_uint8, [_P(lep_sample), c_int16]),
    "lep_filter_label": (c_char_p, [c_uint8]),
    "lep_command_name": (c_char_p, [c_uint8]),
    # client.h
    "lep_client_sizeof": (c_size_t, []),
    "lep_client_set_timeout": (c_int, [_P(lep_client), c_int]),
    "lep_client_set_retries": (c_int, [_P(lep_client), c_uint]),
    "lep_client_get_stats": (None, [_P(lep_client), _P(lep_client_stats)]),
    "lep_client_last_result": (c_uint8, [_P(lep_client)]),
    "lep_client_streaming": (c_bool, [_P(lep_client)]),
    "lep_client_sync": (c_int, [_P(lep_client), c_int, _P(lep_product_info)]),
    "lep_client_product_info": (c_int, [_P(lep_client), _P(lep_product_info)]),
    "lep_client_rated": (c_int, [_P(lep_client), _P(lep_rated)]),
    "lep_client_filter_get": (c_int, [_P(lep_client), _u8p]),
    "lep_client_filter_set": (c_int, [_P(lep_client), c_uint8]),
    "lep_client_sample": (c_int, [_P(lep_client), _P(lep_sample)]),
    "lep_client_start": (c_int, [_P(lep_client)]),
    "lep_client_next_sample": (c_int, [_P(lep_client), _P(lep_sample), c_int]),
    "lep_client_stop": (c_int, [_P(lep_client)]),
    # serial.h
    "lep_serial_open": (c_int, [c_char_p, _P(_P(lep_serial)), _P(c_char), c_size_t]),
    "lep_serial_close": (None, [_P(lep_serial)]),
    "lep_serial_client_init": (c_int, [_P(lep_client), _P(lep_serial)]),
    "lep_serial_get_info": (None, [_P(lep_serial), _P(lep_serial_info)]),
    "lep_serial_path": (c_char_p, [_P(lep_serial)]),
    "lep_monotonic_seconds": (c_double, []),
    "lep_serial_list": (c_int, [_P(lep_port_info), c_size_t, _P(c_size_t)]),
    # sim.h
    "lep_sim_options_init": (None, [_P(lep_sim_options)]),
    "lep_sim_models": (_P(c_char_p), []),
    "lep_sim_model_rated": (c_int, [c_char_p, _P(lep_rated)]),
    "lep_sim_start": (c_int, [_P(lep_sim_options), _P(_P(lep_sim)), _P(c_char), c_size_t]),
    "lep_sim_port": (c_char_p, [_P(lep_sim)]),
    "lep_sim_power_cycle": (None, [_P(lep_sim)]),
    "lep_sim_hangup": (None, [_P(lep_sim)]),
    "lep_sim_stall": (None, [_P(lep_sim), c_int]),
    "lep_sim_get_stats": (None, [_P(lep_sim), _P(lep_sim_stats)]),
    "lep_sim_stop": (None, [_P(lep_sim)]),
    "lep_sim_pty_path": (c_char_p, [_P(lep_sim)]),
    "lep_sim_option_count": (c_size_t, []),
    "lep_sim_option_at": (_P(lep_sim_option_info), [c_size_t]),
    "lep_sim_option_find": (_P(lep_sim_option_info), [c_char_p]),
    "lep_sim_option_set": (c_int, [_P(lep_sim_options), c_char_p, c_char_p, _P(c_char), c_size_t]),
    "lep_sim_option_get": (c_int, [_P(lep_sim_options), c_char_p, _P(c_char), c_size_t]),
    "lep_sim_options_check": (c_int, [_P(lep_sim_options), _P(c_char), c_size_t]),
    "lep_sim_stream_sample": (c_int, [_P(lep_sim), c_uint64, c_uint8, _P(lep_sample)]),
    # record.h
    "lep_record_fill": (
        c_int,
        [_P(lep_client), _P(lep_rated), _P(lep_record_batch), c_double, c_int],
    ),
    # session.h
    "lep_session_options_init": (None, [_P(lep_session_options)]),
    "lep_rotation_from_rpy": (None, [c_double, c_double, c_double, _P(c_double)]),
    "lep_session_open": (
        c_int,
        [_P(lep_session_options), _P(_P(lep_session)), _P(c_char), c_size_t],
    ),
    "lep_session_close": (None, [_P(lep_session)]),
    "lep_session_start": (c_int, [_P(lep_session)]),
    "lep_session_stop": (c_int, [_P(lep_session)]),
    "lep_session_read": (c_int, [_P(lep_session), _P(lep_session_batch), c_int]),
    "lep_session_read_one": (c_int, [_P(lep_session), _P(lep_session_batch)]),
    "lep_session_serial_info": (c_int, [_P(lep_session), _P(lep_serial_info)]),
    "lep_session_next_event": (c_bool, [_P(lep_session), _P(lep_session_event)]),
    "lep_session_tare": (c_int, [_P(lep_session), c_uint, c_double]),
    "lep_session_untare": (c_int, [_P(lep_session)]),
    "lep_session_set_tare": (c_int, [_P(lep_session), _P(c_double)]),
    "lep_session_get_tare": (c_bool, [_P(lep_session), _P(c_double)]),
    "lep_session_taring": (c_bool, [_P(lep_session)]),
    "lep_session_set_lowpass": (c_int, [_P(lep_session), c_double]),
    "lep_session_set_payload": (c_int, [_P(lep_session), _P(lep_payload)]),
    "lep_session_set_gravity": (c_int, [_P(lep_session), _P(c_double)]),
    "lep_session_set_limits": (c_int, [_P(lep_session), _P(c_double)]),
    "lep_session_set_latency": (c_int, [_P(lep_session), c_int]),
    "lep_session_latency": (c_int, [_P(lep_session)]),
    "lep_session_set_rotation": (c_int, [_P(lep_session), _P(c_double), _P(c_double)]),
    "lep_session_get_health": (None, [_P(lep_session), _P(lep_session_health)]),
    "lep_session_get_metadata": (None, [_P(lep_session), _P(lep_session_metadata)]),
    "lep_session_metadata_json": (
        c_int,
        [_P(lep_session), _P(c_char), c_size_t, _P(c_size_t)],
    ),
    "lep_session_client": (_P(lep_client), [_P(lep_session)]),
    "lep_session_sim": (_P(lep_sim), [_P(lep_session)]),
    "lep_session_port": (c_char_p, [_P(lep_session)]),
    "lep_session_fd": (c_int, [_P(lep_session)]),
    "lep_session_streaming": (c_bool, [_P(lep_session)]),
    # output.h
    "lep_output_options_init": (None, [_P(lep_output_options)]),
    "lep_output_open": (
        c_int,
        [c_char_p, _P(lep_output_options), _P(_P(lep_output)), _P(c_char), c_size_t],
    ),
    "lep_output_open_fd": (
        c_int,
        [c_int, _P(lep_output_options), _P(_P(lep_output)), _P(c_char), c_size_t],
    ),
    "lep_output_add_session": (c_int, [_P(lep_output), _P(lep_session), c_char_p]),
    "lep_output_add_sensor": (c_int, [_P(lep_output), c_char_p, c_char_p, c_double]),
    "lep_output_write": (
        c_int,
        [_P(lep_output), c_int, _P(lep_session_batch), c_size_t, _P(lep_session_event),
         c_size_t],
    ),
    "lep_output_flush": (c_int, [_P(lep_output)]),
    "lep_output_errno": (c_int, [_P(lep_output)]),
    "lep_output_close": (c_int, [_P(lep_output)]),
    # payload.h
    "lep_payload_wrench": (c_int, [_P(lep_payload), _P(c_double), _P(c_double)]),
    "lep_payload_identify": (
        c_int,
        [_P(c_double), _P(c_double), c_size_t, _P(lep_payload_fit), _P(c_char), c_size_t],
    ),
    "lep_payload_pose_read": (
        c_int,
        [c_char_p, _P(c_double), _P(c_uint64), _P(c_char), c_size_t],
    ),
}

_SCALARS: Dict[str, Any] = {
    "uint8_t": c_uint8,
    "int16_t": c_int16,
    "uint16_t": c_uint16,
    "size_t": c_size_t,
    "double": c_double,
    "uint64_t": c_uint64,
}


def _ctypes_version(lib: Any) -> str:
    fn = lib.lep_version  # AttributeError: not a libleptrino
    fn.restype = c_char_p
    fn.argtypes = []
    return bytes(fn() or b"").decode("utf-8", "replace")


class CtypesBackend:
    """libleptrino through ctypes (nothing to compile)."""

    name = "ctypes"

    def __init__(self, path: Optional[str] = None) -> None:
        self.lib, self.path = _loader.load(ctypes.CDLL, _ctypes_version, path)
        missing = []
        for fname, (restype, argtypes) in FUNCTIONS.items():
            try:
                fn = getattr(self.lib, fname)
            except AttributeError:
                missing.append(fname)
                continue
            fn.restype = restype
            fn.argtypes = argtypes
        if missing:
            raise ImportError(
                f"leptrino: {self.path} lacks {', '.join(missing)}; "
                "it is not a matching libleptrino"
            )

    # -- allocation --------------------------------------------------------
    def new(self, ctype: str) -> Any:
        """A zeroed struct, passed where the C function wants a pointer to it."""
        return STRUCTS[ctype]()

    def new_array(self, ctype: str, n: int) -> Any:
        return (STRUCTS[ctype] * n)()

    def new_scalar(self, ctype: str) -> Any:
        return _SCALARS[ctype]()

    def value(self, scalar: Any) -> Any:
        return scalar.value

    def new_handle(self, ctype: str) -> Any:
        """Out-parameter for an opaque handle (lep_serial **, lep_sim **)."""
        return POINTER(STRUCTS[ctype])()

    def handle(self, out: Any) -> Any:
        return out if out else None

    def field_ptr(self, struct: Any, name: str) -> Any:
        """Pointer to a struct-typed field of struct (ctypes passes it by reference)."""
        return getattr(struct, name)

    def deref(self, ptr: Any) -> Any:
        """The struct a returned pointer points to."""
        return ptr.contents

    def new_opaque(self, ctype: str) -> Any:
        """A zeroed context of private layout, (pointer, memory to keep alive):
        ctype_sizeof() bytes, 8-aligned."""
        size = int(getattr(self.lib, ctype + "_sizeof")())
        words = (c_uint64 * ((size + 7) // 8))()
        ptr = ctypes.cast(words, POINTER(STRUCTS[ctype]))
        return (ptr, words)

    def new_client(self) -> Any:
        return self.new_opaque("lep_client")

    def new_text(self, size: int) -> Any:
        return ctypes.create_string_buffer(size)

    def text(self, x: Any) -> str:
        """str from a char array field, a returned const char *, or a text buffer."""
        if x is None:
            return ""
        if isinstance(x, ctypes.Array):
            x = x.value
        return bytes(x).decode("utf-8", "replace")

    def cstr(self, s: Optional[str], keep: List[Any]) -> Any:
        """A const char * argument or field value (kept alive by keep)."""
        if s is None:
            return None
        b = s.encode("utf-8")
        keep.append(b)
        return b

    def string_list(self, p: Any) -> List[str]:
        out: List[str] = []
        i = 0
        while p and p[i] is not None:
            out.append(p[i].decode("utf-8", "replace"))
            i += 1
        return out

    # -- memory ------------------------------------------------------------
    def bytes_in(self, data: bytes) -> Any:
        """A uint8_t buffer holding a copy of data."""
        return (c_uint8 * max(1, len(data))).from_buffer_copy(data or b"\0")

    def offset(self, buf: Any, off: int) -> Any:
        return ctypes.cast(ctypes.addressof(buf) + off, POINTER(c_uint8))

    def bytes_out(self, size: int) -> Any:
        return (c_uint8 * size)()

    def bytes_at(self, ptr: Any, n: int) -> bytes:
        if isinstance(ptr, ctypes.Array):
            return bytes(ptr)[:n]
        return ctypes.string_at(ptr, n)

    def array_ptr(self, arr: Any, ctype: str) -> Any:
        """Pointer to a C-contiguous numpy array's data."""
        return arr.ctypes.data_as(POINTER(_SCALARS[ctype]))

    def doubles(self, n: int) -> Any:
        return (c_double * n)()
