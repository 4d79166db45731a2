#!/usr/bin/env bash
# Regenerates the picture gallery of docs/methods/texton.md: for each exemplar, the exemplar, its
# Gaussian version (ADSN), the texton and texton noise; then the filtering row (zoomed out 8x:
# filtered, point-sampled, supersampled 16x16). Only MIT/CC0 corpus images are used, because the
# outputs are committed. Usage: bash scripts/gallery_texton.sh [build-dir]
set -euo pipefail
gallery=texton
source "$(dirname "$0")/gallery_common.sh"

for name in grass_lawn_256 concrete_cement_512 moss_ground_512 sand_height_grey_512 \
  bricks_stone_wall_512; do
  gallery_preview_row "$name" texton texton
done

model="$work/concrete_cement_512.stx"
gallery_filtering_row "$model" 256x256
echo "gallery written to $out"
