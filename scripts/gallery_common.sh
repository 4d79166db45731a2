# Sourced by the gallery scripts (scripts/gallery*.sh) with `gallery` set to the method's name and
# the build folder as the script's optional first argument: builds the CLI and sets `root`,
# `textures`, `stochtex`, `out` (docs/images/<gallery>) and `work` (a temporary folder removed on
# exit).
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
textures="$root/data/exemplars"
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

# gallery_preview_row NAME METHOD PREVIEW: for the corpus exemplar NAME, the exemplar, its Gaussian
# version, the model's `info --export` picture PREVIEW.png and a render, as NAME_exemplar.png,
# NAME_gaussian.png, NAME_PREVIEW.png and NAME_noise.png (256x256, seed 1); the model stays in
# $work/NAME.stx.
gallery_preview_row() {
  local name=$1 method=$2 preview=$3
  local exemplar="$textures/$name.png"
  cp "$exemplar" "$out/${name}_exemplar.png"
  "$stochtex" gaussian "$exemplar" -o "$out/${name}_gaussian.png" --size 256x256 --seed 1
  "$stochtex" analyze "$exemplar" --method "$method" -o "$work/$name.stx"
  "$stochtex" info "$work/$name.stx" --export "$work" >/dev/null
  cp "$work/$preview.png" "$out/${name}_$preview.png"
  "$stochtex" render "$work/$name.stx" -o "$out/${name}_noise.png" --size 256x256 --seed 1
}
