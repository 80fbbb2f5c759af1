#!/usr/bin/env bash
# A baseline of renders across the back-ends, filters and camera effects, to
# show that a change which should not alter images does not.
#
#   tests/bench/render_baseline.sh BIN_DIR OUT_DIR          render the set
#   tests/bench/render_baseline.sh --compare DIR_A DIR_B    compare two sets
#
# Renders are small (96x96) float EXR files; --compare checks their pixels
# with OpenImageIO's idiff at a tolerance of zero (the files themselves carry
# the time they were written), lists each render as "equal" or "DIFFERS" and
# exits 1 when any differs or is missing. A whole set takes about a minute on
# 2 cores.
set -euo pipefail

if [ "${1:-}" = "--compare" ]; then
  [ $# -eq 3 ] || { echo "usage: $0 --compare DIR_A DIR_B" >&2; exit 2; }
  a=$2 b=$3 status=0 n=0
  for f in "$a"/*.exr; do
    [ -e "$f" ] || { echo "error: no renders in $a" >&2; exit 2; }
    name=$(basename "$f")
    n=$((n + 1))
    if [ ! -f "$b/$name" ]; then echo "missing  $name"; status=1
    elif idiff -q -fail 0 -warn 0 "$f" "$b/$name" >/dev/null 2>&1; then echo "equal    $name"
    else echo "DIFFERS  $name"; status=1; fi
  done
  [ $status -eq 0 ] && echo "render_baseline: all $n renders bitwise equal" || echo "render_baseline: differences above"
  exit $status
fi

case "${1:-}" in -h|--help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;; esac
[ $# -eq 2 ] || { echo "usage: $0 BIN_DIR OUT_DIR (or --compare DIR_A DIR_B; see --help)" >&2; exit 2; }
bin=$1 out=$2
[ -x "$bin/tessera-render" ] || { echo "error: $bin/tessera-render not found (build first)" >&2; exit 2; }
mkdir -p "$out"

count=0
render() {  # NAME SCENE ARGS...
  local name=$1 scene=$2
  shift 2
  count=$((count + 1))
  echo "render_baseline: $count $name" >&2
  "$bin/tessera-render" "$scene" --size 96x96 --quiet --output "$out/$name.exr" "$@" >/dev/null
}

cornell=builtin:cornell
for filter in none pixel atrous radiance hybrid denoise; do
  render "embree-$filter" $cornell --spp 8 --filter "$filter"
done
render embree-sobol-independent $cornell --spp 4 --param sampler=independent
render embree-whitted $cornell --spp 1 --param mode=whitted
render embree-lens $cornell --spp 4 --aperture 20 --focus-distance 800
render embree-fog builtin:cornell-fog --spp 4
render embree-motion builtin:animated --spp 4 --shutter 0,0.5
render embree-instances builtin:instances:50 --spp 2
render vulkan $cornell --backend vulkan
render vulkan-fog builtin:cornell-fog --backend vulkan
render vulkan-instances builtin:instances:50 --backend vulkan
render coverage $cornell --backend coverage
render vulkan-plant builtin:plant:20000 --backend vulkan --param visibility=guided
# Sequences: three frames each (NAME.0001.exr ...), temporal PCA and photons.
render "pca.####" builtin:animated --frames 3 --temporal pca --spp 4
render "photons.####" builtin:animated --frames 3 --temporal photons --spp 4 --photon-frames 3
echo "render_baseline: $count renders in $out" >&2
