#!/usr/bin/env bash
# Sets everything up on a fresh Debian 12 machine (as root), builds, and runs
# the main job: two render nodes on loopback path-trace builtin:cornell
# cooperatively at 8 samples per pixel, once as it is and once with pixel
# filtering (Schwenk ch. 3), resolved on the client so tiles show no seams.
# The pictures land in out/: cornell-unfiltered.png, cornell-filtered.png
# and cornell-compare.png (the two side by side).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset default
cmake --build --preset default -j"$(nproc)"
mkdir -p out
bash scripts/cluster-demo.sh out/cornell-unfiltered.png 512x512 --spp 8
bash scripts/cluster-demo.sh out/cornell-filtered.png 512x512 --spp 8 --filter pixel
oiiotool out/cornell-unfiltered.png out/cornell-filtered.png --mosaic 2x1 -o out/cornell-compare.png
echo "wrote out/cornell-compare.png: unfiltered (left) and filtered (right), 8 spp each"
