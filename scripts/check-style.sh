#!/usr/bin/env bash
# Checks C++ against .clang-format and .clang-tidy.
#
#   scripts/check-style.sh [BASE] [--build DIR] [--jobs N]
#   scripts/check-style.sh --all [--build DIR] [--jobs N]
#   scripts/check-style.sh --format
#
# BASE is the git ref the change is measured from (default: origin/main if
# it exists, else HEAD~1); the working tree's edits count too. clang-format
# runs as a dry run with --Werror over the changed lines only, so untouched
# code is not blamed before the tree is formatted in one commit. clang-tidy
# runs over each changed .cpp and each .cpp that includes a changed header,
# reporting findings in the changed files. --all checks every tracked C++ file
# with clang-format and every translation unit of our code with clang-tidy
# (findings in our headers count once). Compile commands come from DIR
# (default build/default; configure it first: the default preset exports
# compile_commands.json). --jobs runs that many clang-tidy processes (default 2).
# --format checks only clang-format, over every tracked C++ file, and needs no
# build: the test command runs it so the whole tree stays formatted.
# Exit 0: clean; 1: findings; 2: usage error.
set -euo pipefail
cd "$(dirname "$0")/.."

base=""
build=build/default
all=0
format_only=0
jobs=2
while [ $# -gt 0 ]; do
  case "$1" in
    --build) [ $# -ge 2 ] || { echo "error: --build needs a directory" >&2; exit 2; }; build=$2; shift 2 ;;
    --jobs)
      [ $# -ge 2 ] && [[ "$2" =~ ^[1-9][0-9]*$ ]] || { echo "error: --jobs needs a positive count" >&2; exit 2; }
      jobs=$2; shift 2 ;;
    --all) all=1; shift ;;
    --format) format_only=1; shift ;;
    -h|--help) sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "error: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) [ -z "$base" ] || { echo "error: one BASE only, got '$base' and '$1'" >&2; exit 2; }; base=$1; shift ;;
  esac
done
[ $all -eq 0 ] || [ -z "$base" ] || { echo "error: --all takes no BASE (got '$base')" >&2; exit 2; }

