#!/usr/bin/env bash
# Sets everything up on a fresh Debian 12 machine (as root) and runs every
# test: the full suite, then the whole suite under ASan+UBSan and the
# named tsan-ci subset under TSan (README "Sanitizers"; scripts/sanitize.sh
# runs the rest), then every fuzz target over its kept inputs plus a few mutations
# (the clang fuzz build takes about 1.5 min on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=$(nproc)

cmake --preset default
cmake --build --preset default -j"$jobs"
ctest --preset default -j"$jobs"

cmake --preset asan
cmake --build --preset asan -j"$jobs"
ctest --preset asan -j"$jobs"

cmake --preset tsan
cmake --build --preset tsan -j"$jobs"
ctest --preset tsan-ci -j"$jobs"

bash scripts/fuzz.sh all -runs=2000
