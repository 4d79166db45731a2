#!/usr/bin/env bash
# Regenerates the picture gallery of docs/methods/gabor.md: for each exemplar, the exemplar, its
# Gaussian version (ADSN), the Gabor noise by example and the fitted power spectrum (the model's
# `spectrum` preview: fourth root of eq. (6), DC centred, synthesis channels as R, G, B). Then the
# filtering row (zoomed out 8x: filtered, point-sampled, supersampled 16x16), then the editing rows
# (section 8: `stochtex edit` on the automatic groups). Only MIT/CC0 corpus images are used,
# because the outputs are committed. Usage: bash scripts/gallery_gabor.sh [build]
set -euo pipefail
gallery=gabor
source "$(dirname "$0")/gallery_common.sh"

for name in grass_lawn_256 brushed_aluminium_grey_256 concrete_cement_512 sand_height_grey_512 \
  bricks_stone_wall_512; do
  gallery_preview_row "$name" gabor spectrum
done

model="$work/grass_lawn_256.stx"
gallery_filtering_row "$model" 128x128

# Editing (section 8): the plaid's periodic peaks removed, then rotated by 30 degrees, then alone
# (the stochastic rest silenced); the aluminium's anisotropic lines rotated by 90 degrees and
# sharpened (bandwidth halved). Each edited model is rendered like the unedited one (seed 1).
# edit_row NAME TAG EDIT...: writes edit_NAME_TAG.png.
edit_row() {
  local name=$1 tag=$2
  shift 2
  "$stochtex" edit "$work/$name.stx" -o "$work/${name}_$tag.stx" "$@"
  "$stochtex" render "$work/${name}_$tag.stx" -o "$out/edit_${name}_$tag.png" --size 256x256 --seed 1
}
plaid=plaid_fabric_256
"$stochtex" analyze "$textures/$plaid.png" --method gabor -o "$work/$plaid.stx"
cp "$textures/$plaid.png" "$out/${plaid}_exemplar.png"
"$stochtex" render "$work/$plaid.stx" -o "$out/${plaid}_noise.png" --size 256x256 --seed 1
edit_row $plaid no_periodic --group periodic --magnitude 0
edit_row $plaid periodic_rotated --group periodic --rotate 30
edit_row $plaid periodic_only --group stochastic --magnitude 0
aluminium=brushed_aluminium_grey_256
edit_row $aluminium anisotropic_rotated --group anisotropic --rotate 90
edit_row $aluminium anisotropic_sharper --group anisotropic --bandwidth 0.5
echo "gallery written to $out"
