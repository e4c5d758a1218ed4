#!/usr/bin/env bash
# The C sources are formatted by the tree's .clang-format (clang-format 14,
# Debian's): any difference fails, naming the files.
set -euo pipefail
cd "$(dirname "$0")/../.."
ci_apt clang-format
files=$(git ls-files '*.c' '*.h')
bad=()
for f in $files; do
  if ! clang-format --style=file "$f" | cmp -s - "$f"; then
    bad+=("$f")
  fi
done
if [ ${#bad[@]} -gt 0 ]; then
  echo "format: not formatted by .clang-format (run: clang-format -i FILE):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "format: $(echo "$files" | wc -w) C files formatted"
