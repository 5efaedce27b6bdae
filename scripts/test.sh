#!/usr/bin/env bash
# The test command: install what is missing, build everything (warnings are errors), run the suite,
# then install the build (library, headers, CLI, Python package) into the prefix (/usr/local), so that
# `antcd` is on PATH and `python3 -c "import antcd"` works. ANTCD_SKIP_INSTALL=1 skips that step.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
. scripts/compiler-cache.sh
build_dir="${ANTCD_BUILD_DIR:-build}"
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DANTCD_WARNINGS_AS_ERRORS=ON
cmake --build "$build_dir" -j "$(nproc)"
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)"

if [ "${ANTCD_SKIP_INSTALL:-0}" != 1 ]; then
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then sudo_cmd=(sudo); fi
  "${sudo_cmd[@]}" cmake --install "$build_dir" >/dev/null
  # The library folder may be new to the loader cache (the Python module finds it by RPATH anyway).
  if command -v ldconfig >/dev/null 2>&1; then "${sudo_cmd[@]}" ldconfig || true; fi
  if [ -d "$build_dir/python/antcd" ]; then
    (cd / && /usr/bin/python3 -c 'import antcd; print("installed: import antcd works (" + antcd.__file__ + ")")')
  fi
fi
