#!/usr/bin/env bash
# What README command 1 (scripts/main.sh) runs: start two render nodes on loopback, path trace
# builtin:cornell cooperatively on them, write the image, stop the nodes.
#   scripts/cluster-demo.sh [OUTPUT.png [WxH [extra tessera-render options]]]
# BUILD selects the build folder (default build/default).
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${BUILD:-build/default}/bin"
output="${1:-cornell-cluster.png}"
size="${2:-512x512}"
shift $(( $# < 2 ? $# : 2 ))
for exe in tessera-node tessera-render; do
  [[ -x "$bin/$exe" ]] || { echo "cluster-demo: $bin/$exe not built (cmake --build ${bin%/bin})" >&2; exit 1; }
done

work="$(mktemp -d)"
pids=()
stop_nodes() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap stop_nodes EXIT

# A fresh shared token; the nodes and the client prove it, never send it.
head -c 32 /dev/urandom | od -An -tx1 | tr -d ' \n' > "$work/token"

addresses=()
for i in 1 2; do
  "$bin/tessera-node" --listen 127.0.0.1:0 --token-file "$work/token" --name "node$i" --threads 1 \
    > "$work/node$i.out" 2> "$work/node$i.log" &
  pids+=("$!")
  line=""
  for _ in $(seq 100); do  # the first stdout line is "listening on HOST:PORT"
    line="$(head -n 1 "$work/node$i.out" 2>/dev/null || true)"
    [[ "$line" == "listening on "* ]] && break
    sleep 0.05
  done
  [[ "$line" == "listening on "* ]] || { echo "cluster-demo: node$i did not start:" >&2; cat "$work/node$i.log" >&2; exit 1; }
  addresses+=("${line#listening on }")
done
echo "nodes: ${addresses[*]}"

"$bin/tessera-render" builtin:cornell --cluster configs/cooperative-2.json \
  --nodes "$(IFS=,; echo "${addresses[*]}")" --token-file "$work/token" \
  --size "$size" --output "$output" "$@"
