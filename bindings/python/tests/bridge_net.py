"""Network helpers shared by the bridge's tests: a free TCP port on
127.0.0.1, waiting for a server's port, a Zenoh session confined to
loopback (no multicast scouting), as the tests' routers, subscribers and
bridges use them, and a Zenoh router fixture."""

from __future__ import annotations

import json
import socket
import time
from typing import Any, Iterator, List

import pytest


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


def wait_for_port(port: int, timeout: float = 15.0) -> None:
    """Until a server answers on 127.0.0.1:port (at most timeout s)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
            return
        except OSError:
            time.sleep(0.1)


@pytest.fixture
def router() -> Iterator[str]:
    """A Zenoh router listening on a free 127.0.0.1 port: its endpoint."""
    ep = f"tcp/127.0.0.1:{free_port()}"
    r = open_zenoh("router", listen=[ep])
    try:
        yield ep
    finally:
        r.close()
