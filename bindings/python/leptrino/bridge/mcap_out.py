"""ROS 2 MCAP recording: the messages the bridge publishes, as rosbag2 writes them.

Profile "ros2"; each schema has encoding "ros2msg" and holds the .msg text
followed by each dependency's text after a line of 80 "=" and a
"MSG: <type>" line; each channel has message encoding "cdr" and carries the
CDR payload exactly as published on Zenoh. Foxglove, PlotJuggler, rosbag2's
MCAP storage plugin and rosbags read it.
"""

from __future__ import annotations

import os
import threading
from typing import IO, Dict, List, Optional

from .typehash import MESSAGES, type_description

_SEPARATOR = "=" * 80


class FileExistsRefused(FileExistsError):
    """The output path already holds a file and --overwrite was not given."""


def ros2msg_schema(ros_type: str) -> bytes:
    """The ros2msg schema text of a message type: its definition, then each
    type it references (by full name, sorted), as rosbag2 writes them."""
    desc = type_description(ros_type)
    parts: List[str] = [MESSAGES[ros_type].rstrip("\n")]
    for ref in desc["referenced_type_descriptions"]:
        name = ref["type_name"]
        parts.append(f"{_SEPARATOR}\nMSG: {name}\n{MESSAGES[name].rstrip(chr(10))}")
    return ("\n".join(parts) + "\n").encode("utf-8")


class McapRecorder:
    """Writes messages to one MCAP file; thread-safe (one lock around the writer).

    Refuses (FileExistsRefused) to replace an existing file unless force (--overwrite).
    close() writes the summary and footer; a file not closed (the process
    killed) is truncated but its complete chunks stay readable with recovery.
    """

    def __init__(self, path: str, force: bool = False) -> None:
        from mcap.writer import CompressionType, Writer  # the "bridge" extra

        self.path = path
        if os.path.isdir(path):
            raise IsADirectoryError(f"{path}: is a directory")
        try:
            self._f: Optional[IO[bytes]] = open(path, "wb" if force else "xb")
        except FileExistsError:
            raise FileExistsRefused(
                f"{path}: already exists; not overwritten (choose another name, or "
                "--overwrite)") from None
        self._w = Writer(self._f, compression=CompressionType.ZSTD, chunk_size=256 * 1024)
        self._w.start(profile="ros2", library="leptrino-bridge")
        self._lock = threading.Lock()
        self._schemas: Dict[str, int] = {}
        self._channels: Dict[str, int] = {}
        self._seq: Dict[int, int] = {}
        self.messages = 0

    def channel(self, topic: str, ros_type: str) -> int:
        """The channel id of a topic (registered on first use)."""
        with self._lock:
            if topic in self._channels:
                return self._channels[topic]
            sid = self._schemas.get(ros_type)
            if sid is None:
                sid = self._w.register_schema(ros_type, "ros2msg", ros2msg_schema(ros_type))
                self._schemas[ros_type] = sid
            cid = self._w.register_channel(topic, "cdr", sid, {"offered_qos_profiles": ""})
            self._channels[topic] = cid
            self._seq[cid] = 0
            return cid

    def write(self, channel_id: int, payload: bytes, publish_ns: int, log_ns: int) -> None:
        """One message: publish_ns is the message's own time (header stamp),
        log_ns when the bridge handled it."""
        with self._lock:
            if self._f is None:
                return
            self._seq[channel_id] += 1
            self._w.add_message(channel_id, log_time=log_ns, data=payload,
                                publish_time=publish_ns, sequence=self._seq[channel_id])
            self.messages += 1

    def close(self) -> None:
        """Finish the file (summary, footer) and close it. Idempotent."""
        with self._lock:
            if self._f is None:
                return
            try:
                self._w.finish()  # type: ignore[no-untyped-call]
            finally:
                self._f.close()
                self._f = None
