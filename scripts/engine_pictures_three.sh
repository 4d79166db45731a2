#!/usr/bin/env bash
# Regenerates docs/images/engines/three.png, the picture of docs/engines.md ("three.js"): runs
# tests/browser/three_test.py with --screenshots, which after its checks renders, in headless
# Chromium (SwiftShader's WebGL2) with three.js from npm, rock_sandstone's albedo (tiling, srgb)
# and normal map (tiling, data) exact web exports as the map and normalMap of one
# MeshStandardMaterial on a ground plane to the horizon (768x432, seed 7; the page's picture()).
# Usage: bash scripts/engine_pictures_three.sh [build-dir]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --parallel 1 --target stochtex
/usr/bin/python3 "$root/tests/browser/three_test.py" "$build/stochtex" "$root" \
  "$build/tests/three_npm" --screenshots "$root/docs/images/engines"
