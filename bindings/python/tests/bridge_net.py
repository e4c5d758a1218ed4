"""Network helpers shared by the bridge's tests: a free TCP port on
127.0.0.1, and a Zenoh session confined to loopback (no multicast
scouting), as the tests' routers, subscribers and bridges use them."""

from __future__ import annotations

import json
import socket
from typing import Any, List


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def open_zenoh(mode: str, **eps: List[str]) -> Any:
    """A Zenoh session in mode ("router", "client", "peer") with the given
    endpoints (listen=[...], connect=[...]) and multicast scouting off."""
    import zenoh  # the "bridge" extra; the callers skip without it

    conf = zenoh.Config()
    conf.insert_json5("mode", json.dumps(mode))
    for k, v in eps.items():
        conf.insert_json5(f"{k}/endpoints", json.dumps(v))
    conf.insert_json5("scouting/multicast/enabled", "false")
    return zenoh.open(conf)
