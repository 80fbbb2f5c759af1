#!/usr/bin/env bash
# The whole suite under the sanitizers, beyond CI's named subsets:
#
#   scripts/sanitize.sh [asan|tsan|both] [ctest options...]
#
# Builds the preset (Debug, every layer, node processes built with the
# same sanitizer: the cluster tests start build/<preset>/bin/tessera-node)
# and runs every test of it. CI (scripts/test.sh) runs the asan-ci and
# tsan-ci subsets only (see docs/fuzzing-and-sanitizers.md). Runtime options and the
# suppressions of libraries we do not own (tests/sanitizers/*.supp, each
# with its reason) come from the test presets in CMakePresets.json.
set -euo pipefail
cd "$(dirname "$0")/.."
which=${1:-both}
[ $# -gt 0 ] && shift
case "$which" in
  asan) presets=(asan) ;;
  tsan) presets=(tsan) ;;
  both) presets=(asan tsan) ;;
  *) echo "error: expected asan, tsan or both, got '$which'" >&2; exit 2 ;;
esac
jobs=$(nproc)
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
status=0
for p in "${presets[@]}"; do
  echo "sanitize: $p: configure and build" >&2
  start=$(date +%s)
  cmake --preset "$p" "${launcher[@]}" >/dev/null
  cmake --build --preset "$p" -j"$jobs"
  echo "sanitize: $p: built in $(( $(date +%s) - start )) s" >&2
  echo "sanitize: $p: every test" >&2
  start=$(date +%s)
  ctest --preset "$p" -j"$jobs" "$@" || status=1
  echo "sanitize: $p: $(( $(date +%s) - start )) s" >&2
done
exit $status
