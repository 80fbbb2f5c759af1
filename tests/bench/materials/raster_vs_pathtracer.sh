#!/usr/bin/env bash
# The rasterizer's image against the converged path tracer's, by the seen
# error (tests/bench/quality/seen_error.py: displayed, de-grained RMSE of
# the whole image and of the worst 16x16 tile), at 128x128, on
# builtin:cornell and every scene of the quality suite.
#   tests/bench/materials/raster_vs_pathtracer.sh [BUILD_BIN] [REFERENCE_SPP]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
bin=${1:-$root/build/default/bin}
spp=${2:-1024}
work=$(mktemp -d /tmp/tsr-raster-vs-pt.XXXXXX)
python3 "$root/tests/bench/quality/suite/make_suite.py" "$work/suite" > /dev/null
printf '%-20s %s\n' scene "seen error whole / worst tile (reference: $spp spp)"
for scene in builtin:cornell "$work"/suite/*.gltf; do
  name=$(basename "${scene#builtin:}" .gltf)
  "$bin/tessera-render" "$scene" --backend embree --size 128x128 --spp "$spp" --quiet --output "$work/$name.ref.exr"
  "$bin/tessera-render" "$scene" --backend vulkan --size 128x128 --quiet --output "$work/$name.vk.exr"
  printf '%-20s %s\n' "$name" "$(/usr/bin/python3 "$root/tests/bench/quality/seen_error.py" "$work/$name.vk.exr" "$work/$name.ref.exr")"
done
echo "images in $work"
