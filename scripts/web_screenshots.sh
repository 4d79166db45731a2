#!/usr/bin/env bash
# Regenerates docs/images/studio/*.png: runs the browser tests with --screenshots, which after
# their checks photograph the pages: tests/browser/browser_test.py (every method's model of
# grass_lawn_128 in `stochtex export-web`'s page, 256-pixel canvases, at scale 1 and zoomed out
# 16x, seed 7: export_web*.png) and tests/browser/studio_browser_test.py (the studio after an
# analysis per method, seed 7: studio.png).
# Usage: bash scripts/web_screenshots.sh [build-dir]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --parallel 1 --target stochtex
/usr/bin/python3 "$root/tests/browser/browser_test.py" "$build/stochtex" \
  "$root/data/exemplars/grass_lawn_128.png" --second "$root/data/exemplars/wood_planks_256.png" \
  --screenshots "$root/docs/images/studio"
/usr/bin/python3 "$root/tests/browser/studio_browser_test.py" "$build/stochtex" \
  "$root/data/exemplars/grass_lawn_128.png" --screenshots "$root/docs/images/studio"
