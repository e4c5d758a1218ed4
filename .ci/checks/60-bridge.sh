#!/usr/bin/env bash
# leptrino-bridge (bindings/python/leptrino/bridge): a fresh venv under
# build/ with the package and its "bridge" and "test" extras (eclipse-zenoh,
# mcap; mcap-ros2-support and rosbags as independent readers), then the
# bridge's tests: a real Zenoh router and subscriber on 127.0.0.1 (ports
# chosen by the tests), the MCAP file read back, the command line, and a
# smoke run of the figures' benchmark (1 and 2 virtual sensors, bounded).
set -euo pipefail
py="$PWD/build/bridge-venv/bin/python"
python3 -m venv build/bridge-venv
"$py" -m pip install -q --upgrade pip
"$py" -m pip install -q "./bindings/python[bridge,test]"
PYTHONDONTWRITEBYTECODE=1 timeout 600 "$py" -m pytest -q -p no:cacheprovider \
  bindings/python/tests/test_bridge_wire.py bindings/python/tests/test_bridge_zenoh.py \
  bindings/python/tests/test_bridge_mcap.py
"$(dirname "$py")/leptrino-bridge" --help >/dev/null   # the console script is installed
(cd /tmp && timeout 300 "$py" -m leptrino.bridge.bench --quick)
