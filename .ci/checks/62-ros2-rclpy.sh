#!/usr/bin/env bash
# Real ROS 2 nodes against leptrino-bridge --dds: rclpy on the default
# middleware (rmw_fastrtps_cpp) of ROS 2 Jazzy (Fast DDS 2.14) and Kilted
# (Fast DDS 3.2), from PyPI's ROS 2 wheels (x86_64; made with CPython 3.11 as
# the issue did), each in a venv of its own under build/ (kept while its
# requirement line is the same):
#   python3.11 -m venv build/ros2-<distro>-venv
#   pip install "ros-<distro>-rclpy[fastrtps]" ros-<distro>-geometry-msgs \
#               ros-<distro>-std-srvs ros-<distro>-diagnostic-msgs
# (about 30 s and 250 MB each on this machine). Then
# test/bridge/test_bridge_ros2_rclpy.py in the bridge's venv (build/bridge-venv,
# made as 60-bridge.sh makes it when missing): the bridge with a virtual
# sensor on DDS, the rclpy client of test/bridge/ros2_nodes checking every
# topic, the graph and both Trigger services, 127.0.0.1 only. What the bridge
# does not do yet is xfail(strict=True) there, with its cause
# (docs/ros2-rmw-notes.md). Bounded: 300 s for both distributions.
set -euo pipefail
t0=$SECONDS
py311=""
for c in python3.11 python3; do
  if command -v "$c" >/dev/null && "$c" -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
    py311=$(command -v "$c"); break
  fi
done
if [ -z "$py311" ]; then
  echo "62-ros2-rclpy: SKIPPED: no CPython 3.11 here (this check installs the ROS 2 wheels with 3.11)"
  exit 0
fi
for d in jazzy kilted; do
  v="build/ros2-$d-venv"
  req="ros-$d-rclpy[fastrtps] ros-$d-geometry-msgs ros-$d-std-srvs ros-$d-diagnostic-msgs"
  if [ -x "$v/bin/python" ] && [ "$(cat "$v/.leptrino-req" 2>/dev/null)" = "$req" ]; then
    echo "62-ros2-rclpy: $v kept"
    continue
  fi
  s=$SECONDS
  rm -rf "$v"
  "$py311" -m venv "$v"
  "$v/bin/python" -m pip install -q --upgrade pip
  # shellcheck disable=SC2086
  "$v/bin/python" -m pip install -q $req
  echo "$req" > "$v/.leptrino-req"
  echo "62-ros2-rclpy: $v made in $((SECONDS - s)) s, $(du -sm "$v" | cut -f1) MB"
done
bpy="$PWD/build/bridge-venv/bin/python"
if ! "$bpy" -c 'import leptrino.bridge, cyclonedds, pytest' 2>/dev/null; then
  python3 -m venv build/bridge-venv
  "$bpy" -m pip install -q --upgrade pip
  "$bpy" -m pip install -q "./bindings/python[bridge,test]"
fi
echo "62-ros2-rclpy: venvs ready ($((SECONDS - t0)) s so far)"
PYTHONDONTWRITEBYTECODE=1 timeout 300 "$bpy" -m pytest -q -rxXs -p no:cacheprovider \
  test/bridge/test_bridge_ros2_rclpy.py
echo "62-ros2-rclpy: done in $((SECONDS - t0)) s"
