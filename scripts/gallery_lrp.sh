#!/usr/bin/env bash
# Regenerates the picture gallery of docs/methods/lrp.md: for each exemplar, the exemplar, its
# Gaussian version (ADSN), the structure-preserving result (r = 0.3 with
# turbulence and random placement, section 5) and the r sweep r = 0, 0.1, 0.2, 0.3, 1 with fixed
# phases alone (no turbulence or placement, so the kept structure sits where it is in the
# exemplar); then continuous targets (a ring and an anisotropic Gaussian, figure 10), from the
# shipped exemplars; all images are 256x256.
# Usage: bash scripts/gallery_lrp.sh [build-dir]
set -euo pipefail
gallery=lrp
source "$(dirname "$0")/gallery_common.sh"

size=(--size 256x256 --seed 1)
for name in wool_knit_blue_256 nuts_grey_256 wood_planks_256; do
  exemplar="$textures/$name.png"
  cp "$exemplar" "$out/${name}_exemplar.png"
  "$stochtex" gaussian "$exemplar" -o "$out/${name}_gaussian.png" "${size[@]}"
  "$stochtex" synth "$exemplar" --method lrp -p ratio=0.3 -p turbulence=2 -p placement=1 \
    -o "$out/${name}_structure.png" "${size[@]}"
  for ratio in 0 0.1 0.2 0.3 1; do
    "$stochtex" synth "$exemplar" --method lrp -p ratio=$ratio -p placement=0 \
      -o "$out/${name}_r${ratio}.png" "${size[@]}"
  done
done

"$stochtex" analyze --method lrp --target ring:radius=0.2,width=0.02 -p cosines=5 -p strata=1 \
  -o "$work/ring.stx"
"$stochtex" render "$work/ring.stx" -o "$out/ring_target.png" "${size[@]}"
"$stochtex" analyze --method lrp --target gaussian:cx=0.08,cy=0.04,along=0.01,across=0.03 \
  -o "$work/gaussian.stx"
"$stochtex" render "$work/gaussian.stx" -o "$out/gaussian_target.png" "${size[@]}"
echo "gallery written to $out"
