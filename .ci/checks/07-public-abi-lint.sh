#!/usr/bin/env bash
# The public headers hold only what any language's FFI can call
# (test/checks/public_abi_lint.py: no bool, no plain unsigned, no struct by
# value, flat or size-first structs, constants as enumerators, each
# caller-allocated context with its lep_*_sizeof); first the lint is shown to
# find each rule broken in a header made to break them, and nothing in one
# made to pass. pycparser: the Python in PATH's, or Debian's.
set -euo pipefail
cd "$(dirname "$0")/../.."
py=python3
if ! python3 -c 'import pycparser' 2>/dev/null; then
  ci_apt python3-pycparser
  py=/usr/bin/python3
fi
lint=test/checks/public_abi_lint.py
"$py" "$lint" --include test/checks/public_abi_lint_bad \
  --expect-rules bool,unsigned,by-value,variadic,nested,pointer,char-array,unsized,macro,context >/dev/null
"$py" "$lint" --include test/checks/public_abi_lint_good >/dev/null
echo "public-abi-lint: the lint finds each rule broken and passes a clean header"
"$py" "$lint"
