#!/usr/bin/env bash
# Large renders (docs/large-renders.md): regions, tiled and mip-mapped OpenEXR files, streaming
# with bounded memory and the refusals before any work.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

large=$work/large
mkdir -p "$large"
# Four --region quadrants of a render, each written alone, assemble into the whole render exactly.
expect_ok "render the whole of a region split" "$stochtex" render "$model" -o "$large/whole.pfm" \
  --size 300x200 --origin 17.5,-3 --scale 1.5 --seed 9
quadrants=()
for region in 0,0,137,90 137,0,163,90 0,90,137,110 137,90,163,110; do
  expect_ok "render --region $region" "$stochtex" render "$model" -o "$large/$region.pfm" \
    --size 300x200 --origin 17.5,-3 --scale 1.5 --seed 9 --region "$region" --threads 1
  quadrants+=("$large/$region.pfm")
done
# PFM: a three-line header, then rows of floats from the bottom row to the top.
if python3 - "$large/whole.pfm" "${quadrants[@]}" <<'PY'; then
import sys

def rows(path):
    data = open(path, "rb").read()
    header = data.split(b"\n", 3)
    width, height = map(int, header[1].split())
    row_bytes = width * 3 * 4
    body = header[3]
    assert len(body) == row_bytes * height
    return [body[i * row_bytes:(i + 1) * row_bytes] for i in range(height)][::-1]

whole = rows(sys.argv[1])
top_left, top_right, bottom_left, bottom_right = (rows(p) for p in sys.argv[2:])
assembled = [l + r for l, r in zip(top_left, top_right)] + \
    [l + r for l, r in zip(bottom_left, bottom_right)]
sys.exit(0 if assembled == whole else 1)
PY
  pass
else
  fail "four --region quadrants assemble into the whole render" "the bytes differ"
fi
# Tiled, mip-mapped and half-float OpenEXR files: stochtex reads their level 0, and it is the
# in-memory (scanline) render's pixels: the same pixels analysed give the same model bytes.
expect_ok "render to a scanline .exr" "$stochtex" render "$model" -o "$large/scanline.exr" \
  --size 300x200 --seed 9
for flag in --tiled --mipmap; do
  expect_ok "render $flag" "$stochtex" render "$model" -o "$large/${flag#--}.exr" \
    --size 300x200 --seed 9 "$flag"
done
expect_ok "render --mipmap --half" "$stochtex" render "$model" -o "$large/half.exr" \
  --size 300x200 --seed 9 --mipmap --half
for image in scanline tiled mipmap; do
  mkdir -p "$large/$image"
  cp "$large/$image.exr" "$large/$image/exemplar.exr"
  expect_ok "analyze the $image .exr" "$stochtex" analyze "$large/$image/exemplar.exr" -m tiling \
    -o "$large/$image/model.stx"
done
for image in tiled mipmap; do
  if cmp -s "$large/scanline/model.stx" "$large/$image/model.stx"; then pass; else
    fail "the $image .exr holds the scanline render's pixels" "their models differ"
  fi
done
if [[ $(stat -c %s "$large/half.exr") -lt $(stat -c %s "$large/mipmap.exr") ]]; then pass; else
  fail "--half writes a smaller file" "half.exr is not smaller than mipmap.exr"
fi
expect_ok "compare reads a tiled .exr" "$stochtex" compare "$exemplar" "$large/half.exr"
if ! gl_skipped 1 "render --backend gl --tiled"; then
  expect_ok "render --backend gl --tiled" "$stochtex" render "$model" -o "$large/gl.exr" \
    --size 100x70 --seed 9 --backend gl --tiled
fi
# A render beyond the in-memory limit (64 Mpixel) to .exr is streamed strip by strip: its peak
# memory is a strip's (44 MB measured), not the 816 MB of the image. Under AddressSanitizer
# (scripts/sanitize.sh sets ASAN_OPTIONS) shadow memory and the 256 MB quarantine of freed blocks
# add to it (427 MB measured): the bound is then the image's own size.
if python3 - "$stochtex" "$tiling_model" "$large/wide.exr" <<'PY'; then
import os, resource, subprocess, sys
stochtex, model, output = sys.argv[1:]
subprocess.run([stochtex, "render", model, "-o", output, "--size", "40000x1700", "--threads", "2"],
               check=True, stderr=subprocess.DEVNULL)
peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
bound_mb = 816 if "ASAN_OPTIONS" in os.environ else 200
print(f"peak {peak_mb:.0f} MB (bound {bound_mb} MB)")
sys.exit(0 if peak_mb < bound_mb else 1)
PY
  pass
else
  fail "a render beyond the in-memory limit streams with bounded memory" "see the peak above"
fi
rm -f "$large/wide.exr"
# Refused with one sentence before any work.
expect_error "render .png beyond the in-memory limit" 2 "write a .exr file" \
  "$stochtex" render "$model" -o "$out/x.png" --size 65536x65536
expect_error "render .pfm region beyond the in-memory limit" 2 "--region 0,0,40000,1700" \
  "$stochtex" render "$model" -o "$out/x.pfm" --size 65536x65536 --region 0,0,40000,1700
expect_error "render --size beyond 2^20" 2 "2000000x16" \
  "$stochtex" render "$model" -o "$out/x.exr" --size 2000000x16
expect_error "render a tiled .exr larger than the disk" 1 "free" \
  timeout 10 "$stochtex" render "$model" -o "$out/x.exr" --size 1048576x1048576
expect_error "render --mipmap to .png" 2 "--mipmap" \
  "$stochtex" render "$model" -o "$out/x.png" --size 64x64 --mipmap
expect_error "render --mipmap --region" 2 "--region" \
  "$stochtex" render "$model" -o "$out/x.exr" --size 64x64 --mipmap --region 0,0,8,8
for region in 0,0,0,8 60,0,8,8 0,60,8,8 1,2,3 a,b,c,d -1,0,8,8; do
  expect_error "render --region $region" 2 "--region" \
    "$stochtex" render "$model" -o "$out/x.png" --size 64x64 --region "$region"
done

summary
