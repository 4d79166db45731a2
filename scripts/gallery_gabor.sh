#!/usr/bin/env bash
# Regenerates the picture gallery of docs/methods/gabor.md: for each exemplar, the exemplar, its
# Gaussian version (ADSN), the Gabor noise by example and the fitted power spectrum (the model's
# `spectrum` preview: fourth root of eq. (6), DC centred, synthesis channels as R, G, B). Then the
# filtering row (zoomed out 8x: filtered, point-sampled, supersampled 16x16). Only MIT/CC0 corpus
# images are used, because the outputs are committed. Usage: bash scripts/gallery_gabor.sh [build]
set -euo pipefail
gallery=gabor
source "$(dirname "$0")/gallery_common.sh"

for name in grass_lawn_256 brushed_aluminium_grey_256 concrete_cement_512 sand_height_grey_512 \
  bricks_stone_wall_512; do
  exemplar="$textures/$name.png"
  cp "$exemplar" "$out/${name}_exemplar.png"
  "$stochtex" gaussian "$exemplar" -o "$out/${name}_gaussian.png" --size 256x256 --seed 1
  "$stochtex" analyze "$exemplar" --method gabor -o "$work/$name.stx"
  "$stochtex" info "$work/$name.stx" --export "$work" >/dev/null
  cp "$work/spectrum.png" "$out/${name}_spectrum.png"
  "$stochtex" render "$work/$name.stx" -o "$out/${name}_noise.png" --size 256x256 --seed 1
done

model="$work/grass_lawn_256.stx"
gallery_filtering_row "$model" 128x128
echo "gallery written to $out"
