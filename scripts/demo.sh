#!/usr/bin/env bash
# The main job: install what is missing, build Release, run `antcd demo` (no arguments needed).
# Extra arguments are passed to `antcd demo`.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
build_dir="${ANTCD_BUILD_DIR:-build}"
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
targets=(antcd_cli)
# The browser page the demo writes next to its table (demo-view.html) needs the viewer's bundle.
if command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1; then
  targets+=(antcd_viewer)
fi
cmake --build "$build_dir" -j "$(nproc)" --target "${targets[@]}"
"$build_dir/apps/antcd/antcd" demo "$@"
