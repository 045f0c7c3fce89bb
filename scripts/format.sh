#!/usr/bin/env bash
# Formats every tracked .cpp and .h with the project's .clang-format (clang-format 14, Debian 12).
#   bash scripts/format.sh           rewrite the files in place
#   bash scripts/format.sh --check   change nothing; fail, naming the files, if any is not formatted
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if [ "${1:-}" = "--check" ]; then
  bad=()
  for f in "${files[@]}"; do
    clang-format-14 --style=file "$f" | cmp -s - "$f" || bad+=("$f")
  done
  if [ ${#bad[@]} -gt 0 ]; then
    echo "format: not formatted (run bash scripts/format.sh): ${bad[*]}" >&2
    exit 1
  fi
else
  clang-format-14 -i --style=file "${files[@]}"
fi
