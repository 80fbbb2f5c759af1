#!/usr/bin/env bash
# The client's per-frame cost of a display wall against its node count:
# walls of N tessera-node processes on loopback (tiny screens, 32x24 unless --tile, a cheap
# back-end so rendering is not what is measured) played by tessera-wall.
# Reports per frame: wall-clock time, the client's CPU time, time assembling tiles, the barrier's
# spread (first to last node done), bytes sent and received, and each as a
# ratio to the smallest wall.
#
# With --pixels-back every frame's pixels also travel to the client (a
# preview); by default they stay on the nodes, which present them.
#
#   tests/bench/cluster/wall_scale.sh [--build DIR] [--counts "4 16 32"] [--backend coverage|vulkan] [--frames N]
#                                     [--tile WxH] [--pixels-back]
set -euo pipefail

build=build/default counts="4 16 32" backend=coverage frames=60 tile=32x24 back=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --counts) counts=$2; shift 2 ;;
    --backend) backend=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --tile) tile=$2; shift 2 ;;
    --pixels-back) back=--pixels-back; shift ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "error: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
node=$build/bin/tessera-node wall=$build/bin/tessera-wall
for b in "$node" "$wall"; do [[ -x $b ]] || { echo "error: $b not built" >&2; exit 2; }; done

work=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

start_nodes() {  # N -> addresses in $work/addresses
  local n=$1 i addresses=""
  for ((i = 0; i < n; ++i)); do
    "$node" --listen 127.0.0.1:0 --name "n$i" --threads 1 --log-level error > "$work/node$i.out" 2> /dev/null &
    pids+=($!)
  done
  for ((i = 0; i < n; ++i)); do
    for _ in $(seq 200); do grep -q "listening on" "$work/node$i.out" 2>/dev/null && break; sleep 0.05; done
    addresses+="${addresses:+,}$(sed -n 's/^listening on //p' "$work/node$i.out")"
  done
  echo "$addresses" > "$work/addresses"
}

stop_nodes() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  pids=()
}

printf "%6s %8s %10s %12s %12s %12s %12s %14s\n" nodes grid "ms/frame" "client CPU ms" "assemble ms" "barrier ms" "sent B" "received B"
base=""
for n in $counts; do
  columns=$(awk -v n="$n" 'BEGIN { c = int(sqrt(n)); while (n % c) --c; print n / c }')
  rows=$((n / columns))
  nodes_json=$(for ((i = 0; i < n; ++i)); do printf '%s{"address": "127.0.0.1:1"}' "$([[ $i -gt 0 ]] && echo ,)"; done)
  cat > "$work/wall.json" <<JSON
{"mode": "tiled", "backend": "$backend", "parameters": {"threads": 1}, "nodes": [$nodes_json],
 "wall": {"columns": $columns, "rows": $rows}, "timeouts": {"connectMs": 10000}}
JSON
  start_nodes "$n"
  # The client's own CPU (user + system, scene loading and the first frame included) per frame.
  TIMEFORMAT="%U %S"
  { time "$wall" "$work/wall.json" builtin:animated --nodes "$(cat "$work/addresses")" --frames "$frames" \
      --size $((columns * ${tile%x*}))x$((rows * ${tile#*x})) --status-every 1000 $back > "$work/wall.out"; } 2> "$work/time"
  line=$(grep "client per frame" "$work/wall.out")
  cpu=$(tail -1 "$work/time" | awk -v f="$frames" '{ printf "%.3f", 1000 * ($1 + $2) / f }')
  stop_nodes
  read -r ms assemble barrier sent received < <(echo "$line" |
    sed -E 's/.*: ([0-9.]+) ms in all, ([0-9.]+) ms assembling tiles, ([0-9.]+) ms barrier spread, ([0-9.]+) bytes sent, ([0-9.]+) bytes received/\1 \2 \3 \4 \5/')
  printf "%6s %8s %10.3f %12s %12.4f %12.3f %12.0f %14.0f\n" "$n" "${columns}x$rows" "$ms" "$cpu" "$assemble" "$barrier" "$sent" "$received"
  if [[ -z $base ]]; then base="$n $ms $assemble $barrier $sent $received"; fi
  echo "$n $ms $assemble $barrier $sent $received" >> "$work/rows"
done

echo
echo "ratios to the $(echo "$base" | cut -d' ' -f1)-node wall (nodes, ms/frame, assemble, barrier, sent, received):"
read -r bn bms bas bba bse bre <<< "$base"
while read -r n ms as ba se re; do
  awk -v n="$n" -v bn="$bn" -v a="$ms" -v b="$bms" -v c="$as" -v d="$bas" -v e="$ba" -v f="$bba" -v g="$se" -v h="$bse" -v i="$re" -v j="$bre" \
    'function r(x, y) { return y > 0 ? x / y : 0 } BEGIN { printf "  %5.1fx nodes: %6.2fx %6.2fx %6.2fx %6.2fx %6.2fx\n", n / bn, r(a, b), r(c, d), r(e, f), r(g, h), r(i, j) }'
done < "$work/rows"
