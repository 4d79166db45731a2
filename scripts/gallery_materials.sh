#!/usr/bin/env bash
# Regenerates the pictures and the table of docs/materials.md: the shipped rock_sandstone material
# (MIT, data/materials/ATTRIBUTION.md) analysed with every method, each method's albedo, normal and
# height maps and the albedo lit by its normal map (scripts/materials_figures.py, which prints the
# table), then the material on a mesh (scripts/materials_mesh.sh). Needs numpy and Pillow
# (python3-numpy, python3-pil). Usage: bash scripts/gallery_materials.sh [build-dir]
set -euo pipefail
gallery=materials
source "$(dirname "$0")/gallery_common.sh"
cmake --build "$build" --parallel --target stochtex_python
/usr/bin/python3 "$root/scripts/materials_figures.py" "$build" "$out"
bash "$root/scripts/materials_mesh.sh" "$build"
