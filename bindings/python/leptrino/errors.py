"""Exceptions. Every error raised by leptrino is a LeptrinoError.

    LeptrinoError                    .code: the library's error, an Error
                                     (Error.TIMEOUT is LEP_E_TIMEOUT); .error:
                                     the same as an int
    ├── TimeoutError                 also the built-in TimeoutError
    ├── DisconnectedError            also the built-in ConnectionError
    ├── SensorError                  the sensor's own result code: .result, .meaning
    ├── NakError                     the sensor kept answering DLE NAK
    ├── ProtocolError                malformed or unexpected message
    ├── StateError                   call not valid now (e.g. sample while streaming)
    ├── NoSyncError                  the line never went quiet at start-up
    └── PortError                    opening the port failed
        ├── PortNotFoundError        also FileNotFoundError
        ├── PortPermissionError      also PermissionError
        ├── NotATerminalError
        └── BusyError                the port is in use by another program
"""

from __future__ import annotations

import builtins
from typing import Any, Dict, Optional, Type, Union

from . import _constants as K
from ._constants import Error

__all__ = ["Error", "LeptrinoError", "error_for", "exit_code"]


class LeptrinoError(Exception):
    """Base of every leptrino error.

    .code is the library's error code as an Error (Error.OK when the error
    did not come from the library); .error is the same value as a plain int."""

    def __init__(self, message: str, error: Union[int, Error] = Error.OK) -> None:
        super().__init__(message)
        try:
            self.code: Union[Error, int] = Error(error)
        except ValueError:  # a code of another library version: kept as a number
            self.code = int(error)
        self.message = message

    @property
    def error(self) -> int:
        """The LEP_E_* code as an int (== .code)."""
        return int(self.code)

    def __str__(self) -> str:
        return self.message


class TimeoutError(LeptrinoError, builtins.TimeoutError):
    """No answer (or no sample) within the timeout."""


class DisconnectedError(LeptrinoError, builtins.ConnectionError):
    """The port went away (hang-up, USB cable pulled)."""


class SensorError(LeptrinoError):
    """The sensor answered with a non-zero result code.

    .code is Error.SENSOR; .result the sensor's result code (1 length
    error, 2 undefined command, 3 invalid setting value, 4 state error:
    LEP_RESULT_*), .meaning its description, .command the command code
    answered when known."""

    def __init__(self, result: int, meaning: str, command: Optional[int] = None) -> None:
        what = f" to command 0x{command:02X}" if command is not None else ""
        super().__init__(
            f"sensor answered{what} with result 0x{result:02X}: {meaning}", Error.SENSOR
        )
        self.result = result
        self.meaning = meaning
        self.command = command


class NakError(LeptrinoError):
    """The sensor kept answering DLE NAK past the retry limit."""


class ProtocolError(LeptrinoError):
    """A malformed, invalid or unexpected message (bad length, BCC, value...)."""


class StateError(LeptrinoError):
    """The call is not valid in the current state (for example while streaming)."""


class NoSyncError(LeptrinoError):
    """The line never went quiet during start-up recovery."""


class PortError(LeptrinoError):
    """Opening the port failed."""


class PortNotFoundError(PortError, builtins.FileNotFoundError):
    """No such port."""


class PortPermissionError(PortError, builtins.PermissionError):
    """No permission to open the port."""


class NotATerminalError(PortError):
    """The path is not a terminal device."""


class BusyError(PortError):
    """The port is already in use by another program."""


_BY_CODE: Dict[int, Type[LeptrinoError]] = {
    K.LEP_E_TIMEOUT: TimeoutError,
    K.LEP_E_STALLED: TimeoutError,
    K.LEP_E_LOST: TimeoutError,  # the stream lost: no data for the data timeout
    K.LEP_E_DISCONNECTED: DisconnectedError,
    K.LEP_E_NAK: NakError,
    K.LEP_E_TOO_LONG: ProtocolError,
    K.LEP_E_BCC: ProtocolError,
    K.LEP_E_ESCAPE: ProtocolError,
    K.LEP_E_LENGTH: ProtocolError,
    K.LEP_E_RESERVED: ProtocolError,
    K.LEP_E_UNEXPECTED: ProtocolError,
    K.LEP_E_VALUE: ProtocolError,
    K.LEP_E_STATE: StateError,
    K.LEP_E_NO_SYNC: NoSyncError,
    K.LEP_E_NOT_FOUND: PortNotFoundError,
    K.LEP_E_PERMISSION: PortPermissionError,
    K.LEP_E_NOT_TTY: NotATerminalError,
    K.LEP_E_BUSY: BusyError,
}


def error_for(be: Any, rc: int, detail: str = "", *, result: Optional[int] = None,
              command: Optional[int] = None, complete: bool = False) -> LeptrinoError:
    """The exception for a negative LEP_E_* return code rc.

    complete: detail is already the library's full message (from its err
    buffer), so the generic lep_strerror text is not appended to it."""
    if rc == K.LEP_E_SENSOR and result is not None:
        return SensorError(result, be.text(be.lib.lep_result_str(result)), command)
    text = be.text(be.lib.lep_strerror(rc))
    if complete and detail:
        msg = detail
    else:
        msg = f"{detail}: {text}" if detail and text not in detail else (detail or text)
    return _BY_CODE.get(rc, LeptrinoError)(msg, rc)


def exit_code(be: Any, exc: BaseException) -> int:
    """The exit status the `leptrino` tool gives for exc: the library's one
    table (lep_exit_code, leptrino/process.h) applied to a LeptrinoError's
    code; LEP_EXIT_FAIL for an error without a library code, or another
    exception."""
    if not isinstance(exc, LeptrinoError) or int(exc.code) == K.LEP_OK:
        return int(K.LEP_EXIT_FAIL)
    return int(be.lib.lep_exit_code(int(exc.code)))
