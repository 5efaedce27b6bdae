#!/usr/bin/env bash
# The main job: install what is missing, build Release, run `antcd demo` (no arguments needed).
# Extra arguments are passed to `antcd demo`.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
build_dir="${ANTCD_BUILD_DIR:-build}"
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "$(nproc)" --target antcd_cli
"$build_dir/apps/antcd/antcd" demo "$@"
