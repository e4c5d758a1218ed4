"""leptrino: Leptrino 6-axis force/torque sensors from Python.

A thin layer over libleptrino (the same shared library C programs link),
through ctypes (default) or cffi in ABI mode; choose with the environment
variable LEPTRINO_BACKEND=ctypes|cffi or the backend= argument.

    import leptrino
    with leptrino.Sensor(sim=True) as sensor:  # or Sensor("/dev/ttyACM0")
        print(sensor.product_info.model, sensor.rated)
        sensor.tare(100)                       # in C, in raw counts
        rec = sensor.record(seconds=1.0)       # numpy arrays, filled by C
        rec.save("forces.csv")                 # the leptrino tool's CSV

Importing loads the library of the default backend and raises ImportError,
listing what was tried, when it cannot be found.
"""

from __future__ import annotations

from ._backend import BACKENDS, get_backend
from ._loader import package_version as _package_version
from .codec import (
    Decoder,
    Event,
    Message,
    decode,
    decode_message,
    encode_command,
    encode_frame,
    sample_to_si,
    saturation_mask,
)
from .errors import (
    BusyError,
    DisconnectedError,
    Error,
    LeptrinoError,
    NakError,
    NoSyncError,
    NotATerminalError,
    PortError,
    PortNotFoundError,
    PortPermissionError,
    ProtocolError,
    SensorError,
    StateError,
    TimeoutError,
)
from .payload import Payload, identify_payload, read_pose
from .recording_file import RecordingFile, read_recording
from .sensor import PowerCycleWarning, SampleBuffer, Sensor, Stream, list_ports
from .simulator import SimOption, Simulator
from .values import (
    ClientStats,
    FrameStats,
    Health,
    PortInfo,
    ProductInfo,
    Rated,
    Recording,
    Sample,
    SessionEvent,
    SimStats,
)

__all__ = [
    "read_recording",
    "RecordingFile",
    "BACKENDS",
    "BusyError",
    "ClientStats",
    "Health",
    "Decoder",
    "DisconnectedError",
    "Error",
    "Event",
    "FrameStats",
    "Message",
    "LeptrinoError",
    "NakError",
    "NoSyncError",
    "NotATerminalError",
    "Payload",
    "PortError",
    "PortInfo",
    "PortNotFoundError",
    "PortPermissionError",
    "PowerCycleWarning",
    "ProductInfo",
    "ProtocolError",
    "Rated",
    "Recording",
    "Sample",
    "SampleBuffer",
    "Sensor",
    "SessionEvent",
    "SimOption",
    "SensorError",
    "SimStats",
    "Simulator",
    "StateError",
    "Stream",
    "TimeoutError",
    "decode",
    "decode_message",
    "encode_command",
    "encode_frame",
    "get_backend",
    "identify_payload",
    "library_version",
    "list_ports",
    "read_pose",
    "sample_to_si",
    "saturation_mask",
]


def library_version(backend: str | None = None) -> str:
    """Version of the libleptrino actually loaded, e.g. "0.1.0"."""
    be = get_backend(backend)
    return str(be.text(be.lib.lep_version()))


# Load the default backend now: a missing library is an ImportError at import.
get_backend()

#: This package's version, from project(VERSION) in the top CMakeLists.txt;
#: the loaded library is checked to be the same.
__version__: str = _package_version()
