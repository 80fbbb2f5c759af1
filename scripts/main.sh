#!/usr/bin/env bash
# Sets everything up on a fresh Debian 12 machine (as root), builds, and runs
# the main job: two render nodes on loopback path-trace builtin:cornell
# cooperatively; the image is written to cornell-cluster.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset default
cmake --build --preset default -j"$(nproc)"
bash scripts/cluster-demo.sh cornell-cluster.png 512x512 --spp 64
