"""leptrino.bridge: sensors as ROS 2 topics on Zenoh (rmw_zenoh's layout),
DDS (ROS 2's DDS conventions), Foxglove live, and to MCAP.

Needs the "bridge" extra (pip install "leptrino[bridge]": eclipse-zenoh,
mcap; cyclonedds and foxglove-sdk from Python 3.10). The command is
leptrino-bridge (cli.main); docs/bridge.md tells the layout, the ROS 2
release it follows and how to receive it.
"""

from .bridge import Bridge, ZenohOptions
from .dds import DdsOptions
from .node import NodeOptions, SensorNode, SensorSpec

__all__ = ["Bridge", "DdsOptions", "NodeOptions", "SensorNode", "SensorSpec", "ZenohOptions"]
