#!/usr/bin/env bash
# Checks that a refactor keeps the outputs byte-identical (docs/design.md §4): two builds of
# `stochtex` (before and after) analyse the same exemplars with every method of the registry, then
# render (point-sampled and zoomed out, PNG and PFM), export the shaders (both variants, every
# language of the new build's `stochtex languages`) and the web viewer, and render a mesh; every
# file must have the same bytes.
# Usage: bash scripts/same_outputs.sh OLD_STOCHTEX NEW_STOCHTEX [EXEMPLAR...]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [[ $# -lt 2 ]]; then
  echo "usage: $0 OLD_STOCHTEX NEW_STOCHTEX [EXEMPLAR...]" >&2
  exit 2
fi
old=$1
new=$2
shift 2
exemplars=("$@")
if [[ ${#exemplars[@]} -eq 0 ]]; then
  exemplars=("$root/data/exemplars/grass_lawn_128.png" "$root/data/exemplars/nuts_grey_256.png")
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
methods=$("$new" methods --json | python3 -c 'import json, sys; print(" ".join(m["name"] for m in json.load(sys.stdin)))')
languages=$("$new" languages --json | python3 -c 'import json, sys; print(" ".join(l["name"] for l in json.load(sys.stdin)))')

# quiet COMMAND...: runs it, printing what it said only when it fails.
quiet() {
  "$@" >"$work/said" 2>&1 || {
    cat "$work/said" >&2
    return 1
  }
}

# outputs BINARY FOLDER: everything the check compares, written by BINARY into FOLDER.
outputs() {
  local stochtex=$1 folder=$2 exemplar name method model
  mkdir -p "$folder"
  for exemplar in "${exemplars[@]}"; do
    name=$(basename "$exemplar" .png)
    for method in $methods; do
      model=$folder/${name}_$method.stx
      quiet "$stochtex" analyze "$exemplar" -m "$method" -o "$model" --analysis-seed 3
      quiet "$stochtex" render "$model" -o "$folder/${name}_$method.png" --size 96x80 --seed 5
      quiet "$stochtex" render "$model" -o "$folder/${name}_${method}_far.pfm" --size 64x48 \
        --origin 1e5,-33.5 --scale 6 --seed 2
      for variant in exact fast; do
        for language in $languages; do
          # A language a model cannot be written in is refused by both builds alike.
          "$stochtex" export-shader "$model" -o "$folder/${name}_${method}_${variant}_$language" \
            --variant "$variant" --language "$language" >/dev/null 2>&1 ||
            echo "refused" >"$folder/${name}_${method}_${variant}_$language.refused"
        done
      done
    done
    quiet "$stochtex" export-web "$folder/${name}"_*.stx -o "$folder/${name}_web"
    quiet "$stochtex" render-mesh "$root/data/meshes/sphere.obj" -o "$folder/${name}_mesh.png" \
      --model "$folder/${name}_tiling.stx" --size 64x64 --seed 4
  done
}

outputs "$old" "$work/old"
outputs "$new" "$work/new"
if diff -r "$work/old" "$work/new" >"$work/diff"; then
  echo "same_outputs.sh: $(find "$work/new" -type f | wc -l) files, the same bytes" \
    "($methods on ${#exemplars[@]} exemplars)"
else
  cat "$work/diff" >&2
  echo "same_outputs.sh: the outputs above differ" >&2
  exit 1
fi
