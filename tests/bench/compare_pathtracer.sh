#!/usr/bin/env bash
# Path tracer throughput against Embree's own tutorial path tracer on the
# same Cornell box (plain, and with a ~1M-triangle sphere): same size, spp
# and path length. Prints rays/s of both and their ratio (ours / Embree's),
# and seconds per sample per pixel of both and their ratio (Embree's / ours:
# above 1 means we are faster), from one run. Both sides exclude loading the
# scene and building its acceleration structures (Embree's --benchmark times
# device_render only; ours reports render_seconds apart from sync_seconds).
#   tests/bench/compare_pathtracer.sh [build/default/bin] [spp]
set -euo pipefail
bin=${1:-build/default/bin}
spp=${2:-16}
here=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
command -v pathtracer >/dev/null || { echo "pathtracer missing: apt-get install embree-tools" >&2; exit 2; }

printf '%-8s %14s %14s %8s %12s %12s %8s\n' scene "embree Mray/s" "tessera Mray/s" ratio "embree s/spp" "tessera s/spp" ratio
for variant in plain heavy; do
  extra=(); [ "$variant" = heavy ] && extra=(--sphere-tris 1000000)
  python3 "$here/../shared/scenes/make_cornell.py" "$work/$variant" "${extra[@]}" >/dev/null
  ref=$(cd "$work" && pathtracer -c "$work/$variant/cornell.ecs" --size 512 512 --spp "$spp" --max-path-length 8 \
          --benchmark 1 4 -o "$work/ref.pfm" 2>&1)
  ref_mrays=$(sed -n 's/^BENCHMARK_RENDER_MRAYPS_AVG //p' <<<"$ref")
  # Embree's benchmark reports frames per second; a frame is --spp samples per pixel.
  ref_fps=$(sed -n 's/^BENCHMARK_RENDER_AVG //p' <<<"$ref")
  ref_frame=$(python3 -c "print(1.0/($ref_fps*$spp))")
  "$bin/tessera-render" "$work/$variant/cornell.gltf" --size 512x512 --spp "$spp" --max-depth 8 --quiet \
      --output "$work/ours.exr" --stats-json "$work/ours.json"
  ours=$(python3 -c "import json;d=json.load(open('$work/ours.json'));print(d['rays_per_second']/1e6, d['render_seconds']/d['spp'])")
  read -r our_mrays our_spp_s <<<"$ours"
  ratio=$(python3 -c "print(round($our_mrays/$ref_mrays,3))")
  spp_ratio=$(python3 -c "print(round($ref_frame/$our_spp_s,3))")
  printf '%-8s %14.2f %14.2f %8s %12.4f %12.4f %8s\n' "$variant" "$ref_mrays" "$our_mrays" "$ratio" "$ref_frame" "$our_spp_s" "$spp_ratio"
done
