"""Options by name (leptrino/options.h): the one table, an options handle,
and setting a Python value on a handle or on an open session.

Python mirrors no layout here: an option is a name, its type comes from the
library's table (lep_option_type), and the value goes through the setter of
that type (lep_options_set_int / _set_double / _set_doubles, or text). What
the library refuses is a ValueError with the library's own message, which
names the option and what it allows.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass
from typing import Any, Iterable, List, Optional

from . import _constants as K
from .errors import error_for

#: lep_option_type -> the type's name in Python
TYPES = {
    K.LEP_OPT_FLAG: "flag",
    K.LEP_OPT_INT: "int",
    K.LEP_OPT_DOUBLE: "float",
    K.LEP_OPT_STRING: "str",
    K.LEP_OPT_CHOICE: "choice",
    K.LEP_OPT_NUMBERS: "numbers",
}

_ERR = 512


@dataclass(frozen=True)
class OptionRow:
    """One row of the library's option table (lep_option_*)."""

    index: int
    name: str  # "data-timeout", "sim-rate"
    type: int  # LEP_OPT_*
    scope: int  # LEP_SCOPE_*
    arg: str  # "" for flags
    help: str
    default: str  # "" when off or empty
    min: float
    max: float
    min_exclusive: bool
    numbers: int


def table(be: Any) -> List[OptionRow]:
    """Every row of the table, in its order."""
    lib = be.lib
    return [OptionRow(
        index=i, name=be.text(lib.lep_option_name(i)), type=int(lib.lep_option_type(i)),
        scope=int(lib.lep_option_scope(i)), arg=be.text(lib.lep_option_arg(i)),
        help=be.text(lib.lep_option_help(i)), default=be.text(lib.lep_option_default(i)),
        min=float(lib.lep_option_min(i)), max=float(lib.lep_option_max(i)),
        min_exclusive=bool(lib.lep_option_min_exclusive(i)),
        numbers=int(lib.lep_option_numbers(i)))
        for i in range(int(lib.lep_option_count()))]


def option_type(be: Any, name: str) -> Optional[int]:
    """LEP_OPT_* of the option called name (any accepted spelling), None when unknown."""
    i = int(be.lib.lep_option_index(name.encode("utf-8")))
    return None if i < 0 else int(be.lib.lep_option_type(i))


def _numbers(value: Any) -> Optional[List[float]]:
    """value as a list of floats when it is a sequence of numbers (not text), else None."""
    if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
        return None
    out: List[float] = []
    for v in value:
        if isinstance(v, bool) or not isinstance(v, numbers.Real):
            return None
        out.append(float(v))
    return out


def _text(value: Any) -> str:
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, float):
        return repr(value)
    if not isinstance(value, str) and isinstance(value, Iterable):
        return ",".join(_text(v) for v in value)
    return str(value)


def set_value(be: Any, target: Any, name: str, value: Any, *, session: bool = False,
              where: str = "") -> None:
    """Set option name to a Python value on an options handle (or, session=True,
    on an open session: lep_session_set*). The option's type picks the setter:
    True/False and whole numbers through _set_int (a bool only for a flag:
    elsewhere it goes as the text "True", which the library refuses), other
    numbers through _set_double, sequences of numbers through _set_doubles,
    anything else as text. ValueError with the library's message when it
    refuses (unknown name, a value out of range or of the wrong type); the
    library's error otherwise (LEP_E_STATE: cannot change on an open session)."""
    lib = be.lib
    fn = "lep_session_set" if session else "lep_options_set"
    key = name.encode("utf-8")
    typ = option_type(be, name)
    err = be.new_text(_ERR)
    nums = _numbers(value) if typ == K.LEP_OPT_NUMBERS else None
    if isinstance(value, bool) or (hasattr(value, "dtype") and value.dtype == bool):
        if typ == K.LEP_OPT_FLAG:
            rc = getattr(lib, fn + "_int")(target, key, int(bool(value)), err, _ERR)
        else:
            rc = getattr(lib, fn)(target, key, str(bool(value)).encode(), err, _ERR)
    elif isinstance(value, numbers.Integral) and typ in (K.LEP_OPT_FLAG, K.LEP_OPT_INT,
                                                         K.LEP_OPT_DOUBLE):
        rc = getattr(lib, fn + "_int")(target, key, int(value), err, _ERR)
    elif isinstance(value, numbers.Real) and typ in (K.LEP_OPT_INT, K.LEP_OPT_DOUBLE):
        rc = getattr(lib, fn + "_double")(target, key, float(value), err, _ERR)
    elif nums is not None:
        arr = be.new_array("double", max(1, len(nums)))
        for i, v in enumerate(nums):
            arr[i] = v
        rc = getattr(lib, fn + "_doubles")(target, key, arr, len(nums), err, _ERR)
    else:
        rc = getattr(lib, fn)(target, key, _text(value).encode("utf-8"), err, _ERR)
    if rc < 0:
        msg = be.text(err)
        if rc in (K.LEP_E_ARG, K.LEP_E_VALUE):
            raise ValueError(f"{where}{msg}" if msg else f"{where}{name}={value!r}: refused")
        raise error_for(be, rc, f"{where}{msg or name}", complete=bool(msg))


class Options:
    """An options handle (lep_options_new), freed by close() or when collected."""

    def __init__(self, be: Any) -> None:
        self._be = be
        self.handle: Any = be.lib.lep_options_new()
        if not self.handle:
            raise MemoryError("lep_options_new: out of memory")

    def set(self, name: str, value: Any, where: str = "") -> None:
        set_value(self._be, self.handle, name, value, where=where)

    def close(self) -> None:
        h, self.handle = self.handle, None
        if h:
            self._be.lib.lep_options_free(h)

    def __enter__(self) -> Options:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:
            pass


def text_result(be: Any, call: Any) -> str:
    """A text result of the library (the text rule of options.h): call(buf, cap,
    len_ptr) is asked for the size first, then given the room. Returns the text;
    raises the library's error."""
    n = be.new_scalar("size_t")
    rc = call(be.NULL, 0, n)
    if rc < 0 and rc != K.LEP_E_BUFFER:
        raise error_for(be, rc, "reading a text from the library")
    for _ in range(4):  # the text may grow between the two calls (metadata): ask again
        cap = int(be.value(n)) + 1
        buf = be.new_text(cap)
        rc = call(buf, cap, n)
        if rc == K.LEP_E_BUFFER:
            continue
        if rc < 0:
            raise error_for(be, rc, "reading a text from the library")
        return str(be.bytes_at(buf, int(be.value(n))).decode("utf-8", "replace"))
    raise error_for(be, K.LEP_E_BUFFER, "reading a text from the library")
