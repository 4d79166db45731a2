#!/usr/bin/env bash
# docs/methods/tiling.md "The default transport (issue 39)": tiling with each transport on every
# colour exemplar of data/exemplars, 1024² renders with seeds 1 and 2, measured by `stochtex
# compare` (the means of the two renders, beside compare's ADSN sample's), and the side-by-side
# crops of water_caustics_256 and plaid_fabric_256 in docs/images/tiling/transports_*.png. Prints
# the markdown table. Needs a built CLI in build/ and /usr/bin/python3 with PIL.
# Usage: [PICTURES=folder] bash scripts/transport_choice.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
stochtex="$root/build/stochtex"
pictures="${PICTURES:-$root/docs/images/tiling}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$pictures"

echo "| exemplar | spectral error, sliced | pca | ADSN | colour SW2, sliced | pca | ADSN | covariance error, sliced | pca |"
echo "|---|---|---|---|---|---|---|---|---|"
for name in concrete_cement_512 grass_lawn_256 grass_lawn_128 rock_sandstone_512 wood_planks_256 \
  moss_ground_512 bricks_stone_wall_512 cobblestone_512 water_caustics_256 plaid_fabric_256 \
  wool_knit_blue_256; do
  exemplar="$root/data/exemplars/$name.png"
  for transport in sliced pca; do
    "$stochtex" analyze "$exemplar" -m tiling -p transport=$transport -o "$work/m.stx" >/dev/null 2>&1
    for seed in 1 2; do
      "$stochtex" render "$work/m.stx" --size 1024x1024 --seed $seed \
        -o "$work/$name.$transport.$seed.png" >/dev/null 2>&1
    done
    "$stochtex" compare "$exemplar" "$work/$name.$transport.1.png" "$work/$name.$transport.2.png" \
      >"$work/$transport.txt" 2>&1
  done
  /usr/bin/python3 - "$name" "$work/sliced.txt" "$work/pca.txt" <<'EOF'
import re, sys
def measures(path):
    rows = {}
    for line in open(path):
        m = re.match(r"(spectral error \(rel\. L1\)|colour histogram \(SW2\)|covariance error \(rel\.\))\s+(\S+)(?:\s+(\S+))?", line)
        if m:
            rows[m.group(1).split()[0]] = (m.group(2), m.group(3))
    return rows
sliced, pca = measures(sys.argv[2]), measures(sys.argv[3])
print("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
    sys.argv[1], sliced["spectral"][0], pca["spectral"][0], sliced["spectral"][1],
    sliced["colour"][0], pca["colour"][0], sliced["colour"][1],
    sliced["covariance"][0], pca["covariance"][0]))
EOF
  case $name in
    water_caustics_256 | plaid_fabric_256)
      /usr/bin/python3 - "$work/$name.sliced.1.png" "$work/$name.pca.1.png" \
        "$pictures/transports_$name.png" <<'EOF'
import sys
from PIL import Image
crops = [Image.open(path).convert("RGB").crop((0, 0, 384, 384)) for path in sys.argv[1:3]]
sheet = Image.new("RGB", (2 * 384 + 8, 384), "white")
for i, crop in enumerate(crops):
    sheet.paste(crop, (i * 392, 0))
sheet.save(sys.argv[3])
EOF
      ;;
  esac
done
