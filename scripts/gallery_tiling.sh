#!/usr/bin/env bash
# Regenerates the picture gallery of docs/methods/tiling.md: for each exemplar, the exemplar, its
# Gaussianised version G = T(X) and the tiling noise; then linear, variance-preserving and
# histogram-preserving blending side by side; the two transports; the filtering row (zoomed out
# 8x: filtered, point-sampled, supersampled 16x16). Only MIT/CC0 corpus images are used, because
# the outputs are committed. Usage: bash scripts/gallery_tiling.sh [build-dir]
set -euo pipefail
gallery=tiling
source "$(dirname "$0")/gallery_common.sh"

for name in moss_ground_512 sand_height_grey_512 metal_grey_256 nuts_grey_256 \
  water_caustics_256 bricks_stone_wall_512; do
  exemplar="$textures/$name.png"
  cp "$exemplar" "$out/${name}_exemplar.png"
  "$stochtex" analyze "$exemplar" --method tiling -o "$work/$name.stx"
  "$stochtex" info "$work/$name.stx" --export "$work" >/dev/null
  cp "$work/gaussian.png" "$out/${name}_gaussian.png"
  "$stochtex" render "$work/$name.stx" -o "$out/${name}_tiling.png" --size 256x256 --seed 1
done

# Blending operators (section 3, figure 4), same lattice, same patches (same seed).
for name in nuts_grey_256 water_caustics_256; do
  exemplar="$textures/$name.png"
  for blend in 0 1 2; do
    "$stochtex" synth "$exemplar" --method tiling -p blend=$blend -o "$out/${name}_blend$blend.png" \
      --size 384x384 --seed 3
  done
done

# Transports (sections 4.1-4.2 against Deliot & Heitz's per-channel transport, the default).
"$stochtex" synth "$textures/moss_ground_512.png" --method tiling -p transport=sliced \
  -o "$out/moss_ground_512_tiling_sliced.png" --size 256x256 --seed 1

# The artist controls (docs/methods/tiling.md, "Artist controls"): defaults, each control alone,
# same seed.
for control in rotation=0 rotation=180 scale_jitter=0.5 sharpness=4; do
  "$stochtex" synth "$textures/bricks_stone_wall_512.png" --method tiling -p "$control" \
    -o "$out/controls_${control%%=*}_${control#*=}.png" --size 256x256 --seed 2
done

model="$work/water_caustics_256.stx"
gallery_filtering_row "$model" 256x256
echo "gallery written to $out"
