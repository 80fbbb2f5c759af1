#!/usr/bin/env bash
# The rasterizer's image against the converged path tracer's, by the seen
# error (tests/bench/quality/seen_error.py: displayed, de-grained RMSE of
# the whole image and of the worst 16x16 tile), at 128x128, on
# builtin:cornell, every scene of the quality suite and its two assimp
# models (when assimp-testmodels is installed).
#
#   tests/bench/materials/raster_vs_pathtracer.sh [OPTIONS] [BUILD_BIN] [REFERENCE_SPP]
#
#   --refs DIR          keep the path tracer's references in DIR and reuse
#                       those already there (they take most of the time)
#   --param NAME=VALUE  a parameter of the rasterizer's renders (repeatable),
#                       e.g. --param bouncedLight=ambient
#   --sheet OUT.png     a side-by-side sheet: per scene the rasterizer
#                       (left) and the path tracer (right), labelled with
#                       the seen error (needs ImageMagick's montage)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
refs="" sheet="" params=() positional=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --refs) refs=$2; shift 2 ;;
    --param) params+=(--param "$2"); shift 2 ;;
    --sheet) sheet=$2; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "$0: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) positional+=("$1"); shift ;;
  esac
done
bin=${positional[0]:-$root/build/default/bin}
spp=${positional[1]:-1024}
[[ -x "$bin/tessera-render" ]] || { echo "$0: $bin/tessera-render not found (build first)" >&2; exit 2; }
if [[ -n "$sheet" ]]; then
  command -v montage > /dev/null || { echo "$0: --sheet needs montage (ImageMagick)" >&2; exit 2; }
fi
work=$(mktemp -d /tmp/tsr-raster-vs-pt.XXXXXX)
refs=${refs:-$work}
mkdir -p "$refs"
python3 "$root/tests/bench/quality/suite/make_suite.py" "$work/suite" > /dev/null
scenes=(builtin:cornell "$work"/suite/*.gltf)
assimp=/usr/share/assimp/models/glTF2
for model in "$assimp/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" "$assimp/issue_3269/texcoord_crash.gltf"; do
  [[ -f "$model" ]] && scenes+=("$model")
done
printf '%-20s %s\n' scene "seen error whole / worst tile (reference: $spp spp)"
labels=()
for scene in "${scenes[@]}"; do
  name=$(basename "${scene#builtin:}")
  name=${name%.*}
  ref="$refs/$name.$spp.exr"
  [[ -f "$ref" ]] ||
    "$bin/tessera-render" "$scene" --backend embree --size 128x128 --spp "$spp" --quiet --output "$ref"
  "$bin/tessera-render" "$scene" --backend vulkan --size 128x128 --quiet "${params[@]}" --output "$work/$name.vk.exr"
  error=$(/usr/bin/python3 "$root/tests/bench/quality/seen_error.py" "$work/$name.vk.exr" "$ref")
  printf '%-20s %s\n' "$name" "$error"
  if [[ -n "$sheet" ]]; then
    for side in vk ref; do
      from=$([[ $side == vk ]] && echo "$work/$name.vk.exr" || echo "$ref")
      oiiotool "$from" --ch R,G,B --colorconvert linear sRGB -d uint8 -o "$work/$name.$side.png"
    done
    short=$(sed -E 's/seen error whole ([0-9.]+) worst tile ([0-9.]+).*/\1 \/ \2/' <<< "$error")
    labels+=(-label "$name raster $short" "$work/$name.vk.png" -label "path tracer" "$work/$name.ref.png")
  fi
done
if [[ -n "$sheet" ]]; then
  montage -pointsize 9 "${labels[@]}" -tile 6x -geometry +2+2 -background white -depth 8 "$sheet"
  echo "wrote $sheet"
fi
echo "images in $work"
