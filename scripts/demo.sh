#!/usr/bin/env bash
# The main job on a bundled photo: builds the CLI, then for every available method (and `auto`,
# which chooses one and says why) analyses the exemplar into a model file and renders it (a large
# view and a zoomed-out, filtered view), beside the exemplar's Gaussian version. The default
# exemplar is a JPEG photo that does not tile (data/exemplars/water_caustics.jpg): the renders
# have no seams. Usage: bash scripts/demo.sh [exemplar] [output-dir]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
exemplar="${1:-$root/data/exemplars/water_caustics.jpg}"
out="${2:-$root/demo-output}"
build="$root/build"
bash "$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --parallel --target stochtex
stochtex="$build/stochtex"
mkdir -p "$out"
cp "$exemplar" "$out/exemplar.${exemplar##*.}"
"$stochtex" gaussian "$exemplar" -o "$out/gaussian.png" --size 512x512 --seed 1
methods=$("$stochtex" methods | sed -n 's/^\([a-z]*\): .*/\1/p')
for method in $methods; do
  "$stochtex" analyze "$exemplar" --method "$method" -o "$out/$method.stx"
  "$stochtex" render "$out/$method.stx" -o "$out/$method.png" --size 512x512 --seed 1
  "$stochtex" render "$out/$method.stx" -o "$out/${method}_scale8.png" --size 512x512 --seed 1 \
    --scale 8
  "$stochtex" compare "$exemplar" "$out/$method.png" > "$out/${method}_compare.txt"
done
echo "stochtex demo: outputs for methods [$(echo $methods)] written to $out"
