#!/usr/bin/env bash
# Checks every C++ file git tracks against .clang-format (clang-format 14, Debian's); lists the
# files that differ and fails. With --fix, rewrites them instead.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || deploy/install-deps.sh --format
mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.cpp.in')
if [[ "${1:-}" == --fix ]]; then
  clang-format -i --style=file "${files[@]}"
  exit 0
fi
# One process for all files; each difference is reported as "FILE:LINE:COL: error: ...".
mapfile -t unformatted < <(clang-format --style=file --dry-run --Werror "${files[@]}" 2>&1 |
                           grep -o '^[^: ]*:[0-9]*:[0-9]*: error' | cut -d: -f1 | sort -u || true)
if (( ${#unformatted[@]} )); then
  echo "not formatted as .clang-format says (fix: deploy/check-format.sh --fix):"
  printf '  %s\n' "${unformatted[@]}"
  exit 1
fi
echo "format: ${#files[@]} files as .clang-format says ($(clang-format --version | grep -o 'version [0-9.]*'))"
