#!/usr/bin/env bash
# The filter quality harness over the suite and builtin:cornell:
#
#   tests/bench/quality/filter_quality.sh BUILD_BIN_DIR [filter_quality options...]
#
# (run_harness.sh says where references and tables go).
exec "$(dirname "$0")/run_harness.sh" filter_quality "$@"
