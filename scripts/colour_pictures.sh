#!/usr/bin/env bash
# Regenerates docs/images/colour/: each high-contrast photo rendered zoomed out 16x by a model of
# data (the average of encoded values, what every model did before colour spaces), by a srgb
# model (the expectation of decoded colour, docs/design.md §14) and by the srgb model
# supersampled 8x8 (the average of linear light the zoomed-out render should show), texton and
# tiling, 128x128 each, seed 5. The exemplars are MIT (data/exemplars/ATTRIBUTION.md), because the
# outputs are committed.
# Usage: bash scripts/colour_pictures.sh [build-dir]
set -euo pipefail
gallery=colour
source "$(dirname "$0")/gallery_common.sh"
render=(--size 128x128 --scale 16 --seed 5)
for name in nuts_grey_256 water_caustics_256; do
  for method in texton tiling; do
    "$stochtex" analyze "$textures/$name.png" -m "$method" --colour-space srgb \
      -o "$work/$method.stx" 2>/dev/null
    "$stochtex" render "$work/$method.stx" "${render[@]}" --colour-space data \
      -o "$out/${name}_${method}_data.png" 2>/dev/null
    "$stochtex" render "$work/$method.stx" "${render[@]}" \
      -o "$out/${name}_${method}_srgb.png" 2>/dev/null
    "$stochtex" render "$work/$method.stx" "${render[@]}" --supersample 8 \
      -o "$out/${name}_${method}_supersampled.png" 2>/dev/null
  done
done
echo "wrote $out"
