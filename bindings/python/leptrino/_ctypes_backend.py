"""ctypes backend: the library's functions with the argtypes/restype of
leptrino._ctypes_decls (generated from include/leptrino/*.h), and the helpers
the high-level code uses (allocation, strings, pointers).
"""

from __future__ import annotations

import ctypes
from ctypes import (
    POINTER,
    c_char_p,
    c_double,
    c_int16,
    c_int64,
    c_size_t,
    c_uint8,
    c_uint16,
    c_uint64,
)
from typing import Any, Dict, List, Optional

from . import _loader
from ._ctypes_decls import FUNCTIONS, OPAQUE, STRUCTS

__all__ = ["CtypesBackend", "FUNCTIONS", "OPAQUE", "STRUCTS"]

_SCALARS: Dict[str, Any] = {
    "uint8_t": c_uint8,
    "int16_t": c_int16,
    "uint16_t": c_uint16,
    "int64_t": c_int64,
    "size_t": c_size_t,
    "double": c_double,
    "uint64_t": c_uint64,
    "int": ctypes.c_int,
}


def _ctypes_version(lib: Any) -> str:
    fn = lib.lep_version  # AttributeError: not a libleptrino
    fn.restype = c_char_p
    fn.argtypes = []
    return bytes(fn() or b"").decode("utf-8", "replace")


class CtypesBackend:
    """libleptrino through ctypes (nothing to compile)."""

    name = "ctypes"
    #: a NULL pointer argument
    NULL: Any = None

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
        """n zeroed structs, or n zeroed scalars ("double", "uint64_t", ...)."""
        return ((STRUCTS[ctype] if ctype in STRUCTS else _SCALARS[ctype]) * n)()

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
