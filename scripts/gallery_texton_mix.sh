#!/usr/bin/env bash
# Regenerates the pictures of docs/methods/texton_mix.md (texton noise mixing, "Texton Noise",
# Galerne, Leclaire, Moisan, CGF 2017, section 7, figure 5) from two MIT corpus exemplars, moss
# (A) and sandstone (B): a strip going from A to B along a horizontal ramp (ramp_strip.png); the
# texture of the regions rho = 0, 0.25, 0.5, 0.75, 1 of a long ramp (rho_0.00.png ... rho_1.00.png,
# in the place of figure 5's row of textons); a grey mask written here (mask.png, black = A,
# white = B) and the mixing it gives (mask_mix.png). Usage: bash scripts/gallery_texton_mix.sh
# [build-dir]
set -euo pipefail
gallery=texton_mix
source "$(dirname "$0")/gallery_common.sh"

a="$textures/moss_ground_512.png"
b="$textures/rock_sandstone_512.png"

# Figure 5's strip: rho from 0 at x = 0 to 1 at x = 768, the paper's R = 21 textons.
"$stochtex" mix "$a" "$b" -o "$work/strip.stx" --ramp 0,768
"$stochtex" render "$work/strip.stx" -o "$out/ramp_strip.png" --size 768x192 --seed 1

# A ramp 5120 pixels long: region k (rho = k / 20) is the 256 pixels around x = 256 k, so a 128 x
# 128 window at its centre shows that region's texture alone.
"$stochtex" mix "$a" "$b" -o "$work/long.stx" --ramp 0,5120
for region in 0:0.00 5:0.25 10:0.50 15:0.75 20:1.00; do
  k=${region%%:*} rho=${region#*:}
  "$stochtex" render "$work/long.stx" -o "$out/rho_$rho.png" --size 128x128 --seed 1 \
    --origin "$((256 * k - 64)),0"
done

# The mask: 64 x 32 grey pixels, 8 model-space pixels each (512 x 256): B below a wavy line and
# in a disc above it, with soft edges (3 mask pixels) so that the regions between show too.
python3 - "$out/mask.png" <<'PY'
import math, struct, sys, zlib
width, height = 64, 32
def rho(x, y):
    wave = (y - 20 - 4 * math.sin(2 * math.pi * x / 32)) / 3
    disc = (9 - math.hypot(x - 44, y - 9)) / 3
    return min(1.0, max(0.0, 0.5 + max(wave, disc)))
rows = b"".join(bytes([0] + [round(255 * rho(x + 0.5, y + 0.5)) for x in range(width)])
                for y in range(height))
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
with open(sys.argv[1], "wb") as png:
    png.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
              + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
PY
"$stochtex" mix "$a" "$b" -o "$work/mask.stx" --mask "$out/mask.png" --mask-scale 8
"$stochtex" render "$work/mask.stx" -o "$out/mask_mix.png" --size 512x256 --seed 1
echo "gallery written to $out"
