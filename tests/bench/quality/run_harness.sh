#!/usr/bin/env bash
# Runs one quality harness (filter_quality, sampling_quality) over the scene
# suite (suite/make_suite.py, written into the cache) and builtin:cornell.
#
#   tests/bench/quality/run_harness.sh HARNESS BUILD_BIN_DIR [HARNESS options...]
#
# References are cached in build/quality-cache (override with --cache DIR),
# shared by the harnesses and never recomputed; the first run renders them
# (about a minute a scene on 2 cores). The tables are printed and written
# to build/quality-cache/HARNESS.md unless --out is given.
set -euo pipefail
harness=${1:-}
if [[ $# -lt 2 || ! -x "$2/$harness" ]]; then
  echo "usage: $0 HARNESS BUILD_BIN_DIR [HARNESS options]  (BUILD_BIN_DIR holds HARNESS)" >&2
  exit 2
fi
bin=$(cd "$2" && pwd)
shift 2
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
have --out || args+=(--out "$cache/$harness.md")
exec "$bin/$harness" "${args[@]}"
