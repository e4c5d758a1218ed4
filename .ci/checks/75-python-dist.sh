#!/usr/bin/env bash
# The Python sdist and wheel, built with `python -m build` and installed as a
# user would, each in a fresh venv outside the checkout; the wheel tagged
# manylinux by the build's auditwheel repair, and auditwheel show on it;
# bindings/python copied alone refused with a clear message.
# (test/python/dist_check.py says what exactly.) Needs PyPI for build,
# auditwheel, numpy, cffi and setuptools.
set -euo pipefail
cd "$(dirname "$0")/../.."
ci_apt python3 python3-venv python3-pip cmake ninja-build gcc
tools=build/venv-dist-tools
python3 -m venv "$tools"
"$tools/bin/python" -m pip install -q --upgrade pip
"$tools/bin/python" -m pip install -q build auditwheel
"$tools/bin/python" test/python/dist_check.py --tools-python "$tools/bin/python"
