#!/usr/bin/env bash
# A clang build of everything with warnings as errors, and its tests.
set -euo pipefail
make clang
