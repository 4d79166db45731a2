#!/usr/bin/env bash
# Regenerates docs/images/triplanar/: a sphere without texture coordinates, orthographic view,
# textured by tiling's triplanar histogram-preserving blending (left) and linear triplanar mapping
# (right), as figure 16 of the tiling paper (bench/compare/triplanar_sphere.cpp). Only MIT/CC0
# corpus images are used, because the outputs are committed.
# Usage: bash scripts/triplanar_picture.sh [build-dir]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
out="$root/docs/images/triplanar"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --parallel --target stochtex_triplanar_sphere
mkdir -p "$out"
for name in moss_ground_512 metal_grey_256; do
  "$build/bench/stochtex_triplanar_sphere" "$root/data/exemplars/$name.png" "$out/${name}_sphere.png" \
    256 1
done
