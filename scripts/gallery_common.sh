# Sourced by the gallery scripts (scripts/gallery*.sh) with `gallery` set to the method's name and
# the build folder as the script's optional first argument: builds the CLI and sets `root`,
# `textures`, `stochtex`, `out` (docs/images/<gallery>) and `work` (a temporary folder removed on
# exit).
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
textures="$root/../shared/textures"
out="$root/docs/images/$gallery"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --parallel --target stochtex
stochtex="$build/stochtex"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# gallery_filtering_row MODEL SIZE: the model zoomed out 8x, filtered, point-sampled (aliased) and
# supersampled 16x16 (the reference), as scale8_{filtered,unfiltered,supersampled}.png.
gallery_filtering_row() {
  local model=$1 size=$2
  "$stochtex" render "$model" -o "$out/scale8_filtered.png" --size "$size" --scale 8 --seed 1
  "$stochtex" render "$model" -o "$out/scale8_unfiltered.png" --size "$size" --scale 8 --seed 1 \
    --no-filter
  "$stochtex" render "$model" -o "$out/scale8_supersampled.png" --size "$size" --scale 8 \
    --seed 1 --supersample 16
}
