#!/usr/bin/env bash
# Photos as artists have them (issue 37): a JPEG larger than a method analyses by default is
# downscaled in linear light and a note says so; --crop and --scale-input choose the part and the
# scale; bad choices are refused in one sentence; --progress shows progress in a log. The decoders themselves are tested in
# tests/unit/image_formats_test.cpp and fuzzed in tests/fuzz/image_fuzz.cpp.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

# A 1600x1200 photo-like JPEG (cjpeg, libjpeg-turbo-progs): smooth blobs and grain.
photo=$inputs/photo.jpg
python3 - "$work/photo.ppm" <<'PY'
import math, random, sys
random.seed(37)
width, height = 1600, 1200
blobs = [[128 + 60 * math.sin(0.05 * x + c) for x in range(width)] for c in range(3)]
rows = []
for y in range(height):
    s = 40 * math.sin(0.031 * y)
    row = bytearray(3 * width)
    for c in range(3):
        base = blobs[c]
        for x in range(c, 3 * width, 3):
            row[x] = max(0, min(255, int(base[x // 3] + s + random.randint(-30, 30))))
    rows.append(bytes(row))
with open(sys.argv[1], "wb") as f:
    f.write(b"P6\n%d %d\n255\n" % (width, height) + b"".join(rows))
PY
cjpeg -quality 90 "$work/photo.ppm" >"$photo"
fast=(-m texton -p support=32 -p iterations=5)

expect_ok "analyze a JPEG photo larger than the method's side" \
  "$stochtex" analyze "$photo" "${fast[@]}" -o "$models/photo.stx" &&
  if grep -qF "is 1600x1200 pixels, more than texton analyses by default (1024 on the longer side): it is analysed downscaled to 1024x768 (a factor of 0.64); give --scale-input 1" "$work/stderr" &&
    grep -qF 'photo.jpg: srgb (JPEG: sRGB by default)' "$work/stderr"; then pass; else
    fail "the downscale and the colour are said" "$(cat "$work/stderr")"
  fi
expect_ok "analyze a crop of it: no downscale" \
  "$stochtex" analyze "$photo" "${fast[@]}" --crop 512x384+700+500 -o "$models/crop.stx" &&
  if ! grep -q "downscaled" "$work/stderr"; then pass; else
    fail "a crop within the side is analysed as it is" "$(cat "$work/stderr")"
  fi
expect_ok "analyze at a chosen scale: no note" \
  "$stochtex" analyze "$photo" "${fast[@]}" --scale-input 0.25 -o "$models/quarter.stx" &&
  if ! grep -q "downscaled" "$work/stderr"; then pass; else
    fail "a chosen scale needs no note" "$(cat "$work/stderr")"
  fi
# mix reads each exemplar down to the region texton analyses, as analyze does.
mixfast=(-p support=16 -p iterations=5 --steps 3)
expect_ok "mix a JPEG photo larger than texton's side" \
  "$stochtex" mix "$photo" "$textures/grass_lawn_128.png" "${mixfast[@]}" -o "$models/mix_photo.stx" &&
  if grep -qF "is 1600x1200 pixels, more than texton analyses by default (1024 on the longer side): it is analysed downscaled to 1024x768" "$work/stderr"; then pass; else
    fail "mix says the downscale" "$(cat "$work/stderr")"
  fi
expect_ok "mix crops of two photos at a chosen scale: no note" \
  "$stochtex" mix "$photo" "$photo" "${mixfast[@]}" --crop-a 256x256+0+0 --crop-b 256x256+1300+900 \
  --scale-input 0.5 -o "$models/mix_crops.stx" &&
  if ! grep -q "downscaled" "$work/stderr"; then pass; else
    fail "mix of chosen crops and scale needs no note" "$(cat "$work/stderr")"
  fi
expect_error "mix with a crop outside B" 2 "photo.jpg" \
  "$stochtex" mix "$photo" "$photo" "${mixfast[@]}" --crop-b 1000x1000+900+0 -o "$out/x.stx"
expect_parse_error "mix --scale-input 0" \
  "$stochtex" mix "$photo" "$photo" --scale-input 0 -o "$out/x.stx"
expect_ok "synth a JPEG photo in one command" \
  "$stochtex" synth "$photo" "${fast[@]}" -o "$out/photo_synth.png" --size 256x256 &&
  expect_file "synth wrote its PNG" "$out/photo_synth.png"

# Tileability: a photo cut from a larger scene is said to be one; a tileable exemplar is not.
expect_ok "analyze a non-tileable exemplar" "$stochtex" analyze "$textures/water_caustics_256.png" \
  "${fast[@]}" -o "$models/water.stx" &&
  if grep -qF "water_caustics_256.png: not tileable: a repeat of it steps 4.6 times as much at its wrap as between neighbouring pixels (x 4.6, y 4.4)" "$work/stderr"; then pass; else
    fail "a non-tileable exemplar is said to be one" "$(cat "$work/stderr")"
  fi
expect_ok "synth says it too" "$stochtex" synth "$textures/water_caustics_256.png" "${fast[@]}" \
  -o "$work/water.png" --size 64x64 &&
  if grep -qF "water_caustics_256.png: not tileable" "$work/stderr" &&
    grep -qF "water_caustics_256.png: srgb (no colour chunk: sRGB by default)" "$work/stderr"; then
    pass
  else
    fail "synth says what analyze says" "$(cat "$work/stderr")"
  fi
expect_ok "analyze a tileable exemplar" "$stochtex" analyze "$textures/grass_lawn_256.png" \
  "${fast[@]}" -o "$models/grass.stx" &&
  if ! grep -q "not tileable" "$work/stderr"; then pass; else
    fail "a tileable exemplar is not said to be otherwise" "$(cat "$work/stderr")"
  fi

# Progress in a log (stderr not a terminal): lines with --progress, wherever it is given; none
# without.
expect_ok "compare --progress in a log" "$stochtex" compare "$out/photo_synth.png" \
  "$out/photo_synth.png" --progress &&
  if grep -qx 'compare: 100%' "$work/stderr"; then pass; else
    fail "--progress prints progress lines" "$(cat "$work/stderr")"
  fi
expect_ok "compare without --progress in a log" "$stochtex" compare "$out/photo_synth.png" \
  "$out/photo_synth.png" &&
  if [[ ! -s $work/stderr ]]; then pass; else
    fail "no progress in a log by default" "$(cat "$work/stderr")"
  fi
find "$out" -mindepth 1 -delete

expect_error "a crop outside the photo" 2 "photo.jpg" \
  "$stochtex" analyze "$photo" "${fast[@]}" --crop 1000x1000+900+0 -o "$out/x.stx"
expect_error "a crop that is not WxH+X+Y" 2 "--crop" \
  "$stochtex" analyze "$photo" "${fast[@]}" --crop 100x -o "$out/x.stx"
expect_parse_error "--scale-input 0" \
  "$stochtex" analyze "$photo" "${fast[@]}" --scale-input 0 -o "$out/x.stx"
expect_parse_error "--scale-input 2" \
  "$stochtex" analyze "$photo" "${fast[@]}" --scale-input 2 -o "$out/x.stx"
head -c 5000 "$photo" >"$inputs/cut.jpg"
expect_error "a truncated JPEG" 1 "cut.jpg" \
  "$stochtex" analyze "$inputs/cut.jpg" "${fast[@]}" -o "$out/x.stx"

summary
