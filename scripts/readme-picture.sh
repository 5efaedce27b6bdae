#!/usr/bin/env bash
# The README's picture, docs/viewer-frame140.png: the browser viewer page that `antcd demo` writes
# (the paper's scene, exact against MACO), drawn by Debian's headless Chromium at frame 140 once
# the viewer says it is ready (tests/viewer/screenshot.mjs; no browser is downloaded).
#
#   bash scripts/readme-picture.sh [OUT.png]     default docs/viewer-frame140.png
#
# Uses the build in $ANTCD_BUILD_DIR (default build/), configured already; builds only the tool and
# the viewer's bundle there. Needs node, npm (the viewer's bundle) and chromium.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${ANTCD_BUILD_DIR:-build}"
out="${1:-docs/viewer-frame140.png}"
for tool in node chromium; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "error: $tool is not installed (scripts/install-deps.sh installs it)" >&2
    exit 2
  fi
done
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  echo "error: no build in $build_dir (configure one first: docs/building.md)" >&2
  exit 2
fi
cmake --build "$build_dir" -j "$(nproc)" --target antcd_cli antcd_viewer >/dev/null
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# The demo's defaults: the paper's scene (seeded) and its methods; the page holds exact and MACO.
"$build_dir/apps/antcd/antcd" demo --view "$work/demo-view.html" >"$work/demo.txt"
node tests/viewer/screenshot.mjs --node-modules "$build_dir/viewer/node_modules" \
  --chromium "$(command -v chromium)" --page "$work/demo-view.html" --frame 140 \
  --width 1200 --height 700 --out "$out"
echo "wrote $out ($(stat -c %s "$out") bytes)"