# Whole-tree clang-format, nothing else.
if [ $format_only -eq 1 ]; then
  [ $all -eq 0 ] && [ -z "$base" ] || { echo "error: --format takes neither BASE nor --all" >&2; exit 2; }
  command -v clang-format >/dev/null || { echo "error: clang-format not found (scripts/install-deps.sh installs it)" >&2; exit 2; }
  mapfile -t files < <(git ls-files -- '*.cpp' '*.hpp' '*.h')
  unformatted=()
  for f in "${files[@]}"; do
    clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || unformatted+=("$f")
  done
  echo "check-style: clang-format: ${#unformatted[@]} of ${#files[@]} file(s) differ from .clang-format"
  [ ${#unformatted[@]} -eq 0 ] && exit 0
  for f in "${unformatted[@]}"; do echo "  $f (fix: clang-format -i $f)"; done
  exit 1
fi
if [ $all -eq 0 ] && [ -z "$base" ]; then
  if git rev-parse -q --verify origin/main >/dev/null; then base=origin/main; else base=HEAD~1; fi
fi
[ $all -eq 1 ] || git rev-parse -q --verify "$base^{commit}" >/dev/null ||
  { echo "error: '$base' is not a git commit" >&2; exit 2; }
for tool in clang-format clang-tidy; do
  command -v "$tool" >/dev/null || { echo "error: $tool not found (scripts/install-deps.sh installs it)" >&2; exit 2; }
done
if [ ! -f "$build/compile_commands.json" ]; then
  echo "error: $build/compile_commands.json missing: configure first (cmake --preset default)" >&2
  exit 2
fi
status=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Runs clang-tidy over the units in $tmp/units, $jobs at a time, each unit's
# output into its own file (progress on stderr); extra arguments go to
# clang-tidy. Prints the findings, each once (a header's finding shows in
# every unit that includes it), and sets $findings.
run_tidy() {
  mkdir -p "$tmp/out"
  local total
  total=$(wc -l <"$tmp/units")
  # shellcheck disable=SC2016
  xargs -a "$tmp/units" -d '\n' -P "$jobs" -I{} bash -c \
    'tmp=$1 build=$2 total=$3; shift 3; u=${!#}
     clang-tidy -p "$build" --quiet "$@" >"$tmp/out/${u//\//_}.log" 2>/dev/null || true
     echo "check-style: $(find "$tmp/out" -name "*.log" | wc -l)/$total $u" >&2' \
    _ "$tmp" "$build" "$total" "$@" {}
  cat "$tmp"/out/*.log | grep -E '^[^ ]+:[0-9]+:[0-9]+: (warning|error): ' | sort -u >"$tmp/findings" || true
  findings=$(wc -l <"$tmp/findings")
  if [ "$findings" -gt 0 ]; then
    sed "s|^$(pwd)/||" "$tmp/findings"
    echo "check-style: findings per check:"
    sed -n 's/.*\[\([a-z0-9.-]*\)\(,-warnings-as-errors\)\{0,1\}\]$/\1/p' "$tmp/findings" | sort | uniq -c | sort -rn
  fi
}

if [ $all -eq 1 ]; then
  mapfile -t files < <(git ls-files -- '*.cpp' '*.hpp' '*.h')
  unformatted=0
  for f in "${files[@]}"; do
    clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || unformatted=$((unformatted + 1))
  done
  echo "check-style: clang-format: $unformatted of ${#files[@]} file(s) differ from .clang-format"
  [ $unformatted -eq 0 ] || status=1
  # Our units: the compile database's files in the tree, not generated ones
  # under the build directory nor the Dear ImGui examples from /usr.
  python3 - "$build/compile_commands.json" "$(pwd)" >"$tmp/units" <<'PY'
import json, re, sys
root = sys.argv[2] + "/"
ours = re.compile(re.escape(root) + r"(scenegraph|backends|mediators|cluster|apps|tests)/")
for f in sorted({e["file"] for e in json.load(open(sys.argv[1]))}):
    if ours.match(f):
        print(f[len(root):])
PY
  echo "check-style: clang-tidy over $(wc -l <"$tmp/units") translation unit(s), $jobs at a time"
  run_tidy
  echo "check-style: clang-tidy: $findings finding(s)"
  [ "$findings" -eq 0 ] || status=1
  [ $status -eq 0 ] && echo "check-style: clean" || echo "check-style: findings above"
  exit $status
fi

mapfile -t files < <(git diff --name-only --diff-filter=ACMR "$base" -- '*.cpp' '*.hpp' '*.h' | sort -u)
if [ ${#files[@]} -eq 0 ]; then
  echo "check-style: no C++ changed since $base"
  exit 0
fi

# clang-format: the changed line ranges of each file, from a zero-context diff.
formatted=0
for f in "${files[@]}"; do
  mapfile -t ranges < <(git diff -U0 "$base" -- "$f" |
    sed -n 's/^@@ -[0-9,]* +\([0-9]*\)\(,\([0-9]*\)\)\{0,1\} @@.*/\1 \3/p' |
    awk '{n = ($2 == "") ? 1 : $2; if (n > 0) print "--lines=" $1 ":" ($1 + n - 1)}')
  [ ${#ranges[@]} -gt 0 ] || continue
  formatted=$((formatted + 1))
  clang-format --dry-run --Werror "${ranges[@]}" "$f" || status=1
done
echo "check-style: clang-format checked the changed lines of $formatted file(s)"

# clang-tidy: translation units that see a changed file.
units=()
for f in "${files[@]}"; do
  case "$f" in
    *.cpp) units+=("$f") ;;
    *) mapfile -t -O ${#units[@]} units < <(git grep -l --full-name -F "$(basename "$f")\"" -- '*.cpp' | head -n 1 || true) ;;
  esac
done
printf '%s\n' "${units[@]}" | sort -u |
  while read -r u; do grep -q "\"file\": \".*/$u\"" "$build/compile_commands.json" && echo "$u"; done >"$tmp/units" || true
echo "check-style: clang-tidy over $(wc -l <"$tmp/units") translation unit(s)"
# Findings are reported in the changed files only, not in every header or
# unchanged .cpp the units bring in.
lines="[$(for f in "${files[@]}"; do printf '{"name":"%s"},' "$(pwd)/$f"; done | sed 's/,$//')]"
[ ! -s "$tmp/units" ] || run_tidy --header-filter='.*' --line-filter="$lines"
[ "${findings:-0}" -eq 0 ] || status=1
[ $status -eq 0 ] && echo "check-style: clean" || echo "check-style: findings above"
exit $status
