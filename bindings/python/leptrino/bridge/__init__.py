"""leptrino.bridge: sensors on Zenoh in ROS 2's layout (rmw_zenoh) and to MCAP.

Needs the "bridge" extra (pip install "leptrino[bridge]": eclipse-zenoh,
mcap). The command is leptrino-bridge (cli.main); docs/bridge.md tells the
layout, the ROS 2 release it follows and how to receive it.
"""

from .bridge import Bridge, ZenohOptions
from .node import NodeOptions, SensorNode, SensorSpec

__all__ = ["Bridge", "NodeOptions", "SensorNode", "SensorSpec", "ZenohOptions"]
