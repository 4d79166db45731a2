#!/usr/bin/env bash
# Regenerates docs/comparison.md: runs `stochtex report` on every shipped exemplar (data/exemplars),
# keeps the full HTML report in BUILD/report (not committed: open BUILD/report/index.html), and
# writes the small committed version, the Markdown page with 96-pixel thumbnails under
# docs/images/comparison/ and the measured tables per exemplar and per category.
# Usage: bash scripts/report.sh [build-dir]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
textures="$root/data/exemplars"
report="$build/report"
images="$root/docs/images/comparison"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --parallel --target stochtex
rm -rf "$report" "$images"
"$build/stochtex" report "$textures"/*.png -o "$report" --thumbnail 96
/usr/bin/python3 "$root/scripts/comparison_markdown.py" "$report/report.json" \
  "$textures/ATTRIBUTION.md" "$report/thumbnails" "$images" images/comparison \
  >"$root/docs/comparison.md.tmp"
mv "$root/docs/comparison.md.tmp" "$root/docs/comparison.md"
echo "wrote $root/docs/comparison.md and $images (full report: $report/index.html)"
