#!/usr/bin/env bash
# The `leptrino` tool's tests (test/cli: pytest against the real binaries and
# the virtual sensor), with tmux installed so that `leptrino watch` and the
# stream's keys are driven in a real terminal, never skipped
# (LEPTRINO_REQUIRE_TMUX=1 turns a missing tmux into a failure). ctest runs
# the same tests only when the system python has pytest.
set -euo pipefail
ci_apt tmux
root=$(pwd)
cli=$root/build/dev/tools/leptrino/leptrino
helper=$root/build/dev/test/cli/lep_cli_sim
if ! [ -x "$cli" ] || ! [ -x "$helper" ]; then
  cmake --preset dev >/dev/null && cmake --build --preset dev
fi
py=$root/build/venv/bin/python   # made by `make test`, with pytest
if ! [ -x "$py" ] || ! "$py" -c "import pytest" 2>/dev/null; then
  ci_apt python3-pytest
  py=python3
fi
cd test/cli
LEPTRINO_REQUIRE_TMUX=1 LEPTRINO_CLI="$cli" LEPTRINO_CLI_SIM="$helper" \
  PYTHONDONTWRITEBYTECODE=1 "$py" -m pytest -q -p no:cacheprovider .
