#!/usr/bin/env bash
# Path tracer throughput against Embree's own tutorial path tracer on the
# same Cornell box (plain, and with a ~1M-triangle sphere): same size, spp
# and path length. Prints rays/s of both and their ratio (ours / Embree's),
# and seconds per sample per pixel of both and their ratio (Embree's / ours:
# above 1 means we are faster). Both sides exclude loading the scene and
# building its acceleration structures (Embree's --benchmark times
# device_render only; ours reports render_seconds apart from sync_seconds).
#
# The machine is shared and noisy, so the two renderers run alternately for
# ROUNDS rounds, in ABBA order, and each column is the median over rounds;
# the ratios are medians of the per-round ratios (each round's pair ran back
# to back).
#   tests/bench/compare_pathtracer.sh [build/default/bin] [spp] [rounds] [size]
# (issue 29's table: tests/bench/compare_pathtracer.sh build/default/bin 32 5 256)
set -euo pipefail
bin=${1:-build/default/bin}
spp=${2:-16}
rounds=${3:-5}
size=${4:-512}
here=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
command -v pathtracer >/dev/null || { echo "pathtracer missing: apt-get install embree-tools" >&2; exit 2; }

printf '%-8s %14s %14s %8s %12s %12s %8s\n' scene "embree Mray/s" "tessera Mray/s" ratio "embree s/spp" "tessera s/spp" ratio
for variant in plain heavy; do
  extra=(); [ "$variant" = heavy ] && extra=(--sphere-tris 1000000)
  python3 "$here/tests/bench/scenes/make_cornell.py" "$work/$variant" "${extra[@]}" >/dev/null
  : >"$work/rounds"
  for round in $(seq "$rounds"); do
    run_ref() {
      ref=$(cd "$work" && pathtracer -c "$work/$variant/cornell.ecs" --size "$size" "$size" --spp "$spp" --max-path-length 8 \
              --benchmark 1 4 -o "$work/ref.pfm" 2>&1)
    }
    run_ours() {
      "$bin/tessera-render" "$work/$variant/cornell.gltf" --size "${size}x${size}" --spp "$spp" --max-depth 8 --quiet \
          --output "$work/ours.exr" --stats-json "$work/ours.json"
    }
    # Which renderer goes first alternates (ABBA): on this machine the first
    # of two back-to-back runs tends to be a little faster.
    if ((round % 2)); then run_ref; run_ours; else run_ours; run_ref; fi
    ref_mrays=$(sed -n 's/^BENCHMARK_RENDER_MRAYPS_AVG //p' <<<"$ref")
    # Embree's benchmark reports frames per second; a frame is --spp samples per pixel.
    ref_fps=$(sed -n 's/^BENCHMARK_RENDER_AVG //p' <<<"$ref")
    python3 -c "import json;d=json.load(open('$work/ours.json'));print($ref_mrays, 1.0/($ref_fps*$spp), d['rays_per_second']/1e6, d['render_seconds']/d['spp'])" >>"$work/rounds"
  done
  python3 - "$variant" "$work/rounds" <<'PY'
import statistics, sys
rows = [list(map(float, l.split())) for l in open(sys.argv[2])]
med = lambda xs: statistics.median(xs)
ref_m, ref_s, our_m, our_s = (med([r[i] for r in rows]) for i in range(4))
ratio = med([r[2] / r[0] for r in rows])
spp_ratio = med([r[1] / r[3] for r in rows])
print(f"{sys.argv[1]:<8} {ref_m:14.2f} {our_m:14.2f} {ratio:8.3f} {ref_s:12.4f} {our_s:12.4f} {spp_ratio:8.3f}")
PY
done
