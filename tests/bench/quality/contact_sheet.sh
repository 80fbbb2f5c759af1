#!/usr/bin/env bash
# A contact sheet of the quality suite from filter_quality --png DIR: one
# row a scene, columns unfiltered 8 spp, each filter at 8 spp, unfiltered
# 256 spp, reference. Needs ImageMagick (montage) and the DejaVu font.
#
#   tests/bench/quality/contact_sheet.sh PNG_DIR OUT.png [FILTER ...]
set -euo pipefail
if [[ $# -lt 2 || ! -d "$1" ]]; then
  echo "usage: $0 PNG_DIR OUT.png [FILTER ...]  (PNG_DIR: filter_quality --png's folder)" >&2
  exit 2
fi
dir=$1 out=$2
shift 2
filters=("$@")
[[ ${#filters[@]} -gt 0 ]] || filters=(pixel atrous radiance hybrid)
command -v montage > /dev/null || { echo "$0: montage (ImageMagick) not found" >&2; exit 1; }
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
[[ -f "$font" ]] || { echo "$0: $font not found (Debian package fonts-dejavu-core)" >&2; exit 1; }

columns=(none_8spp)
for f in "${filters[@]}"; do columns+=("${f}_8spp"); done
columns+=(none_256spp reference)
args=()
rows=0
for ref in "$dir"/*_reference.png; do
  key=$(basename "$ref" _reference.png)
  for c in "${columns[@]}"; do
    file="$dir/${key}_${c}.png"
    [[ -f "$file" ]] || { echo "$0: $file missing" >&2; exit 1; }
    args+=(-label "$key ${c%_8spp}" "$file")
  done
  rows=$((rows + 1))
done
[[ $rows -gt 0 ]] || { echo "$0: no *_reference.png in $dir" >&2; exit 1; }
montage -font "$font" -pointsize 9 "${args[@]}" -tile "${#columns[@]}x$rows" -geometry +2+2 -background white -depth 8 "$out"
echo "wrote $out ($rows scenes x ${#columns[@]} columns)"
