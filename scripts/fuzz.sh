#!/usr/bin/env bash
# Builds the fuzz preset (clang libFuzzer + ASan/UBSan) and runs fuzz targets.
#   scripts/fuzz.sh TARGET|all SECONDS   fuzz each for SECONDS, new inputs kept in build/fuzz/corpus
#   scripts/fuzz.sh TARGET|all -runs=N   regression only: N runs over the kept corpus (what CI does)
# Prints executions and findings per target; a finding's input lands in
# build/fuzz/findings/TARGET/ — fix it, then copy it to
# tests/fuzz/regressions/TARGET/ so the normal test suite replays it.
set -uo pipefail
cd "$(dirname "$0")/.."
targets=(wire_codec cluster_messages pixel_codec gltf_import import_cache cluster_config launch_address_file launch_rank_line
         viewer_script camera_bookmarks anaglyph_script cull_http_request cull_preview_message)
[ $# -eq 2 ] || { echo "usage: scripts/fuzz.sh TARGET|all SECONDS|-runs=N" >&2; exit 2; }
[ "$1" = all ] || targets=("$1")
cmake --preset fuzz > /dev/null && cmake --build build/fuzz -j"${FUZZ_JOBS:-2}" \
  $(printf -- '--target fuzz_%s ' "${targets[@]}") > /dev/null || { echo "fuzz build failed" >&2; exit 2; }

status=0
printf '%-20s %12s %10s %9s\n' target executions exec/s findings
for t in "${targets[@]}"; do
  work=build/fuzz/corpus/$t findings=build/fuzz/findings/$t
  rm -rf "$findings"; mkdir -p "$work" "$findings"
  # libFuzzer adds new inputs to the first folder: the one in build/, never the tree's.
  if [[ $2 == -runs=* ]]; then mode=("$2"); else mode=(-max_total_time="$2"); fi
  dirs=("$work" tests/fuzz/corpus/"$t" tests/fuzz/regressions/"$t")
  existing=(); for d in "${dirs[@]}"; do [ -d "$d" ] && existing+=("$d"); done
  dict=(); [ -f tests/fuzz/dict/"$t".dict ] && dict=(-dict=tests/fuzz/dict/"$t".dict)
  log=build/fuzz/$t.log
  # Bounded: 2 s per input, 2 GB of memory, no single allocation over 256 MB.
  build/fuzz/bin/fuzz_"$t" "${mode[@]}" "${dict[@]}" -timeout=2 -rss_limit_mb=2048 -malloc_limit_mb=256 \
    -max_len=65536 -artifact_prefix="$findings/" -print_final_stats=1 "${existing[@]}" > "$log" 2>&1
  rc=$?
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  speed=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  found=$(find "$findings" -type f | wc -l)
  printf '%-20s %12s %10s %9s\n' "$t" "${execs:-?}" "${speed:-?}" "$found"
  if [ $rc -ne 0 ]; then status=1; grep -m3 -E 'ERROR|SUMMARY|runtime error' "$log" | sed 's/^/    /'; fi
done
exit $status
