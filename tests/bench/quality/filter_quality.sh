#!/usr/bin/env bash
# Runs the filter quality harness over the scene suite (suite/make_suite.py,
# written into the cache) and builtin:cornell.
#
#   tests/bench/quality/filter_quality.sh BUILD_BIN_DIR [filter_quality options...]
#
# References are cached in build/quality-cache (override with --cache DIR)
# and never recomputed; the first run renders them (about a minute a scene
# on 2 cores). The tables are printed and written to
# build/quality-cache/filter_quality.md unless --out is given.
set -euo pipefail
if [[ $# -lt 1 || ! -x "$1/filter_quality" ]]; then
  echo "usage: $0 BUILD_BIN_DIR [filter_quality options]  (BUILD_BIN_DIR holds filter_quality)" >&2
  exit 2
fi
bin=$(cd "$1" && pwd)
shift
repo=$(cd "$(dirname "$0")/../../.." && pwd)
args=("$@")
have() { local o; for o in "${args[@]}"; do [[ "$o" == "$1" || "$o" == "$1="* ]] && return 0; done; return 1; }

cd "$repo"
cache=build/quality-cache
for ((i = 0; i < ${#args[@]}; ++i)); do [[ "${args[$i]}" == "--cache" ]] && cache="${args[$((i + 1))]}"; done
have --cache || args+=(--cache "$cache")
mkdir -p "$cache/suite"
python3 tests/bench/quality/suite/make_suite.py "$cache/suite" > /dev/null
have --suite || args+=(--suite "$cache/suite")
have --out || args+=(--out "$cache/filter_quality.md")
exec "$bin/filter_quality" "${args[@]}"
