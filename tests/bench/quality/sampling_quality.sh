#!/usr/bin/env bash
# The sampling quality harness over the suite and builtin:cornell: unfiltered
# error against spp and time, white noise and power-picked emitters
# ("before") beside Sobol samples and the light tree ("after"):
#
#   tests/bench/quality/sampling_quality.sh BUILD_BIN_DIR [sampling_quality options...]
#
# (run_harness.sh says where references and tables go).
exec "$(dirname "$0")/run_harness.sh" sampling_quality "$@"
