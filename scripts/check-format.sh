#!/usr/bin/env bash
# Checks the formatting (.clang-format, Debian's clang-format 14) of every C++ file git tracks (and
# of new ones added with `git add -N`). The whole tree was formatted once, in a commit of its own,
# so every file is checked, not only the lines a change touched. About 4 s.
# Usage: scripts/check-format.sh        exits 1 naming each file clang-format would change (fix
#                                       with: clang-format -i FILE), 2 on a usage error.
set -euo pipefail
cd "$(dirname "$0")/.."

if [ $# -gt 0 ]; then
  echo "usage: scripts/check-format.sh" >&2
  exit 2
fi
clang_format="$(command -v clang-format-14 || command -v clang-format || true)"
if [ -z "$clang_format" ]; then
  echo "error: clang-format is needed (Debian package clang-format)" >&2
  exit 2
fi

mapfile -t files < <(git ls-files -- '*.cpp' '*.hpp' '*.h' '*.cc')
if [ ${#files[@]} -eq 0 ]; then
  echo "check-format: no C++ file tracked" >&2
  exit 2
fi
mapfile -t bad < <("$clang_format" --dry-run "${files[@]}" 2>&1 | sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: warning:.*/\1/p' | sort -u)
if [ ${#bad[@]} -gt 0 ]; then
  printf '%s\n' "${bad[@]}"
  echo "check-format: ${#bad[@]} of ${#files[@]} file(s) are not formatted; fix with: clang-format -i FILE" >&2
  exit 1
fi
echo "check-format: all ${#files[@]} C++ files are formatted"
