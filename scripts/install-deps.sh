#!/usr/bin/env bash
# Installs the Debian 12 packages antcd needs to build, test and benchmark, if any are missing.
# Usage: scripts/install-deps.sh [EXTRA-PACKAGE ...]   (run as root, or with sudo available)
# Extra packages (e.g. clang for scripts/fuzz.sh) are installed the same way.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git ccache
  libeigen3-dev libassimp-dev libtinyobjloader-dev libtbb-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev libcgal-dev
  libfcl-dev libbullet-dev clang-format
  libkainjow-mustache-dev
  libtorch-dev zlib1g-dev
  assimp-testmodels gnuplot-nox valgrind
  python3-dev python3-pybind11 pybind11-dev python3-numpy python3-pytest python3-matplotlib
  python3-pip python3-setuptools python3-wheel python3-venv python3-build
  chromium
  # The WebAssembly package (wasm/) and the live viewer page: Emscripten 3.1 (with node-acorn).
  emscripten
  "$@"
)
# The browser viewer is bundled with npm (viewer/package-lock.json) and needs node >= 18. Debian's
# nodejs and npm only when the commands are missing: a node from elsewhere (e.g. nodesource, whose
# nodejs package conflicts with Debian's npm) is kept.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "installing missing Debian packages: ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo_cmd=(sudo)
  else
    echo "error: missing packages (${missing[*]}) and not root: run this script as root" >&2
    exit 2
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
