#!/usr/bin/env bash
# Checks the formatting (.clang-format, Debian's clang-format) of the C++ lines changed since a base
# commit: the lines changed in BASE..HEAD and in the working tree (staged or not). Lines nobody
# touched are not checked (much of the tree predates the check; reformatting it all at once would
# collide with every branch in flight), so the tree converges as files are edited.
# Usage: scripts/check-format.sh [BASE]
#   BASE defaults to the merge base with the branch `main` (when HEAD is not main itself), else
#   HEAD~1 (CI on main: the last commit). Exits 1 and prints the diff clang-format asks for when a
#   changed line is not formatted (apply it with: git clang-format BASE), 2 on a usage error.
# --files instead checks every changed file as a whole: scripts/check-format.sh --files [BASE].
set -euo pipefail
cd "$(dirname "$0")/.."

whole_files=0
if [ "${1:-}" = "--files" ]; then
  whole_files=1
  shift
fi
if [ $# -gt 1 ]; then
  echo "usage: scripts/check-format.sh [--files] [BASE]" >&2
  exit 2
fi

clang_format="$(command -v clang-format-14 || command -v clang-format || true)"
git_clang_format="$(command -v git-clang-format-14 || command -v git-clang-format || true)"
if [ -z "$clang_format" ] || [ -z "$git_clang_format" ]; then
  echo "error: clang-format and git-clang-format are needed (Debian package clang-format)" >&2
  exit 2
fi

base="${1:-}"
if [ -z "$base" ]; then
  if git rev-parse -q --verify main >/dev/null &&
    [ "$(git rev-parse main)" != "$(git rev-parse HEAD)" ]; then
    base="$(git merge-base main HEAD)"
  elif git rev-parse -q --verify HEAD~1 >/dev/null; then
    base="HEAD~1"
  else
    echo "error: no base commit to compare with (name one: scripts/check-format.sh BASE)" >&2
    exit 2
  fi
fi
if ! git rev-parse -q --verify "$base^{commit}" >/dev/null; then
  echo "error: base '$base' is not a commit" >&2
  exit 2
fi

extensions=cpp,hpp,h,cc
if [ "$whole_files" = 1 ]; then
  mapfile -t files < <(git diff --name-only --diff-filter=ACMR "$base" -- '*.cpp' '*.hpp' '*.h' '*.cc')
  if [ ${#files[@]} -eq 0 ]; then
    echo "check-format: no C++ file changed since $base"
    exit 0
  fi
  if ! "$clang_format" --dry-run -Werror "${files[@]}"; then
    echo "check-format: ${#files[@]} changed file(s) since $base; fix with: clang-format -i FILE" >&2
    exit 1
  fi
  echo "check-format: ${#files[@]} changed file(s) since $base are formatted"
  exit 0
fi

# New files count only once added to git (git add -N is enough).
out="$("$git_clang_format" --binary "$clang_format" --extensions "$extensions" --diff "$base" 2>&1)"
if printf '%s\n' "$out" | grep -q '^diff --git'; then
  printf '%s\n' "$out"
  echo "check-format: changed lines since $(git rev-parse --short "$base") are not formatted;" \
    "fix with: git clang-format $base" >&2
  exit 1
fi
echo "check-format: changed lines since $(git rev-parse --short "$base") are formatted"
