"""Recordings to files through the library's one writer (leptrino/output.h),
so a file written from Python has the bytes the `leptrino` tool writes."""

from __future__ import annotations

from typing import Any, List, Optional, Sequence

import numpy as np

from . import _args as A
from . import _constants as K
from ._backend import get_backend
from .errors import error_for
from .values import EVENT_NAMES, Recording

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
    o = be.new("lep_output_options")
    lib.lep_output_options_init(o)
    o.format = FORMATS[format]
    o.time = TIMES[time]
    o.columns = column_bits(columns)
    o.overwrite = bool(overwrite)
    keep: List[Any] = []
    out = be.new_handle("lep_output")
    err = be.new_text(512)
    rc = lib.lep_output_open(be.cstr(path, keep), o, out, err, 512)
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
        b, arrays = _batch(be, rec)
        keep.append(arrays)
        nev = len(rec.events)
        evs = be.new_array("lep_session_event", max(1, nev))
        for i, e in enumerate(rec.events):
            c = evs[i]
            c.type = _EVENT_CODES.get(e.type, 0)
            c.sample, c.t_mono, c.t_utc = e.sample, e.t, e.t_utc
            c.gap_from, c.gap_to, c.lost, c.error = e.gap_from, e.gap_to, e.lost, e.error
            c.axes, c.status = e.axes, e.status
            for j in range(K.LEP_AXES):
                c.tare[j] = e.tare[j]
                c.wrench[j] = e.wrench[j]
        rc = lib.lep_output_write(w, 0, b, 0, evs, nev)
        if rc < 0:
            raise error_for(be, rc, f"{path}: writing")
    except BaseException:
        lib.lep_output_close(w)
        raise
    rc = lib.lep_output_close(w)
    if rc < 0:
        raise error_for(be, rc, f"{path}: closing")


def _batch(be: Any, rec: Recording) -> Any:
    """A lep_session_batch over rec's arrays (C-contiguous copies where needed)."""
    n = len(rec)
    cols = {
        "t_mono": (rec.t, np.float64, "double"),
        "t_utc": (rec.t_utc if len(rec.t_utc) == n else np.zeros(n), np.float64, "double"),
        "raw": (rec.raw, np.int16, "int16_t"),
        "zeroed": (rec.zeroed if len(rec.zeroed) == n else rec.raw.astype(np.float64),
                   np.float64, "double"),
        "si": (rec.si, np.float64, "double"),
        "status": (rec.status, np.uint8, "uint8_t"),
        "flags": (rec.flags if len(rec.flags) == n else np.zeros(n, np.uint8), np.uint8,
                  "uint8_t"),
        "seq": (rec.seq, np.uint16, "uint16_t"),
    }
    b = be.new("lep_session_batch")
    arrays = []
    for k, (a, dt, ct) in cols.items():
        arr = np.ascontiguousarray(a, dtype=dt)
        if arr.size == 0:
            arr = np.zeros(max(1, arr.shape[0] if arr.ndim else 1) * (6 if arr.ndim == 2 else 1),
                           dtype=dt)
        arrays.append(arr)
        setattr(b, k, be.array_ptr(arr, ct))
    b.cap = n
    b.n = n
    return b, arrays
