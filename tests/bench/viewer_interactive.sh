#!/usr/bin/env bash
# tessera-viewer's interactive budget (issue 29), with the default preview
# filter (pixel) of the path-traced viewport:
#  - seconds from a camera move to the first filtered preview (2 samples:
#    the pixel filter's first step), and
#  - progressive frames per second after it (one pass of one sample a frame).
# Timed by the viewer's own script: screenshots written just before the
# move, at the first preview and FRAMES frames later; their modification
# times are the clock (writing one costs the same in every run), so any
# viewer binary, an older one included, is measured the same way. Medians
# over ROUNDS runs under xvfb-run (lavapipe presents the swapchain).
#   tests/bench/viewer_interactive.sh [build/default/bin] [rounds] [size] [scene] [viewer options ...]
# e.g. with figure 5.6's chain: ... build/default/bin 3 1280x720 builtin:cornell --raster-while-moving
set -euo pipefail
bin=${1:-build/default/bin}
rounds=${2:-3}
size=${3:-1280x720}
scene=${4:-builtin:cornell}
shift $(($# < 4 ? $# : 4))
frames=4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/script.txt" <<EOF
wait samples 2
screenshot $work/before.png
orbit 10
wait samples 2
screenshot $work/first.png
wait samples $((2 + frames))
screenshot $work/later.png
EOF

: >"$work/rounds"
for round in $(seq "$rounds"); do
  rm -f "$work"/*.png
  xvfb-run -a "$bin/tessera-viewer" "$scene" --size "$size" --script "$work/script.txt" --exit-after "$@" \
    >"$work/log" 2>&1 || { echo "tessera-viewer failed:" >&2; tail -5 "$work/log" >&2; exit 1; }
  echo "$(stat -c %.9Y "$work/before.png") $(stat -c %.9Y "$work/first.png") $(stat -c %.9Y "$work/later.png")" \
    >>"$work/rounds"
done
python3 - "$work/rounds" "$frames" "$size" "$scene" "$*" <<'PY'
import statistics, sys
rows = [list(map(float, l.split())) for l in open(sys.argv[1])]
frames = int(sys.argv[2])
first = statistics.median(r[1] - r[0] for r in rows)
fps = statistics.median(frames / (r[2] - r[1]) for r in rows)
print(f"{sys.argv[4]} {sys.argv[3]} {sys.argv[5] or '(defaults)'}: first filtered preview {first:.2f} s after the move, "
      f"progressive {fps:.2f} frames/s (medians of {len(rows)})")
PY
