"""Recordings to files through the library's one writer (leptrino/output.h),
so a file written from Python has the bytes the `leptrino` tool writes."""

from __future__ import annotations

from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

from . import _args as A
from . import _constants as K
from ._backend import get_backend
from .errors import error_for
from .values import EVENT_NAMES, Recording, SessionEvent

#: column name -> LEP_COL_* bit
COLUMNS = {
    "raw": K.LEP_COL_RAW,
    "zeroed": K.LEP_COL_ZEROED,
    "si": K.LEP_COL_SI,
    "status": K.LEP_COL_STATUS,
    "flags": K.LEP_COL_FLAGS,
    "seq": K.LEP_COL_SEQ,
}
TIMES = {"rel": K.LEP_TIME_REL, "mono": K.LEP_TIME_MONO, "utc": K.LEP_TIME_UTC}
FORMATS = {"csv": K.LEP_OUTPUT_CSV, "jsonl": K.LEP_OUTPUT_JSONL}
_EVENT_CODES = {name: code for code, name in EVENT_NAMES.items()}


def column_bits(columns: Sequence[str]) -> int:
    if isinstance(columns, (str, bytes)):
        raise TypeError(f"columns: {columns!r} is not a list of names "
                        f"({', '.join(COLUMNS)}); give [{columns!r}]")
    bits = 0
    for c in columns:
        if c not in COLUMNS:
            raise ValueError(f"unknown column {c!r}; columns are {', '.join(COLUMNS)}")
        bits |= COLUMNS[c]
    if not bits:
        raise ValueError("give at least one column")
    return bits


def write_recording(rec: Recording, path: str, *, format: str = "csv",
                    columns: Sequence[str] = ("si", "status"), time: str = "rel",
                    overwrite: bool = False, name: Optional[str] = None,
                    backend: Optional[str] = None) -> None:
    """Write rec to path (CSV or JSON lines) with lep_output: the metadata
    line, the header, the rows, the events where they belong. FileExistsError
    for an existing file unless overwrite; the library's error otherwise."""
    overwrite = A.flag("save", "overwrite", overwrite)
    if format not in FORMATS:
        raise ValueError(f"format must be one of {', '.join(FORMATS)}, not {format!r}")
    if time not in TIMES:
        raise ValueError(f"time must be one of {', '.join(TIMES)}, not {time!r}")
    be = get_backend(backend)
    lib = be.lib
    keep: List[Any] = []
    out = be.new_handle("lep_output")
    err = be.new_text(512)
    rc = lib.lep_output_open(be.cstr(path, keep), FORMATS[format], TIMES[time],
                             column_bits(columns), 0.0, int(overwrite), out, err, 512)
    if rc < 0:
        msg = be.text(err)
        if rc == K.LEP_E_ARG and "exist" in msg:
            raise FileExistsError(f"{path}: already exists; not overwritten (choose another "
                                  "name, or overwrite=True)")
        raise error_for(be, rc, msg or path, complete=bool(msg))
    w = be.handle(out)
    try:
        rc = lib.lep_output_add_sensor(w, be.cstr(name or None, keep),
                                       be.cstr(rec.metadata_json or "{}", keep),
                                       float(rec.start_mono))
        if rc < 0:
            raise error_for(be, rc, f"{path}: adding the sensor")
        n, ptrs, arrays = _columns(be, rec)
        keep.append(arrays)
        evs = event_rows(rec.events)
        keep.append(evs)
        rc = lib.lep_output_write(w, 0, n, *ptrs, be.array_ptr(evs, "double"), len(rec.events),
                                  K.LEP_EVF_COUNT)
        if rc < 0:
            raise error_for(be, rc, f"{path}: writing")
    except BaseException:
        lib.lep_output_close(w)
        raise
    rc = lib.lep_output_close(w)
    if rc < 0:
        raise error_for(be, rc, f"{path}: closing")


def event_rows(events: Sequence[SessionEvent]) -> np.ndarray:
    """Events as the rows lep_session_next_event fills (LEP_EVF_COUNT doubles
    each, fields at the LEP_EVF_* indices): what lep_output_write takes."""
    rows = np.zeros((max(1, len(events)), K.LEP_EVF_COUNT), np.float64)
    for i, e in enumerate(events):
        r = rows[i]
        r[K.LEP_EVF_TYPE] = _EVENT_CODES.get(e.type, 0)
        r[K.LEP_EVF_SAMPLE] = e.sample
        r[K.LEP_EVF_T_MONO] = e.t
        r[K.LEP_EVF_T_UTC] = e.t_utc
        r[K.LEP_EVF_GAP_FROM] = e.gap_from
        r[K.LEP_EVF_GAP_TO] = e.gap_to
        r[K.LEP_EVF_LOST] = e.lost
        r[K.LEP_EVF_ERROR] = e.error
        r[K.LEP_EVF_AXES] = e.axes
        r[K.LEP_EVF_STATUS] = e.status
        r[K.LEP_EVF_TARE:K.LEP_EVF_TARE + K.LEP_AXES] = e.tare
        r[K.LEP_EVF_WRENCH:K.LEP_EVF_WRENCH + K.LEP_AXES] = e.wrench
    return rows


def _columns(be: Any, rec: Recording) -> Tuple[int, List[Any], List[np.ndarray]]:
    """(n, the eight column pointers in lep_output_write's order, the arrays to
    keep alive): C-contiguous copies of rec's arrays where needed."""
    n = len(rec)
    cols = [
        (rec.t, np.float64, "double"),
        (rec.t_utc if len(rec.t_utc) == n else np.zeros(n), np.float64, "double"),
        (rec.si, np.float64, "double"),
        (rec.raw, np.int16, "int16_t"),
        (rec.zeroed if len(rec.zeroed) == n else rec.raw.astype(np.float64), np.float64,
         "double"),
        (rec.status, np.uint8, "uint8_t"),
        (rec.flags if len(rec.flags) == n else np.zeros(n, np.uint8), np.uint8, "uint8_t"),
        (rec.seq, np.uint16, "uint16_t"),
    ]
    arrays: List[np.ndarray] = []
    ptrs: List[Any] = []
    for a, dt, ct in cols:
        arr = np.ascontiguousarray(a, dtype=dt)
        if arr.size == 0:
            arr = np.zeros(max(1, arr.shape[0] if arr.ndim else 1) * (6 if arr.ndim == 2 else 1),
                           dtype=dt)
        arrays.append(arr)
        ptrs.append(be.array_ptr(arr, ct))
    return n, ptrs, arrays
