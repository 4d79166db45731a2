#!/usr/bin/env bash
# Colour (docs/design.md §14, issue 36): --colour-space on analyze, synth and render, a model's
# colour space in info, renders of srgb models as linear light written to PNG with an sRGB chunk,
# and the refusals.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

nuts=$textures/nuts_grey_256.png
meshes=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../data/meshes" && pwd)
fast=(-m texton -p support=32 -p iterations=5)
expect_ok "analyze --colour-space srgb" "$stochtex" analyze "$nuts" "${fast[@]}" \
  --colour-space srgb -o "$models/srgb.stx"
expect_ok "info names the colour space" "$stochtex" info "$models/srgb.stx" &&
  if grep -q '^colour    srgb$' "$work/stdout"; then pass; else
    fail "info names the colour space" "no 'colour    srgb' line in: $(cat "$work/stdout")"
  fi
expect_json "info --json of a srgb model" "$stochtex" info "$models/srgb.stx" --json &&
  if python3 -c 'import json,sys; assert json.load(sys.stdin)["colour_space"] == "srgb"' \
    <"$work/stdout"; then pass; else fail "info --json has colour_space srgb" "not srgb"; fi
# The default, auto, with tiling, whose colour costs less to set up than texton's (measured
# removed deviations: seconds under the sanitizers).
expect_ok "analyze (--colour-space auto, the default)" "$stochtex" analyze "$nuts" -m tiling \
  -o "$models/auto.stx" &&
  if grep -qF 'srgb (no colour chunk: sRGB by default)' "$work/stderr"; then pass; else
    fail "analyze --colour-space auto says what it read" "$(cat "$work/stderr")"
  fi
expect_ok "info of an auto model" "$stochtex" info "$models/auto.stx" &&
  if grep -q '^colour    srgb$' "$work/stdout"; then pass; else
    fail "a PNG without a colour chunk is sRGB" "$(cat "$work/stdout")"
  fi
expect_ok "analyze as data" "$stochtex" analyze "$nuts" "${fast[@]}" --colour-space data \
  -o "$models/data.stx"
expect_parse_error "analyze --colour-space oklab" "$stochtex" analyze "$nuts" "${fast[@]}" \
  --colour-space oklab -o "$out/x.stx"

# A render of a srgb model is linear light, encoded again into its PNG (with an sRGB chunk): at
# scale 1 the bytes of the data model's render, at scale 16 the photo's linear-light mean where
# the data model averages encoded values (41 levels of 255 darker on nuts).
for space in srgb data; do
  for scale in 1 16; do
    expect_ok "render a $space model at scale $scale" "$stochtex" render "$models/$space.stx" \
      --size 64x64 --scale "$scale" --seed 4 -o "$models/${space}_$scale.png"
  done
