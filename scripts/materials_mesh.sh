#!/usr/bin/env bash
# The pictures and times of docs/materials.md, "On a mesh": the shipped rock_sandstone material
# (all five maps) analysed by each method and rendered by render-mesh on the torus through linear
# triplanar mapping (which every method has), 256x256, seed 1, two 256-pixel exemplars across the
# torus; tiling's albedo and ao alone (no normal map) for comparison. Prints the render-mesh times
# of each method's material against its albedo alone (a model of one image), one run each on one
# thread. Called by scripts/gallery_materials.sh. Usage: bash scripts/materials_mesh.sh [build-dir]
set -euo pipefail
gallery=materials
source "$(dirname "$0")/gallery_common.sh"
rock="$root/data/materials/rock_sandstone"
torus="$root/data/meshes/torus.obj"
render_mesh() {
  "$stochtex" render-mesh "$torus" --model "$1" -o "$2" --size 256x256 --seed 1 --camera 20,35 \
    --texture-scale 192 --threads 1 2>/dev/null
}
# The seconds a command takes.
seconds() {
  local start=$EPOCHREALTIME
  "$@"
  awk "BEGIN { print $EPOCHREALTIME - $start }"
}
"$stochtex" analyze --map albedo="$rock/albedo.png" --map ao="$rock/ao.png" -m tiling \
  -o "$work/rock_flat.stx" 2>/dev/null
render_mesh "$work/rock_flat.stx" "$out/mesh_tiling_without_normals.png"
echo "| method | render-mesh, albedo alone (s) | render-mesh, material (s) |"
echo "|---|---|---|"
for method in texton tiling lrp gabor; do
  "$stochtex" analyze --map albedo="$rock/albedo.png" --map normal="$rock/normal.png" \
    --map roughness="$rock/roughness.png" --map height="$rock/height.png" \
    --map ao="$rock/ao.png" -m "$method" -o "$work/rock_$method.stx" 2>/dev/null
  "$stochtex" analyze "$rock/albedo.png" -m "$method" -o "$work/albedo_$method.stx" 2>/dev/null
  alone=$(seconds render_mesh "$work/albedo_$method.stx" "$work/albedo_$method.png")
  material=$(seconds render_mesh "$work/rock_$method.stx" "$out/mesh_$method.png")
  printf "| %s | %.2f | %.2f |\n" "$method" "$alone" "$material"
done
