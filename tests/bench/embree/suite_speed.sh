#!/usr/bin/env bash
# Path tracer time per sample on every scene of the quality suite, two
# builds side by side: which is faster, scene by scene, and do they give
# the same image.
#
#   tests/bench/embree/suite_speed.sh BIN_A BIN_B [rounds] [size] [spp]
#   (issue 42's table: tests/bench/embree/suite_speed.sh /tmp/before/bin build/default/bin 4 128 32)
#
# BIN_A and BIN_B are bin/ folders holding tessera-render. Each scene is
# rendered by both, alternating which goes first (ABBA: on this shared
# machine the first of two back-to-back runs tends to be faster), ROUNDS
# times; the table gives the median render_seconds per sample of each and
# the median of the per-round ratios A/B (above 1: B is faster), and whether
# the two images are bitwise equal. The suite's outdoor scene is rendered
# under the default light rig here (tessera-render takes no environment
# map); motion opens the shutter over its 0.1 s frame.
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
a=$1 b=$2 rounds=${3:-4} size=${4:-128} spp=${5:-32}
for bin in "$a" "$b"; do
  [ -x "$bin/tessera-render" ] || { echo "error: $bin/tessera-render is missing" >&2; exit 2; }
done
here=$(cd "$(dirname "$0")/../../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 "$here/tests/bench/quality/suite/make_suite.py" "$work/suite" >/dev/null

scenes=(builtin:cornell)
while read -r file; do scenes+=("$file"); done < <(python3 -c "
import json, os, sys
d = json.load(open(sys.argv[1]))
for s in d['scenes']:
    f = s['file']
    path = f if os.path.isabs(f) else os.path.join(os.path.dirname(sys.argv[1]), f)
    if os.path.exists(path): print(path)
" "$work/suite/suite.json")

render() {  # bin scene out.exr stats.json
  local extra=()
  case "$2" in *motion.gltf) extra=(--shutter 0,1 --fps 10) ;; esac
  # Scenes without lights warn that they get the default rig: kept out of
  # the table, shown when a render fails.
  "$1/tessera-render" "$2" --size "${size}x${size}" --spp "$spp" --quiet --output "$3" --stats-json "$4" \
      "${extra[@]}" 2>"$work/log" || { cat "$work/log" >&2; return 1; }
}
seconds() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(d['render_seconds'] / d['spp'])" "$1"; }

printf '%-20s %12s %12s %8s %s\n' scene "A ms/spp" "B ms/spp" "A/B" image
for scene in "${scenes[@]}"; do
  : >"$work/rounds"
  for round in $(seq "$rounds"); do
    if ((round % 2)); then order="a b"; else order="b a"; fi
    for which in $order; do
      bin=$a; [ "$which" = b ] && bin=$b
      render "$bin" "$scene" "$work/$which.exr" "$work/$which.json"
    done
    echo "$(seconds "$work/a.json") $(seconds "$work/b.json")" >>"$work/rounds"
  done
  same=differs
  idiff -q -fail 0 -warn 0 "$work/a.exr" "$work/b.exr" >/dev/null 2>&1 && same=equal
  python3 - "$(basename "$scene")" "$work/rounds" "$same" <<'PY'
import statistics, sys
rows = [list(map(float, l.split())) for l in open(sys.argv[2])]
a = statistics.median(r[0] for r in rows)
b = statistics.median(r[1] for r in rows)
ratio = statistics.median(r[0] / r[1] for r in rows)
print(f"{sys.argv[1]:<20} {a * 1e3:12.2f} {b * 1e3:12.2f} {ratio:8.3f} {sys.argv[3]}")
PY
done
