#!/usr/bin/env bash
# The pictures of docs/meshes.md: each shipped mesh (data/meshes, scripts/make_meshes.py) rendered
# by `stochtex render-mesh` on the CPU with models of corpus exemplars, through each mapping of the
# papers, into docs/images/meshes/; then the measurements of the uv wrap seam with and without
# --periodic and their times, printed as docs/meshes.md's tables.
# Usage: bash scripts/mesh_pictures.sh [build-dir]
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
# The sphere and the torus through their texture coordinates, repeating every uv unit
# (--periodic) so that their uv wrap seams do not show; the sphere also without, its seam showing.
uv=(--size 512x384 --mapping uv --texture-scale 1536)
"$stochtex" render-mesh "$meshes/sphere.obj" --model "$work/bricks.stx" "${uv[@]}" --seed 1 \
  -o "$out/sphere_uv.png"
"$stochtex" render-mesh "$meshes/sphere.obj" --model "$work/bricks.stx" "${uv[@]}" --seed 1 \
  -o "$out/sphere_uv_periodic.png" --periodic
"$stochtex" render-mesh "$meshes/torus.obj" --model "$work/bricks.stx" "${uv[@]}" --seed 1 \
  -o "$out/torus_uv_periodic.png" --camera 20,35 --periodic
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

# The uv wrap seam (docs/meshes.md, "UV wrap seams"): the sphere seen from +z (--camera 0,0), so
# that its seam, the meridian x = 0 where u jumps from 1 to 0, runs between the picture's middle
# columns 255 and 256. The seam step: the mean absolute difference across it over rows 96 to 287
# (the sphere's middle half) and the colour channels, over the mean step between the other
# neighbouring columns from 160 to 352 on those rows; 1 is seamless. Mean ± standard deviation
# over seeds 1 to 8, without and with --periodic, and as a control the same step across the
# meridian u = 1/4 (no seam, the same whole exemplar pixel as the seam's u = 0: --camera 90,0),
# without --periodic: the bricks of the pictures and each method's model of grass_lawn_256 at its
# defaults. Then the wall time of the picture's render (seed 1, --threads 2, the fastest of three
# runs) without and with --periodic.
for method in texton tiling lrp gabor; do
  "$stochtex" analyze "$textures/grass_lawn_256.png" -m "$method" -o "$work/grass_$method.stx" \
    2>/dev/null
done
models=(bricks grass_texton grass_tiling grass_lrp grass_gabor)
echo "| model | seam step, default | seam step, --periodic | control: u = 1/4, default |"
echo "|---|---|---|---|"
for model in "${models[@]}"; do
  for seed in 1 2 3 4 5 6 7 8; do
    for kind in default periodic control; do
      flags=(--camera "0,0")
      if [[ $kind == periodic ]]; then flags+=(--periodic); fi
      if [[ $kind == control ]]; then flags=(--camera "90,0"); fi
      "$stochtex" render-mesh "$meshes/sphere.obj" --model "$work/$model.stx" "${uv[@]}" \
        --seed "$seed" -o "$work/seam_${kind}_$seed.pfm" "${flags[@]}" 2>/dev/null
    done
  done
  PYTHONPATH="$root/scripts" /usr/bin/python3 - "$work" "$model" <<'PY'
import sys
import numpy
work, model = sys.argv[1], sys.argv[2]
from pfm import read_pfm
def seam_step(image):
    steps = numpy.abs(numpy.diff(image[96:288, 160:353], axis=1)).mean(axis=(0, 2))
    seam = steps[255 - 160]
    return seam / numpy.delete(steps, 255 - 160).mean()
row = [model]
for kind in ("default", "periodic", "control"):
    values = numpy.array([seam_step(read_pfm(f"{work}/seam_{kind}_{s}.pfm")) for s in range(1, 9)])
    row.append(f"{values.mean():.2f} ± {values.std():.2f}")
print("| " + " | ".join(row) + " |")
PY
done
echo
echo "| model | default (s) | --periodic (s) |"
echo "|---|---|---|"
for model in "${models[@]}"; do
  times=()
  for flag in "" --periodic; do
    best=""
    for _ in 1 2 3; do
      start=$(date +%s.%N)
      # shellcheck disable=SC2086
      "$stochtex" render-mesh "$meshes/sphere.obj" --model "$work/$model.stx" "${uv[@]}" \
        --seed 1 --threads 2 -o "$work/time.pfm" $flag 2>/dev/null
      end=$(date +%s.%N)
      best=$(awk -v a="$start" -v b="$end" -v best="$best" \
        'BEGIN { t = b - a; if (best != "" && best < t) t = best; printf "%.2f", t }')
    done
    times+=("$best")
  done
  echo "| $model | ${times[0]} | ${times[1]} |"
done
