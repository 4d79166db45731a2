#!/usr/bin/env bash
# docs/inputs.md "Photos that do not tile": tiling with make_tileable off (the exemplar as is) and
# auto (made tileable when its wrap step is beyond 1.5) on the shipped exemplars that do not tile
# and any others given. Prints a markdown table: the exemplar's wrap step (`stochtex info`), the
# wrap step of the Gaussianised exemplar the patches read (G, from `info --export`), and the
# `stochtex compare` numbers of 4 seeds at 256x256 beside ADSN's; writes 384x384 renders of each
# side by side into docs/images/inputs/. Needs a built CLI in build/ and /usr/bin/python3 with
# numpy and PIL. Usage: [PICTURES=folder] bash scripts/make_tileable.sh [exemplar...]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
stochtex="$root/build/stochtex"
pictures="${PICTURES:-$root/docs/images/inputs}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$pictures"
exemplars=("$@")
if [ ${#exemplars[@]} -eq 0 ]; then
  exemplars=("$root/data/exemplars/water_caustics_256.png" "$root/data/exemplars/wood_planks_256.png")
fi

# Wrap steps of an image (metrics.hpp's wrap_steps, all channels together), "x y".
wrap_of() {
  /usr/bin/python3 - "$1" <<'EOF'
import sys
import numpy as np
from PIL import Image
a = np.asarray(Image.open(sys.argv[1]), dtype=np.float64)
a = a.reshape(a.shape[0], a.shape[1], -1)
inside_x = np.abs(np.diff(a, axis=1)).mean()
inside_y = np.abs(np.diff(a, axis=0)).mean()
print(f"{np.abs(a[:, 0] - a[:, -1]).mean() / inside_x:.2f} {np.abs(a[0] - a[-1]).mean() / inside_y:.2f}")
EOF
}

echo "| exemplar | its wrap step (x, y) | make_tileable | G's wrap step (x, y) | spectral error (ADSN) | averaged (ADSN) | colour SW2 (ADSN) | covariance |"
echo "|---|---|---|---|---|---|---|---|"
for exemplar in "${exemplars[@]}"; do
  name="$(basename "${exemplar%.*}")"
  for choice in off auto; do
    model="$work/${name}_$choice.stx"
    "$stochtex" analyze "$exemplar" -m tiling -p make_tileable=$choice -o "$model" 2>/dev/null
    wrap="$("$stochtex" info "$model" --json | /usr/bin/python3 -c \
      'import json,sys; w=json.load(sys.stdin)["exemplar_wrap_step"]; print(f"{w[0]:.2f}, {w[1]:.2f}")')"
    made="$("$stochtex" info "$model" --json | /usr/bin/python3 -c \
      'import json,sys; print(["off","on"][int(json.load(sys.stdin)["params"]["make_tileable"])])')"
    mkdir -p "$work/${name}_$choice"
    "$stochtex" info "$model" --export "$work/${name}_$choice" >/dev/null
    g="$(wrap_of "$work/${name}_$choice/gaussian.png" | tr ' ' ',' | sed 's/,/, /')"
    renders=()
    for seed in 1 2 3 4; do
      "$stochtex" render "$model" -o "$work/${name}_${choice}_$seed.png" --size 256x256 \
        --seed $seed >/dev/null 2>&1
      renders+=("$work/${name}_${choice}_$seed.png")
    done
    "$stochtex" compare --json "$exemplar" "${renders[@]}" | /usr/bin/python3 -c "
import json, sys
c = json.load(sys.stdin)
print(f\"| $name | $wrap | $choice ($made) | $g | {c['spectral_error']:.3f} ({c['spectral_error_adsn']:.3f}) \"
      f\"| {c['averaged_spectral_error']:.3f} ({c['averaged_spectral_error_adsn']:.3f}) \"
      f\"| {c['histogram_error']:.4f} ({c['histogram_error_adsn']:.4f}) | {c['covariance_error']:.3f} |\")"
    "$stochtex" render "$model" -o "$work/${name}_${choice}_big.png" --size 384x384 --seed 3 \
      >/dev/null 2>&1
  done
  /usr/bin/python3 - "$work/${name}_off_big.png" "$work/${name}_auto_big.png" \
    "$pictures/make_tileable_$name.png" <<'EOF'
import sys
from PIL import Image
left, right = Image.open(sys.argv[1]).convert("RGB"), Image.open(sys.argv[2]).convert("RGB")
page = Image.new("RGB", (left.width + right.width + 16, left.height), "white")
page.paste(left, (0, 0))
page.paste(right, (left.width + 16, 0))
page.save(sys.argv[3], optimize=True)
EOF
done
