#!/usr/bin/env bash
# Runs the temporal quality harness (frame by frame vs --temporal pca) on
# builtin:animated and stitches a before/after strip for docs/.
#
#   tests/bench/quality/temporal_quality.sh BUILD_BIN_DIR [--gltf] [temporal_quality options...]
#
# --gltf: instead, an animated glTF with a moving camera: make_cornell.py's
# box (tests/bench/scenes) animated by animate_cornell.py (camera trucking,
# light and box moving); its table, frames and strip get a "_gltf" suffix.
#
# The default run is short (96x96, 16 frames). References are cached in
# build/quality-cache and never recomputed; the first run renders them.
# The table goes to build/quality-cache/temporal_quality.md unless --out
# is given; frames go to build/quality-png/temporal and, with oiiotool,
# the strip to build/quality-png/temporal_strip.png.
set -euo pipefail
if [[ $# -lt 1 || ! -x "$1/temporal_quality" ]]; then
  echo "usage: $0 BUILD_BIN_DIR [temporal_quality options]  (BUILD_BIN_DIR holds temporal_quality)" >&2
  exit 2
fi
bin=$(cd "$1" && pwd)
shift
repo=$(cd "$(dirname "$0")/../../.." && pwd)
cd "$repo"
args=()
gltf=""
for a in "$@"; do if [[ "$a" == "--gltf" ]]; then gltf=1; else args+=("$a"); fi; done
have() { local o; for o in "${args[@]}"; do [[ "$o" == "$1" || "$o" == "$1="* ]] && return 0; done; return 1; }
suffix=${gltf:+_gltf}
if [[ -n "$gltf" ]]; then
  mkdir -p build/quality-cache/scene
  python3 tests/bench/scenes/make_cornell.py build/quality-cache/scene > /dev/null
  python3 tests/bench/quality/animate_cornell.py build/quality-cache/scene/cornell.gltf \
    build/quality-cache/scene/cornell_animated.gltf
  have --scene || args+=(--scene build/quality-cache/scene/cornell_animated.gltf)
fi
have --cache || args+=(--cache build/quality-cache)
have --out || args+=(--out "build/quality-cache/temporal_quality$suffix.md")
pngs=build/quality-png/temporal$suffix
have --png-dir || args+=(--png-dir "$pngs")
"$bin/temporal_quality" "${args[@]}"

# Strip: rows frame by frame (16 spp), PCA, photons (when run), reference;
# six frames around the light switch.
if command -v oiiotool > /dev/null && [[ -d "$pngs" ]]; then
  picks=()
  rows=0
  for row in frame_by_frame_16spp pca pca_object photons reference; do
    [[ -f "$pngs/${row}_0003.png" ]] || continue
    rows=$((rows + 1))
    for t in 0003 0006 0007 0008 0009 0012; do picks+=("$pngs/${row}_$t.png"); done
  done
  for f in "${picks[@]}"; do [[ -f "$f" ]] || { echo "strip: $f missing" >&2; exit 1; }; done
  if [[ $rows -ge 3 ]]; then
    oiiotool "${picks[@]}" --mosaic:pad=2 6x$rows -o "build/quality-png/temporal_strip$suffix.png"
    echo "strip: build/quality-png/temporal_strip$suffix.png (rows: frame by frame 16 spp, image-space PCA 16 spp, object-space PCA, photons, reference; frames 3 6 7 8 9 12)"
  fi
fi
