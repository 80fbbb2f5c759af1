#!/usr/bin/env bash
# Runs the filter quality harness on builtin:cornell and on the Cornell box
# of ../shared/scenes/make_cornell.py (diffuse, and with a glossy wall).
#
#   tests/bench/quality/filter_quality.sh BUILD_BIN_DIR [--quick] [filter_quality options...]
#
# References are cached in build/quality-cache (override with --cache DIR)
# and never recomputed; the first run renders them (minutes). The table is
# printed and written to build/quality-cache/filter_quality[_quick].md
# unless --out is given.
set -euo pipefail
if [[ $# -lt 1 || ! -x "$1/filter_quality" ]]; then
  echo "usage: $0 BUILD_BIN_DIR [--quick] [filter_quality options]  (BUILD_BIN_DIR holds filter_quality)" >&2
  exit 2
fi
bin=$(cd "$1" && pwd)
shift
repo=$(cd "$(dirname "$0")/../../.." && pwd)
shared="$repo/../shared"
[[ -f "$shared/scenes/make_cornell.py" ]] || { echo "$0: $shared/scenes/make_cornell.py not found" >&2; exit 1; }

quick=""
args=()
for a in "$@"; do
  if [[ "$a" == "--quick" ]]; then quick=1; fi
  args+=("$a")
done
have() { local o; for o in "${args[@]}"; do [[ "$o" == "$1" || "$o" == "$1="* ]] && return 0; done; return 1; }

cd "$repo"
have --cache || args+=(--cache build/quality-cache)
cache=build/quality-cache
for ((i = 0; i < ${#args[@]}; ++i)); do [[ "${args[$i]}" == "--cache" ]] && cache="${args[$((i + 1))]}"; done
mkdir -p "$cache/scene"
python3 "$shared/scenes/make_cornell.py" "$cache/scene" > /dev/null
have --out || args+=(--out "$cache/filter_quality${quick:+_quick}.md")
exec "$bin/filter_quality" --gltf "$cache/scene/cornell.gltf" "${args[@]}"
