#!/usr/bin/env bash
# Temporal reprojection on an orbiting camera (builtin:cornell and the
# suite's indirect room and rough metal):
#
#   tests/bench/quality/history_quality.sh BUILD_BIN_DIR [history_quality options...]
#
# (run_harness.sh says where references and tables go).
exec "$(dirname "$0")/run_harness.sh" history_quality "$@"
