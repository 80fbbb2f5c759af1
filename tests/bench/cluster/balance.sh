#!/usr/bin/env bash
# Cooperative load balancing measured: four tessera-node processes on
# loopback render an animation of a scene whose cost is uneven (a glass
# knot in the top left corner, uneven_scene.py), one node slowed: node 3
# renders with one thread (the others with two) and runs under `nice -n
# --nice` (default 5), so on a machine whose cores are all busy it gets
# about a third of the CPU the others get (thread count alone changes little
# there). The animation is rendered twice, with the balancer off (tolerance
# 1000: tiles stay where the first frame put them, contiguous runs of rows)
# and on (tolerance 0.05, up to --moves tiles a frame); each frame's
# balance (the slowest node's render time over the mean, from
# tessera-render --stats-json) is printed side by side.
#
#   tests/bench/cluster/balance.sh [--build DIR] [--frames N] [--size WxH] [--spp N] [--tile PX]
#                                  [--moves N] [--nice N] [--floor] [--out DIR]
# --out keeps the statistics and every frame with its workload image
# (off.NNNN.png, off.NNNN.workload.png, on.*); default: a temporary folder.
set -euo pipefail

build=build/default frames=12 size=320x240 spp=8 tile=32 moves=8 nice=5 floor="" out=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --spp) spp=$2; shift 2 ;;
    --tile) tile=$2; shift 2 ;;
    --moves) moves=$2; shift 2 ;;
    --nice) nice=$2; shift 2 ;;
    --floor) floor=--floor; shift ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "error: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
node=$build/bin/tessera-node render=$build/bin/tessera-render
for b in "$node" "$render"; do [[ -x $b ]] || { echo "error: $b not built" >&2; exit 2; }; done
here=$(cd "$(dirname "$0")" && pwd)

work=$(mktemp -d)
[[ -n $out ]] || out=$work/out
mkdir -p "$out"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

python3 "$here/uneven_scene.py" "$work/uneven.gltf" $floor > /dev/null
addresses=""
for i in 0 1 2 3; do
  slow=(); [[ $i -eq 3 ]] && slow=(nice -n "$nice")
  "${slow[@]}" "$node" --listen 127.0.0.1:0 --name "n$i" --log-level error > "$work/node$i.out" 2> /dev/null &
  pids+=($!)
done
for i in 0 1 2 3; do
  for _ in $(seq 200); do grep -q "listening on" "$work/node$i.out" 2>/dev/null && break; sleep 0.05; done
  addresses+="${addresses:+,}$(sed -n 's/^listening on //p' "$work/node$i.out")"
done

config() {  # NAME TOLERANCE
  cat > "$work/$1.json" <<JSON
{"mode": "cooperative", "backend": "embree",
 "parameters": {"spp": $spp, "maxDepth": 8, "seed": 1, "threads": 2, "filter": "none"},
 "nodes": [{"address": "127.0.0.1:1"}, {"address": "127.0.0.1:1"}, {"address": "127.0.0.1:1"},
           {"address": "127.0.0.1:1", "parameters": {"threads": 1}}],
 "cooperative": {"tileSize": $tile, "tolerance": $2, "maxMovesPerFrame": $moves},
 "timeouts": {"connectMs": 10000}}
JSON
}
config off 1000
config on 0.05

for run in off on; do
  echo "rendering $frames frames, load balancing $run ..." >&2
  "$render" "$work/uneven.gltf" --cluster "$work/$run.json" --nodes "$addresses" --frames "$frames" --fps "$(awk -v f="$frames" 'BEGIN { print f / 2 }')" \
    --size "$size" --aov workload --stats-json "$out/$run.json" --output "$out/$run.####.png" --quiet > /dev/null
done

python3 - "$out/off.json" "$out/on.json" <<'PY'
import json, sys
off, on = (json.load(open(p)) for p in sys.argv[1:3])
print("balance = slowest node's render time / mean of the 4 nodes (1 = even); node 3 slowed (1 thread, nice)")
print("%5s | %11s %9s %-24s | %11s %9s %-24s" % ("frame", "balance off", "frame s", "ms per node (off)",
                                                    "balance on", "frame s", "ms per node (on)"))
for a, b in zip(off["per_frame"], on["per_frame"]):
    ms = lambda f: " ".join("%5.0f" % n["milliseconds"] for n in f["nodes"])
    print("%5d | %11.2f %9.2f %-24s | %11.2f %9.2f %-24s" % (a["frame"], a["balance"], a["seconds"], ms(a),
                                                             b["balance"], b["seconds"], ms(b)))
mean = lambda r: sum(f["balance"] for f in r["per_frame"]) / len(r["per_frame"])
secs = lambda r: sum(f["seconds"] for f in r["per_frame"])
print("mean  | %11.2f %9.2f %-24s | %11.2f %9.2f" % (mean(off), secs(off), "(sum)", mean(on), secs(on)))
tiles = lambda r: " ".join(str(n["tiles"]) for n in r["per_frame"][-1]["nodes"])
print("tiles per node in the last frame: off %s, on %s" % (tiles(off), tiles(on)))
PY
