#!/usr/bin/env bash
# Python lint and type check of the package (leptrino and leptrino.bridge):
# ruff and mypy, pinned, in a venv under build/, configured in
# bindings/python/pyproject.toml ([tool.ruff], [tool.mypy]). The optional
# dependencies the package imports (numpy for its types; zenoh, mcap,
# cyclonedds, foxglove for the bridge) are not installed: mypy is told to
# take them as untyped (ignore_missing_imports), so the check needs no
# compiler and no network beyond these two tools.
set -euo pipefail
t0=$SECONDS
venv="$PWD/build/lint-venv"
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -m pip install -q "ruff==0.17.6" "mypy==2.4.1" "numpy>=1.20"
cd bindings/python
"$venv/bin/ruff" check leptrino
"$venv/bin/mypy" leptrino
echo "58-python-lint: done in $((SECONDS - t0)) s"
