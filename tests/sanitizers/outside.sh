#!/bin/sh
# The sanitizer test presets preload libraries into every process a test
# starts: asan the ASan runtime and lavapipe, tsan lavapipe (both so that
# lavapipe stays loaded after vkDestroyInstance: its leaks keep their name
# for LeakSanitizer, and TSan dies when a library matched by a
# called_from_lib suppression is unloaded). Programs we do not own
# (xvfb-run with its Xvfb and xauth, bash, cmake, cpack, mpirun) fail on
# their own leaks with the ASan runtime and have no use for lavapipe, so
# tests start them through this script:
#
#   outside.sh COMMAND...         COMMAND and its children without the preload
#   outside.sh --ours COMMAND...  our binary, started by such a program, with
#                                 the preload back
#
# Our binaries carry the sanitizer runtime themselves; only the ones that
# load lavapipe need the preload. Builds without sanitizers do not use this script.
if [ "${1:-}" = --ours ]; then
  shift
  [ -n "${TSR_OUTSIDE_PRELOAD:-}" ] && export LD_PRELOAD="$TSR_OUTSIDE_PRELOAD"
  exec "$@"
fi
export TSR_OUTSIDE_PRELOAD="${LD_PRELOAD:-}"
unset LD_PRELOAD
exec "$@"
