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
# The WebAssembly package (wasm/, with the Emscripten install-deps.sh installs) is part of the
# build; ctest runs its node tests, its npm pack and the live viewer page (wasm_node, wasm_pack,
# viewer_live). Installed Emscripten but no package means the build skipped it: fail here.
if command -v emcmake >/dev/null 2>&1 && [ ! -f wasm/dist/antcd_core.wasm ]; then
  echo "error: Emscripten is installed but the build made no wasm/dist/antcd_core.wasm" >&2
  exit 1
fi
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
