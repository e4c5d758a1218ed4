"""cffi backend (ABI mode: ffi.cdef + ffi.dlopen, nothing to compile).

The declarations are leptrino._cdef.CDEF, generated from include/leptrino/*.h
by tools/gen_python_decls.py.
"""

from __future__ import annotations

from typing import Any, List, Optional

from . import _loader
from ._cdef import CDEF, FUNCTIONS

try:
    import cffi
except ImportError as exc:  # pragma: no cover - depends on the environment
    raise ImportError(
        "leptrino: the cffi backend needs the cffi package (pip install cffi), "
        "or use LEPTRINO_BACKEND=ctypes"
    ) from exc


class CffiBackend:
    """libleptrino through cffi in ABI mode."""

    name = "cffi"

    def __init__(self, path: Optional[str] = None) -> None:
        self.ffi = cffi.FFI()
        self.ffi.cdef(CDEF)
        #: a NULL pointer argument
        self.NULL = self.ffi.NULL
        self.lib, self.path = _loader.load(self.ffi.dlopen, self._version_of, path)
        # Resolve every declared function now, so a mismatched library fails
        # at load time rather than at first use.
        missing = []
        for fname in self.function_names():
            try:
                getattr(self.lib, fname)
            except AttributeError:
                missing.append(fname)
        if missing:
            raise ImportError(
                f"leptrino: {self.path} lacks {', '.join(missing)}; "
                "it is not a matching libleptrino"
            )

    def _version_of(self, lib: Any) -> str:
        p = lib.lep_version()  # AttributeError: not a libleptrino
        return "" if p == self.ffi.NULL else bytes(self.ffi.string(p)).decode("utf-8", "replace")

    def function_names(self) -> List[str]:
        """The functions CDEF declares (whether or not the library has them)."""
        return sorted(FUNCTIONS)

    # -- allocation --------------------------------------------------------
    def new(self, ctype: str) -> Any:
        return self.ffi.new(ctype + " *")

    def new_array(self, ctype: str, n: int) -> Any:
        return self.ffi.new(ctype + "[]", n)

    def new_scalar(self, ctype: str) -> Any:
        return self.ffi.new(ctype + " *")

    def value(self, scalar: Any) -> Any:
        return scalar[0]

    def new_handle(self, ctype: str) -> Any:
        return self.ffi.new(ctype + " **")

    def handle(self, out: Any) -> Any:
        h = out[0]
        return None if h == self.ffi.NULL else h

    def field_ptr(self, struct: Any, name: str) -> Any:
        """Pointer to a struct-typed field of the struct struct points to."""
        return self.ffi.addressof(struct, name)

    def deref(self, ptr: Any) -> Any:
        """The struct a returned pointer points to."""
        return ptr[0]

    def new_opaque(self, ctype: str) -> Any:
        """A zeroed context of private layout, (pointer, memory to keep alive):
        ctype_sizeof() bytes, 8-aligned."""
        size = int(getattr(self.lib, ctype + "_sizeof")())
        words = self.ffi.new("uint64_t[]", (size + 7) // 8)
        return (self.ffi.cast(ctype + " *", words), words)

    def new_client(self) -> Any:
        return self.new_opaque("lep_client")

    def new_text(self, size: int) -> Any:
        return self.ffi.new("char[]", size)

    def text(self, x: Any) -> str:
        if x is None or x == self.ffi.NULL:
            return ""
        return bytes(self.ffi.string(x)).decode("utf-8", "replace")

    def cstr(self, s: Optional[str], keep: List[Any]) -> Any:
        if s is None:
            return self.ffi.NULL
        p = self.ffi.new("char[]", s.encode("utf-8"))
        keep.append(p)
        return p

    def string_list(self, p: Any) -> List[str]:
        out: List[str] = []
        i = 0
        while p != self.ffi.NULL and p[i] != self.ffi.NULL:
            out.append(self.text(p[i]))
            i += 1
        return out

    # -- memory ------------------------------------------------------------
    def bytes_in(self, data: bytes) -> Any:
        buf = self.ffi.new("uint8_t[]", max(1, len(data)))
        self.ffi.memmove(buf, bytes(data), len(data))
        return buf

    def offset(self, buf: Any, off: int) -> Any:
        return buf + off

    def bytes_out(self, size: int) -> Any:
        return self.ffi.new("uint8_t[]", size)

    def bytes_at(self, ptr: Any, n: int) -> bytes:
        return bytes(self.ffi.buffer(ptr, n))

    def array_ptr(self, arr: Any, ctype: str) -> Any:
        return self.ffi.cast(ctype + " *", arr.ctypes.data)

    def doubles(self, n: int) -> Any:
        return self.ffi.new("double[]", n)
