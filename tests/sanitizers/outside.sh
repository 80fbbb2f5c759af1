#!/bin/sh
# The asan test preset preloads the ASan runtime (and lavapipe) into every
# process a test starts. Programs we do not own (xvfb-run with its Xvfb and
# xauth, bash, cmake, cpack, mpirun) then fail on their own leaks, so tests
# start them through this script:
#
#   outside.sh COMMAND...         COMMAND and its children without the preload
#   outside.sh --ours COMMAND...  our binary, started by such a program, with
#                                 the preload back (lavapipe's leaks keep their name)
#
# Our binaries carry the sanitizer runtime themselves; only the ones that
# load lavapipe need the preload. Non-asan builds do not use this script.
if [ "${1:-}" = --ours ]; then
  shift
  [ -n "${TSR_OUTSIDE_PRELOAD:-}" ] && export LD_PRELOAD="$TSR_OUTSIDE_PRELOAD"
  exec "$@"
fi
export TSR_OUTSIDE_PRELOAD="${LD_PRELOAD:-}"
unset LD_PRELOAD
exec "$@"
