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
from typing import IO, Dict, Optional, Sequence

from .transport import Endpoint, Publisher, Transport
from .schema import ros2msg_schema

#: rmw's RMW_DURATION_INFINITE (rmw/time.h), as rosbag2 writes it
_INFINITE = "\n    sec: 9223372036\n    nsec: 854775807"


def offered_qos_profiles(depth: int = 10, reliable: bool = True) -> str:
    """The channel metadata rosbag2 writes and reads on playback: a YAML list
    of the publishers' QoS profiles, in the form of rosbag2's metadata
    version 9 (policies by name: rosbag2_storage qos.cpp). The bridge offers
    one profile per topic: keep last `depth`, reliable, volatile, infinite
    deadline, lifespan and lease, automatic liveliness (rmw_zenoh's default,
    the same as its graph key expression says)."""
    return ("- history: keep_last\n"
            f"  depth: {int(depth)}\n"
            f"  reliability: {'reliable' if reliable else 'best_effort'}\n"
            "  durability: volatile\n"
            f"  deadline:{_INFINITE}\n"
            f"  lifespan:{_INFINITE}\n"
            "  liveliness: automatic\n"
            f"  liveliness_lease_duration:{_INFINITE}\n"
            "  avoid_ros_namespace_conventions: false")


class FileExistsRefused(FileExistsError):
    """The output path already holds a file and --overwrite was not given."""


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

    def channel(self, topic: str, ros_type: str, qos_depth: int = 10) -> int:
        """The channel id of a topic (registered on first use), with the QoS
        the bridge offers it with in the channel's offered_qos_profiles."""
        with self._lock:
            if topic in self._channels:
                return self._channels[topic]
            sid = self._schemas.get(ros_type)
            if sid is None:
                sid = self._w.register_schema(ros_type, "ros2msg", ros2msg_schema(ros_type))
                self._schemas[ros_type] = sid
            cid = int(self._w.register_channel(
                topic, "cdr", sid, {"offered_qos_profiles": offered_qos_profiles(qos_depth)}))
            self._channels[topic] = cid
            self._seq[cid] = 0
            return cid

    def write(self, channel_id: int, payload: bytes, publish_ns: int, log_ns: int) -> None:
        """One message: publish_ns is the message's own time (header stamp),
        log_ns when the bridge handled it."""
        self.write_batch(channel_id, (payload,), (publish_ns,), log_ns)

    def write_batch(self, channel_id: int, payloads: Sequence[bytes], publish_ns: Sequence[int],
                    log_ns: int) -> None:
        """Several messages of one channel, handled at log_ns."""
        with self._lock:
            if self._f is None:
                return
            seq = self._seq[channel_id]
            add = self._w.add_message
            for p, t in zip(payloads, publish_ns):
                seq += 1
                add(channel_id, log_time=log_ns, data=p, publish_time=t, sequence=seq)
            self._seq[channel_id] = seq
            self.messages += len(payloads)

    def close(self) -> None:
        """Finish the file (summary, footer) and close it. Idempotent."""
        with self._lock:
            if self._f is None:
                return
            try:
                self._w.finish()
            finally:
                self._f.close()
                self._f = None


class McapPublisher(Publisher):
    """A channel of the recording: always listening while the file is open."""

    def __init__(self, rec: McapRecorder, channel_id: int) -> None:
        self._rec = rec
        self._cid = channel_id

    @property
    def listening(self) -> bool:
        return self._rec._f is not None

    def publish(self, payloads: Sequence[bytes], stamps: Sequence[int], now_ns: int) -> None:
        self._rec.write_batch(self._cid, payloads, stamps, now_ns)


class McapTransport(Transport):
    """The recording as a transport: topics only (no services, no inputs)."""

    name = "mcap"
    interactive = False

    def __init__(self, rec: McapRecorder) -> None:
        self.recorder = rec

    def advertise(self, endpoint: Endpoint) -> Publisher:
        return McapPublisher(self.recorder,
                             self.recorder.channel(endpoint.name, endpoint.ros_type,
                                                   endpoint.qos_depth))

    def close(self) -> None:
        self.recorder.close()
