#!/usr/bin/env bash
# Sets everything up on a fresh Debian 12 machine (as root) and runs every
# test: the full suite, then the scene graph (and the wire codec's fuzz
# inputs) under ASan+UBSan and its concurrency test under TSan, the asan-ci
# and tsan-ci presets (docs/fuzzing-and-sanitizers.md: scripts/sanitize.sh builds
# every layer under both and runs the whole suite), then every fuzz target
# over its kept inputs plus a few mutations
# (the clang fuzz build takes about 1.5 min on 2 cores). First of all, the
# whole tree must match .clang-format (half a minute, no build needed).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/check-style.sh --format
jobs=$(nproc)

cmake --preset default
cmake --build --preset default -j"$jobs"
ctest --preset default -j"$jobs"

cmake --preset asan-ci
cmake --build --preset asan-ci -j"$jobs"
ctest --preset asan-ci -j"$jobs"

cmake --preset tsan-ci
cmake --build --preset tsan-ci -j"$jobs"
ctest --preset tsan-ci -j"$jobs"

bash scripts/fuzz.sh all -runs=2000
