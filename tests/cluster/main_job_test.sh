#!/usr/bin/env bash
# README command 1's job (scripts/main.sh after the build): two loopback
# nodes path-trace builtin:cornell cooperatively, unfiltered and filtered.
# A newcomer's first command must not warn of a fault that is not there:
# fails on a non-zero exit or any warning line (a node called late).
#   main_job_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
cd "$2"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for filter in default pixel; do  # as scripts/main.sh: as it is, then --filter pixel
  extra=()
  [[ $filter == default ]] || extra=(--filter "$filter")
  BUILD="$build" bash scripts/cluster-demo.sh "$out/cornell-$filter.png" 512x512 --spp 8 "${extra[@]}" \
    > "$out/log" 2>&1 || { cat "$out/log"; echo "main_job_test: the cluster demo failed" >&2; exit 1; }
  cat "$out/log"
  if grep -qi "warning\|is late" "$out/log"; then
    echo "main_job_test: the main job warned (--filter $filter)" >&2
    exit 1
  fi
  [[ -s "$out/cornell-$filter.png" ]] || { echo "main_job_test: no image written" >&2; exit 1; }
done
