#!/usr/bin/env python3
"""Spike, not the bridge: leptrino-bridge's command line with its DDS
transport served by rclpy (the real rmw: rmw_fastrtps_cpp by default)
instead of Cyclone DDS' Python binding -- option (a) of
docs/ros2-rmw-notes.md, measured there.

It runs leptrino.bridge.cli.main() unchanged, with the one class the bridge
makes for --dds (leptrino.bridge.dds.DdsParticipant) swapped for RclpyDds
below, which offers the same methods (writer, command, service,
subscription, announce, close): one rclpy node per sensor, publishers that
publish the bridge's CDR bytes as they are (Publisher.publish(bytes)),
std_srvs/srv/Trigger services, raw subscriptions for the gravity input.

Run with a ROS 2 Python (rclpy importable) that can also import leptrino:
  ROS_PY=build/ros2-jazzy-venv/bin/python
  $ROS_PY rclpy_bridge_spike.py --site build/bridge-venv/lib/python3.11/site-packages \
      --sim a --dds --domain 42
(--site appends the bridge venv's site-packages to sys.path; every other
argument is leptrino-bridge's.)"""

import sys
import threading
from typing import Any, Callable, Dict, Tuple


def _take_site(argv):
    if "--site" in argv:
        i = argv.index("--site")
        sys.path.append(argv[i + 1])
        del argv[i:i + 2]


class RclpyDds:
    """leptrino.bridge.dds.DdsParticipant's interface on rclpy."""

    def __init__(self, domain: int, opts: Any) -> None:
        import rclpy
        from rclpy.executors import MultiThreadedExecutor

        self.rclpy = rclpy
        from rclpy.signals import SignalHandlerOptions

        self.context = rclpy.Context()
        # the bridge handles SIGINT/SIGTERM itself: rclpy installs no handler
        rclpy.init(context=self.context, domain_id=domain,
                   signal_handler_options=SignalHandlerOptions.NO)
        self.executor = MultiThreadedExecutor(num_threads=2, context=self.context)
        self.nodes: Dict[Tuple[str, str], Any] = {}
        self._spin = None
        self._keep = []

    def _node(self, node: Tuple[str, str]) -> Any:
        if node not in self.nodes:
            ns, name = node
            n = self.rclpy.create_node(name, namespace=ns, context=self.context,
                                       start_parameter_services=False)
            self.nodes[node] = n
            self.executor.add_node(n)
        return self.nodes[node]

    @staticmethod
    def _qos() -> Any:
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
        return QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE,
                          durability=DurabilityPolicy.VOLATILE, history=HistoryPolicy.KEEP_LAST)

    @staticmethod
    def _msg_class(ros_type: str) -> Any:
        import importlib
        pkg, _, name = ros_type.split("/")
        return getattr(importlib.import_module(f"{pkg}.msg"), name)

    def writer(self, node: Tuple[str, str], fq_name: str, ros_type: str) -> Any:
        pub = self._node(node).create_publisher(self._msg_class(ros_type), fq_name, self._qos())

        class Writer:
            def publish(self, payloads, stamps, now_ns):
                for p in payloads:
                    pub.publish(bytes(p))

            def close(self):
                pass
        return Writer()

    def command(self, node: Tuple[str, str], fq_name: str, action: Callable[[str], Any]) -> None:
        from rclpy.qos import qos_profile_sensor_data
        from std_msgs.msg import Empty

        def cb(_msg):
            threading.Thread(target=action, args=("rclpy command topic",), daemon=True).start()
        self._keep.append(self._node(node).create_subscription(Empty, fq_name, cb,
                                                               qos_profile_sensor_data))

    def service(self, node: Tuple[str, str], fq_name: str,
                action: Callable[[str], Tuple[bool, str]], on_rejected: Callable[[], None]) -> Any:
        from std_srvs.srv import Trigger

        def cb(request, response):
            ok, message = action("rclpy client")
            response.success, response.message = bool(ok), message
            return response
        srv = self._node(node).create_service(Trigger, fq_name, cb)

        class Svc:
            headerless_clients = 0
            rejected = 0
            service = srv
        return Svc()

    def subscription(self, node: Tuple[str, str], fq_name: str, ros_type: str,
                     on_payload: Callable[[bytes], Any]) -> None:
        from rclpy.qos import qos_profile_sensor_data
        self._keep.append(self._node(node).create_subscription(
            self._msg_class(ros_type), fq_name, lambda raw: on_payload(bytes(raw)),
            qos_profile_sensor_data, raw=True))

    def announce(self) -> None:  # rclpy's nodes are in the graph already; start serving
        self._spin = threading.Thread(target=self.executor.spin, daemon=True)
        self._spin.start()

    def close(self) -> None:
        self.executor.shutdown(timeout_sec=1.0)
        for n in self.nodes.values():
            n.destroy_node()
        self.rclpy.shutdown(context=self.context)


def main() -> int:
    argv = sys.argv[1:]
    _take_site(argv)
    import leptrino.bridge.dds as dds
    from leptrino.bridge.cli import main as bridge_main

    dds.DdsParticipant = RclpyDds  # type: ignore[misc,assignment]
    sys.argv = ["leptrino-bridge"] + argv
    return bridge_main()


if __name__ == "__main__":
    sys.exit(main())
