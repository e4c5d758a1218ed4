"""Read a recording back: leptrino.read_recording(path).

Reads what the one writer (src/host/output/output.c, leptrino/output.h; format in
docs/session.md "Recordings") writes for `leptrino stream -o` and
Recording.save, and the .npz of Recording.save:

- CSV: `# leptrino-metadata: {json}` lines (one per sensor), the header line,
  then rows; events are `# WORD key=value ...` comment lines before the row
  they precede (`# overload begin ...` / `# overload end ...`; `sensor=NAME`
  after the word with a sensor column).
- JSON lines: `{"metadata": {...}}` objects (one per sensor), then one object
  per row (the CSV header's keys) and `{"event": "...", ...}` objects.

A last line cut by a crash (no newline at its end) is left out with a
RuntimeWarning; the rows before it are read.
"""

from __future__ import annotations

import json
import os
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Union

import numpy as np

METADATA_PREFIX = "# leptrino-metadata: "
#: numpy dtype of each column the writer knows (the rest are float64)
_DTYPES = {"status": np.uint8, "flags": np.uint8, "seq": np.uint16, "sensor": object}
_COUNTS = ("fx_counts", "fy_counts", "fz_counts", "mx_counts", "my_counts", "mz_counts")
SI = ("fx_N", "fy_N", "fz_N", "mx_Nm", "my_Nm", "mz_Nm")
ZEROED = tuple(c.replace("_counts", "_zeroed_counts") for c in _COUNTS)
TIMES = ("t_s", "t_mono_s", "t_utc_s")


