#!/usr/bin/env bash
# `leptrino watch` in a real terminal: the tmux-driven tests of test/cli must
# run here, not be skipped (ctest skips them on a machine without tmux).
set -euo pipefail
ci_apt tmux
cli=build/dev/tools/leptrino/leptrino
[ -x "$cli" ] || { cmake --preset dev >/dev/null && cmake --build --preset dev; }
py=build/venv/bin/python   # made by `make test`, with pytest
if ! [ -x "$py" ] || ! "$py" -c "import pytest" 2>/dev/null; then
  ci_apt python3-pytest
  py=python3
fi
LEPTRINO_REQUIRE_TMUX=1 LEPTRINO_CLI="$cli" LEPTRINO_CLI_SIM=build/dev/test/cli/lep_cli_sim \
  PYTHONDONTWRITEBYTECODE=1 "$py" -m pytest -q -p no:cacheprovider test/cli/test_cli_watch.py
