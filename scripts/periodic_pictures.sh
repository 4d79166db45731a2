#!/usr/bin/env bash
# The measurements and pictures of docs/render.md ("Periodic renders"): for each method's model of
# grass_lawn_256 at its defaults, the wrap steps (metrics' wrap_steps: the step across the
# junction of a 2x2 tiling over the mean step between neighbouring pixels; 1 = seamless) of
# 200x136 renders at --scale 1 and 0.5 with and without --periodic, mean and spread over 8 seeds,
# and the wall time of a 1024x1024 render of each (--threads 2, one run each), by default, by the
# scalar reference evaluator (--cpu-target reference, what --periodic runs) and with --periodic;
# then the 2x2 tilings of a 256x256 render of each at --scale 0.5, default and periodic, into
# docs/images/periodic/. Prints the tables of docs/render.md.
# Usage: bash scripts/periodic_pictures.sh [build-dir]
set -euo pipefail
gallery=periodic
source "$(dirname "$0")/gallery_common.sh"
methods=(texton tiling lrp gabor)
for method in "${methods[@]}"; do
  "$stochtex" analyze "$textures/grass_lawn_256.png" -m "$method" -o "$work/$method.stx" 2>/dev/null
done

echo "| method | scale | default x | default y | --periodic x | --periodic y |"
echo "|---|---|---|---|---|---|"
for method in "${methods[@]}"; do
  for scale in 1 0.5; do
    for seed in 1 2 3 4 5 6 7 8; do
      "$stochtex" render "$work/$method.stx" -o "$work/${method}_default_$seed.pfm" --size 200x136 \
        --seed "$seed" --scale "$scale" 2>/dev/null
      "$stochtex" render "$work/$method.stx" -o "$work/${method}_periodic_$seed.pfm" \
        --size 200x136 --seed "$seed" --scale "$scale" --periodic 2>/dev/null
    done
    PYTHONPATH="$root/scripts" /usr/bin/python3 - "$method" "$work" "$scale" <<'PY'
import sys
import numpy
method, work = sys.argv[1], sys.argv[2]
from pfm import read_pfm
def wrap(image):
    # metrics/metrics.hpp wrap_steps: mean |last - first| over the mean |neighbour step|.
    steps = []
    for axis in (1, 0):
        inner = numpy.abs(numpy.diff(image, axis=axis)).mean()
        last = numpy.take(image, -1, axis=axis)
        first = numpy.take(image, 0, axis=axis)
        steps.append(numpy.abs(last - first).mean() / inner)
    return steps
row = [method, sys.argv[3]]
for kind in ("default", "periodic"):
    values = numpy.array([wrap(read_pfm(f"{work}/{method}_{kind}_{s}.pfm")) for s in range(1, 9)])
    for axis in range(2):
        row.append(f"{values[:, axis].mean():.2f} ± {values[:, axis].std():.2f}")
print("| " + " | ".join(row) + " |")
PY
  done
done

echo
echo "| method | default 1024² (s) | --cpu-target reference (s) | --periodic (s) |"
echo "|---|---|---|---|"
for method in "${methods[@]}"; do
  times=()
  for flag in "" "--cpu-target reference" "--periodic"; do
    start=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$stochtex" render "$work/$method.stx" -o "$work/time.pfm" --size 1024x1024 --seed 1 \
      --threads 2 $flag 2>/dev/null
    end=$(date +%s.%N)
    times+=("$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')")
  done
  echo "| $method | ${times[0]} | ${times[1]} | ${times[2]} |"
done

for method in "${methods[@]}"; do
  for kind in default periodic; do
    flag=()
    if [[ $kind == periodic ]]; then flag=(--periodic); fi
    "$stochtex" render "$work/$method.stx" -o "$work/${method}_$kind.png" --size 256x256 \
      --scale 0.5 --seed 1 "${flag[@]}" 2>/dev/null
    /usr/bin/python3 -c "
import sys
from PIL import Image
tile = Image.open(sys.argv[1])
out = Image.new(tile.mode, (2 * tile.width, 2 * tile.height))
for x in (0, tile.width):
    for y in (0, tile.height):
        out.paste(tile, (x, y))
out.save(sys.argv[2], optimize=True)
" "$work/${method}_$kind.png" "$out/${method}_${kind}_2x2.png"
  done
done
echo "pictures written to $out"