done
if python3 - "$models" <<'PY'; then pass; else fail "srgb renders encode linear light" "see above"; fi
import struct, sys, zlib
folder = sys.argv[1]
def png(path):
    data = open(path, "rb").read()
    chunks, at = {}, 8
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        chunks.setdefault(kind, b"")
        chunks[kind] += data[at + 8:at + 8 + length]
        at += 12 + length
    width, height = struct.unpack(">II", chunks[b"IHDR"][:8])
    assert chunks[b"IHDR"][8:10] == bytes([8, 0]), "8-bit grey"
    raw, values, previous = zlib.decompress(chunks[b"IDAT"]), [], bytes(width)
    for row in range(height):  # the PNG specification's filters, one byte a pixel
        kind, line = raw[row * (width + 1)], bytearray(raw[row * (width + 1) + 1:(row + 1) * (width + 1)])
        for x in range(width):
            a, b = line[x - 1] if x else 0, previous[x]
            c = previous[x - 1] if x else 0
            p = a + b - c
            paeth = a if abs(p - a) <= min(abs(p - b), abs(p - c)) else b if abs(p - b) <= abs(p - c) else c
            line[x] = (line[x] + [0, a, b, (a + b) // 2, paeth][kind]) % 256
        values += line
        previous = bytes(line)
    return chunks, values
srgb1, s1 = png(folder + "/srgb_1.png")
data1, d1 = png(folder + "/data_1.png")
srgb16, s16 = png(folder + "/srgb_16.png")
data16, d16 = png(folder + "/data_16.png")
assert b"sRGB" in srgb1 and b"sRGB" not in data1, "the sRGB chunk"
assert max(abs(a - b) for a, b in zip(s1, d1)) <= 1, "scale 1 is the data model's render"
mean = lambda v: sum(v) / len(v)
print("scale 16 means, srgb and data:", mean(s16), mean(d16))
assert mean(s16) > mean(d16) + 20, "zoomed out, srgb is the linear-light mean, brighter"
PY
expect_ok "render a data model --colour-space srgb" "$stochtex" render "$models/data.stx" \
  --size 64x64 --scale 16 --seed 4 --colour-space srgb -o "$models/as_srgb_16.png"
if cmp -s "$models/srgb_16.png" "$models/as_srgb_16.png"; then pass; else
  fail "render --colour-space srgb of a data model is the srgb model's render" "they differ"
fi

# A mesh textured by a srgb model is lit in linear light and written with an sRGB chunk.
expect_ok "render-mesh of a srgb model" "$stochtex" render-mesh "$meshes/scan.obj" \
  --model "$models/srgb.stx" -o "$models/mesh.png" --size 40x32 --mapping triplanar-linear &&
  if grep -q sRGB "$models/mesh.png"; then pass; else
    fail "render-mesh of a srgb model" "the PNG has no sRGB chunk"
  fi
if ! gl_skipped 1 "render-mesh --backend gl of a srgb model"; then
  expect_ok "render-mesh --backend gl of a srgb model" "$stochtex" render-mesh \
    "$meshes/scan.obj" --model "$models/srgb.stx" -o "$models/mesh_gl.png" --size 40x32 \
    --mapping triplanar-linear --backend gl
fi

# mix takes the colour space of both exemplars, and refuses two.
expect_ok "mix --colour-space srgb" "$stochtex" mix "$nuts" "$textures/metal_grey_256.png" \
  -p support=16 -p iterations=5 --steps 3 --colour-space srgb -o "$models/mix.stx" &&
  expect_ok "info of a srgb mix" "$stochtex" info "$models/mix.stx" &&
  if grep -q '^colour    srgb$' "$work/stdout"; then pass; else
    fail "mix --colour-space srgb" "$(cat "$work/stdout")"
  fi
expect_ok "a grey PFM" "$stochtex" render "$models/data.stx" --size 64x64 -o "$inputs/grey.pfm"
expect_error "mix of a srgb PNG and a linear PFM, auto" 1 "one colour space" "$stochtex" mix \
  "$nuts" "$inputs/grey.pfm" -p support=16 -p iterations=5 --steps 3 --colour-space auto \
  -o "$out/x.stx"

# The GL backend renders srgb models and their exported shaders return linear light
# (tests/gl/colour_gl_test.cpp and export_language_test.cpp compare them with the CPU), which the
# web viewer encodes for its canvas (tests/browser/browser_test.py).
if ! gl_skipped 1 "render --backend gl of a srgb model"; then
  expect_ok "render --backend gl of a srgb model" "$stochtex" render "$models/srgb.stx" \
    --backend gl --size 8x8 -o "$models/gl.png"
fi
expect_ok "export-shader of a srgb model" "$stochtex" export-shader "$models/srgb.stx" \
  -o "$models/export" &&
  if tr "\n" " " <"$models/export/README.md" | grep -q "returns linear light" &&
    [[ -f $models/export/decoded.exr && -f $models/export/removed.exr ]]; then pass; else
    fail "export-shader of a srgb model" "$(ls "$models/export")"
  fi
expect_ok "export-web of a srgb model" "$stochtex" export-web "$models/srgb.stx" \
  -o "$models/web" &&
  if grep -rq '"colour": "linear"' "$models/web"; then pass; else
    fail "export-web of a srgb model" "no manifest says its colour is linear"
  fi

# gaussian: the ADSN of a photo's sRGB values is written as a srgb model's render would be, into
# a PNG as it is with an sRGB chunk and into PFM (as OpenEXR) decoded to linear light, never the
# encoded values in a linear file (a washed-out texture in Blender, issue 38).
for space in auto data; do
  expect_ok "gaussian --colour-space $space to PFM" "$stochtex" gaussian "$nuts" --size 32x32 \
    --seed 3 --colour-space "$space" -o "$models/gaussian_$space.pfm"
done
if python3 - "$models" <<'PY'; then pass; else fail "gaussian's PFM holds linear light" "see above"; fi
import struct, sys
def pfm(path):
    data = open(path, "rb").read()
    header = data.split(b"\n", 3)
    assert header[0] == b"Pf", "a grey PFM"
    count = len(header[3]) // 4
    return struct.unpack(("<" if float(header[2]) < 0 else ">") + "%df" % count, header[3])
decode = lambda v: v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4
linear, encoded = pfm(sys.argv[1] + "/gaussian_auto.pfm"), pfm(sys.argv[1] + "/gaussian_data.pfm")
error = max(abs(decode(e) - l) for e, l in zip(encoded, linear))
print("gaussian to PFM: largest |decode(data) - auto|", error)
assert error < 1e-5 and max(abs(e - l) for e, l in zip(encoded, linear)) > 0.1
PY
expect_ok "gaussian to PNG" "$stochtex" gaussian "$nuts" --size 32x32 -o "$models/gaussian.png" &&
  if grep -q sRGB "$models/gaussian.png"; then pass; else
    fail "gaussian of a photo to PNG" "the PNG has no sRGB chunk"
  fi

# A material's colour maps take a colour space; its data maps refuse one.
rock=$textures/../materials/rock_sandstone
expect_ok "a material's albedo in sRGB" "$stochtex" analyze --map albedo:srgb="$rock/albedo.png" \
  --map roughness="$rock/roughness.png" -m tiling -o "$models/material.stx"
expect_ok "info of a srgb albedo" "$stochtex" info "$models/material.stx" &&
  if grep -q '^map       albedo (colour, 3 channels, srgb)' "$work/stdout" &&
    grep -q '^map       roughness (scalar, 1 channel, data)' "$work/stdout"; then pass; else
    fail "info of a srgb albedo" "$(cat "$work/stdout")"
  fi
expect_error "a roughness map in sRGB" 1 "roughness" "$stochtex" analyze \
  --map albedo="$rock/albedo.png" --map roughness:srgb="$rock/roughness.png" -m tiling \
  -o "$out/x.stx"
expect_error "a map qualifier that is neither" 2 "oklab" "$stochtex" analyze \
  --map albedo:oklab="$rock/albedo.png" -m tiling -o "$out/x.stx"
expect_error "render --colour-space of a material" 2 "--colour-space" "$stochtex" render \
  "$models/material.stx" --colour-space srgb --size 8x8 -o "$out/m_{map}.png"

summary
