#!/usr/bin/env bash
# The pictures of docs/meshes.md: each shipped mesh (data/meshes, scripts/make_meshes.py) rendered
# by `stochtex render-mesh` on the CPU with models of corpus exemplars, through each mapping of the
# papers, into docs/images/meshes/. Usage: bash scripts/mesh_pictures.sh [build-dir]
set -euo pipefail
gallery=meshes
source "$(dirname "$0")/gallery_common.sh"
meshes="$root/data/meshes"
"$stochtex" analyze "$textures/moss_ground_512.png" --method tiling -o "$work/moss.stx"
"$stochtex" analyze "$textures/bricks_stone_wall_512.png" --method tiling -o "$work/bricks.stx"
# The scan has no texture coordinates: linear triplanar mapping.
"$stochtex" render-mesh "$meshes/scan.obj" --model "$work/moss.stx" -o "$out/scan_triplanar_linear.png" \
  --size 512x384 --seed 1
"$stochtex" render-mesh "$meshes/torus.obj" --model "$work/moss.stx" \
  -o "$out/torus_triplanar_linear.png" --size 512x384 --seed 1 --camera 20,35
# The sphere and the torus through their texture coordinates.
"$stochtex" render-mesh "$meshes/sphere.obj" --model "$work/bricks.stx" -o "$out/sphere_uv.png" \
  --size 512x384 --seed 1 --mapping uv --texture-scale 1536
"$stochtex" render-mesh "$meshes/torus.obj" --model "$work/bricks.stx" -o "$out/torus_uv.png" \
  --size 512x384 --seed 1 --mapping uv --texture-scale 1536 --camera 20,35
# Surface noise on the scan, which has no texture coordinates (texton paper figure 4): texton noise
# (MNI 60 as in the paper) and Gabor noise by example, both of a corpus photo.
"$stochtex" analyze "$textures/rock_sandstone_512.png" --method texton -o "$work/rock_texton.stx"
"$stochtex" analyze "$textures/rock_sandstone_512.png" --method gabor -o "$work/rock_gabor.stx"
for method in texton gabor; do
  "$stochtex" render-mesh "$meshes/scan.obj" --model "$work/rock_$method.stx" \
    -o "$out/scan_surface_$method.png" --size 512x384 --seed 1 --mapping surface
done
# Triplanar mapping (tiling paper figure 16): histogram-preserving against linear blending, where
# the three projections overlap on the torus.
for mapping in triplanar triplanar-linear; do
  "$stochtex" render-mesh "$meshes/torus.obj" --model "$work/bricks.stx" \
    -o "$out/torus_bricks_${mapping/-/_}.png" --size 512x384 --seed 1 --camera 20,35 --mapping "$mapping"
done