@dataclass
class RecordingFile:
    """A recording read back from a file.

    columns: one numpy array per column, named as in the file (t_s or
    t_mono_s or t_utc_s, fx_counts..., fx_N..., status, flags, seq, sensor).
    metadata: the first (or only) sensor's metadata object; sensors: every
    sensor's, by name ("" for an unnamed one). events: dicts with "event"
    (gap, disconnected, tare, overload_begin, overload_end), "row" (the index
    of the row it comes before; len(rows) when after the last) and the
    file's fields (from, to, lost, reason, at, fx..mz or offset_counts, axes,
    status, sensor). time: the name of the time column."""

    path: str
    format: str  # csv, jsonl or npz
    columns: Dict[str, np.ndarray]
    metadata: Dict[str, Any]
    sensors: Dict[str, Dict[str, Any]] = field(default_factory=dict)
    events: List[Dict[str, Any]] = field(default_factory=list)
    time: str = "t_s"

    def __len__(self) -> int:
        return int(len(self.columns[self.time])) if self.time in self.columns else 0

    def to_dataframe(self) -> Any:
        """The rows as a pandas DataFrame (pandas is optional: ImportError
        saying so when it is not installed); .attrs holds metadata, events."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("read_recording(..., pandas=True) / to_dataframe() need pandas "
                              "(pip install pandas); the arrays are in .columns") from None
        df = pd.DataFrame({k: v for k, v in self.columns.items()})
        df.attrs["metadata"] = self.metadata
        df.attrs["events"] = self.events
        return df


def _value(v: str) -> Any:
    try:
        return int(v)
    except ValueError:
        pass
    try:
        return float(v)
    except ValueError:
        return v


def _csv_event(text: str, row: int) -> Optional[Dict[str, Any]]:
    words = text[1:].split()
    if not words:
        return None
    name = words[0]
    rest = words[1:]
    if name == "overload" and rest and rest[0] in ("begin", "end"):
        name = f"overload_{rest[0]}"
        rest = rest[1:]
    ev: Dict[str, Any] = {"event": name, "row": row}
    for w in rest:
        if "=" not in w:
            return None  # not an event line: a comment of someone else's
        k, v = w.split("=", 1)
        ev[k] = v if k in ("sensor", "reason") else _value(v)
    return ev


def _split_cut_line(text: str, path: str) -> str:
    if text and not text.endswith("\n"):
        cut = text.rfind("\n") + 1
        warnings.warn(f"{path}: the last line is cut (a crash or a kill while writing?): "
                      f"read up to the last whole row", RuntimeWarning, stacklevel=3)
        return text[:cut]
    return text


def _columns(names: List[str], rows: List[List[Any]]) -> Dict[str, np.ndarray]:
    cols: Dict[str, np.ndarray] = {}
    for i, name in enumerate(names):
        vals = [r[i] for r in rows]
        if name == "sensor":
            cols[name] = np.array(vals, dtype=object)
        elif name in _COUNTS:
            cols[name] = np.array(vals, dtype=np.int16)
        else:
            cols[name] = np.array(vals, dtype=_DTYPES.get(name, np.float64))
    return cols


def _read_csv(path: str, text: str) -> RecordingFile:
    sensors: Dict[str, Dict[str, Any]] = {}
    first: Optional[Dict[str, Any]] = None
    header: Optional[List[str]] = None
    rows: List[List[Any]] = []
    events: List[Dict[str, Any]] = []
    for n, line in enumerate(text.splitlines(), 1):
        if not line:
            continue
        if line.startswith(METADATA_PREFIX):
            m = json.loads(line[len(METADATA_PREFIX):])
            sensors[str(m.get("sensor", ""))] = m
            first = first or m
        elif line.startswith("#"):
            ev = _csv_event(line, len(rows))
            if ev is not None:
                events.append(ev)
        elif header is None:
            header = line.split(",")
            if header[0] not in TIMES:
                raise ValueError(f"{path}:{n}: not a leptrino recording (the header starts "
                                 f"with {header[0]!r}, not t_s, t_mono_s or t_utc_s)")
        else:
            f = line.split(",")
            if len(f) != len(header):
                raise ValueError(f"{path}:{n}: {len(f)} fields where the header has "
                                 f"{len(header)}")
            rows.append([v if h == "sensor" else float(v) for h, v in zip(header, f)])
    if header is None:
        raise ValueError(f"{path}: not a leptrino recording (no header line)")
    return RecordingFile(path, "csv", _columns(header, rows), first or {}, sensors, events,
                         header[0])


def _read_jsonl(path: str, text: str) -> RecordingFile:
    sensors: Dict[str, Dict[str, Any]] = {}
    first: Optional[Dict[str, Any]] = None
    names: Optional[List[str]] = None
    rows: List[List[Any]] = []
    events: List[Dict[str, Any]] = []
    for n, line in enumerate(text.splitlines(), 1):
        if not line:
            continue
        try:
            obj = json.loads(line)
        except json.JSONDecodeError as e:
            raise ValueError(f"{path}:{n}: not JSON ({e.msg})") from None
        if "metadata" in obj and len(obj) == 1:
            m = obj["metadata"]
            sensors[str(m.get("sensor", ""))] = m
            first = first or m
        elif "event" in obj:
            events.append({"event": obj["event"], "row": len(rows),
                           **{k: v for k, v in obj.items() if k != "event"}})
        else:
            if names is None:
                names = list(obj)
                if names[0] not in TIMES:
                    raise ValueError(f"{path}:{n}: not a leptrino recording (a row without "
                                     "t_s, t_mono_s or t_utc_s first)")
            rows.append([obj[k] for k in names])
    if names is None:
        names = ["t_s"]
    return RecordingFile(path, "jsonl", _columns(names, rows), first or {}, sensors, events,
                         names[0])


def _read_npz(path: str) -> RecordingFile:
    from .values import Recording

    rec = Recording.load(path)
    cols: Dict[str, np.ndarray] = {"t_s": rec.t - rec.start_mono, "t_mono_s": rec.t,
                                   "t_utc_s": rec.t_utc}
    for i in range(6):
        cols[_COUNTS[i]] = rec.raw[:, i]
    for i in range(6):
        cols[ZEROED[i]] = rec.zeroed[:, i]
    for i in range(6):
        cols[SI[i]] = rec.si[:, i]
    cols.update(status=rec.status, flags=rec.flags, seq=rec.seq)
    events = [{"event": e.type, "row": e.sample, **e.as_dict()} for e in rec.events]
    return RecordingFile(path, "npz", cols, rec.metadata, {"": rec.metadata}, events, "t_s")


def read_recording(path: Union[str, "os.PathLike[str]"], *, pandas: bool = False) -> Any:
    """Read a recording of `leptrino stream` or Recording.save (.csv, .jsonl,
    .npz; the format is told by the content, not the name).

    Returns a RecordingFile (.columns: numpy arrays, .metadata, .events), or
    with pandas=True a pandas DataFrame whose .attrs hold "metadata" and
    "events". ValueError for a file that is not a recording; a last line cut
    by a crash is left out with a RuntimeWarning."""
    p = os.fspath(path)
    with open(p, "rb") as f:
        head = f.read(6)
    if head.startswith(b"PK"):
        out = _read_npz(p)
    else:
        with open(p, encoding="utf-8") as f:
            text = _split_cut_line(f.read(), p)
        stripped = text.lstrip()
        if stripped.startswith("{"):
            out = _read_jsonl(p, text)
        elif stripped.startswith("#") or stripped.startswith("t_"):
            out = _read_csv(p, text)
        else:
            raise ValueError(f"{p}: not a leptrino recording (CSV with '# leptrino-metadata' "
                             "lines, JSON lines, or .npz)")
    return out.to_dataframe() if pandas else out


def recording_from_file(path: str) -> Any:
    """A Recording (values.Recording) from a CSV or JSON-lines file: the
    columns the file has; the others zeros (raw, zeroed, status, flags, seq)
    or NaN (SI, times). t is the file's time column (t_s: seconds from the
    stream's start, start_mono 0)."""
    from .values import Recording, SessionEvent

    rf = read_recording(path)
    n = len(rf)
    c = rf.columns

    def six(names: tuple, dtype: Any, fill: Any) -> np.ndarray:
        if all(k in c for k in names):
            return np.stack([np.asarray(c[k], dtype=dtype) for k in names], axis=1) \
                if n else np.empty((0, 6), dtype)
        return np.full((n, 6), fill, dtype=dtype)

    def one(name: str, dtype: Any) -> np.ndarray:
        return np.asarray(c[name], dtype=dtype) if name in c else np.zeros(n, dtype)

    t = np.asarray(c[rf.time], dtype=np.float64)
    start_utc = float(rf.metadata.get("start_utc", 0.0) or 0.0)
    if rf.time == "t_utc_s":
        t_utc = t
        t = t - start_utc
    elif rf.time == "t_s" and start_utc:
        t_utc = t + start_utc
    else:
        t_utc = np.full(n, np.nan)
    events = []
    for e in rf.events:
        at = float(e.get("at", e.get("from", 0.0)))
        tare = e.get("offset_counts") or [e.get(k, 0.0) for k in ("fx", "fy", "fz", "mx", "my",
                                                                  "mz")]
        events.append(SessionEvent(
            type=str(e["event"]), sample=int(e["row"]), t=at, t_utc=at + start_utc,
            gap_from=float(e.get("from", 0.0)), gap_to=float(e.get("to", 0.0)),
            lost=int(e.get("lost", 0)), error=0, axes=int(e.get("axes", 0)),
            status=int(e.get("status", 0)), tare=tuple(float(x) for x in tare)))  # type: ignore
    return Recording(t=t, si=six(SI, np.float64, np.nan), raw=six(_COUNTS, np.int16, 0),
                     status=one("status", np.uint8), seq=one("seq", np.uint16), t_utc=t_utc,
                     zeroed=six(ZEROED, np.float64, np.nan), flags=one("flags", np.uint8),
                     events=events, metadata_json=json.dumps(rf.metadata), start_mono=0.0)
