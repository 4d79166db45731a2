#!/usr/bin/env bash
# Measures the 4-gigapixel bake of docs/performance.md ("Baking beyond memory") on this machine:
# a 65536² colour render of a tiling model of grass_lawn_256, through the CLI (tiled, mip-mapped
# half-float OpenEXR) and through stochtex.dask with 1 and 2 workers into Zarr, then the same scaling
# (1 and 2 workers) on a 16384² bake. Prints wall time and peak memory of each; needs about 45 GB
# of free disk in DIR (each output is removed after it is measured).
# Usage: bash scripts/bake.sh [build-dir] [DIR]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
dir="${2:-$build/bake}"
mkdir -p "$dir"
stochtex="$build/stochtex"
"$stochtex" analyze "$root/data/exemplars/grass_lawn_256.png" -m tiling -o "$dir/tiling.stx"

echo "== CLI: 65536x65536, --half --mipmap, 2 threads"
/usr/bin/time -f "%e s wall, %U s user, peak memory %M KB" \
  "$stochtex" render "$dir/tiling.stx" --size 65536x65536 --half --mipmap --threads 2 --seed 1 \
  -o "$dir/big.exr"
ls -l "$dir/big.exr"
rm -f "$dir/big.exr"

export PYTHONPATH="$build/python"
for run in "65536 1" "65536 2" "16384 1" "16384 2"; do
  read -r size workers <<<"$run"
  echo "== Dask: ${size}x${size}, $workers workers, float16 Zarr"
  /usr/bin/python3 "$root/scripts/bake_dask.py" "$dir/tiling.stx" "$dir/big.zarr" --size "$size" \
    --workers "$workers"
  rm -rf "$dir/big.zarr"
done
