#!/usr/bin/env bash
# The long soak of issue 17: four loopback tessera-node processes,
# builtin:animated in each cluster mode (10,000 frames each by default), a
# replica hash check every 100 frames, node RSS and descriptor counts at
# start and end, and every fault injected once per mode (node killed and
# restarted, SIGSTOP past the dead-node timeout, connection cut mid-snapshot,
# a second client killed mid-frame, a slow link through a throttling proxy,
# garbage peers). Prints per fault what was lost and how long recovery took.
#
#   scripts/soak.sh [--preset default|asan|tsan] [tsr_soak options...]
#   scripts/soak.sh --frames 2000 --modes cooperative
#
# Bounds checked (exit 1 when broken): 0 divergent replicas, 0 failed
# frames, every fault recovered, median frame time under garbage peers at
# most --max-slowdown (3x) the baseline, node RSS growth at most
# --max-rss-growth-mib (32 MiB), no descriptor growth.
set -euo pipefail
cd "$(dirname "$0")/.."
preset=default
if [ "${1:-}" = "--preset" ]; then
  [ $# -ge 2 ] || { echo "error: --preset needs a name" >&2; exit 2; }
  preset=$2
  shift 2
fi
bin=build/$preset/bin
if [ ! -x "$bin/tsr_soak" ] || [ ! -x "$bin/tessera-node" ] || [ ! -x "$bin/tessera-render" ]; then
  echo "soak: building tsr_soak, tessera-node and tessera-render ($preset preset)" >&2
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" --target tsr_soak tessera-node tessera-render
fi
exec "$bin/tsr_soak" --render-binary "$bin/tessera-render" "$@"
