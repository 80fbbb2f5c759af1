#!/usr/bin/env bash
# Installs every Debian 12 package Tessera needs. Idempotent: apt-get skips
# what is already there, and the package index is refreshed only when stale.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config python3
  libembree-dev embree-tools libtbb-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-tools glslc vulkan-validationlayers
  libglfw3-dev xvfb xauth xdotool
  libtinygltf-dev libdraco-dev libmeshoptimizer-dev gltfpack nlohmann-json3-dev libstb-dev
  libxxhash-dev       # the converted-scene cache's keys and checksums (XXH3)
  libopenimageio-dev openimageio-tools
  libboost-dev liblz4-dev libzstd-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev clang-format clang-tidy
  libcli11-dev libspdlog-dev libfmt-dev libglm-dev libimgui-dev
  libeigen3-dev
  openmpi-bin
  assimp-testmodels   # real glTF models of the filter quality suite (tests/bench/quality/suite)
  python3-numpy python3-openimageio  # image metrics of the benchmark scripts
  chromium            # the web client's browser test (Playwright drives it)
  curl                # docs/huge-models.md asks the culling service from the shell (its block is run by the docs test)
)

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps.sh: run as root (it calls apt-get)" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The web client's packages (three.js; playwright-core for its test), as
# web/package-lock.json pins them; reinstalled only when the lock changed.
web="$(dirname "$0")/../web"
if ! command -v npm >/dev/null; then
  echo "install-deps: npm not found (Node.js 20 with npm is needed for the web client)" >&2
  exit 2
fi
if ! cmp -s "$web/package-lock.json" "$web/node_modules/.package-lock.json.installed"; then
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
  cp "$web/package-lock.json" "$web/node_modules/.package-lock.json.installed"
fi
