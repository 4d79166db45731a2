#!/usr/bin/env bash
# The measurements and pictures of docs/inputs.md: a phone-sized JPEG (4000x3000, quality 90, made
# by cjpeg from data/exemplars/rock_sandstone_512.png, a CC0 photo, cropped to 512x384 and
# enlarged bilinearly, as a phone's photo of a rock face, one scene at large scale) goes through
# `stochtex analyze` with each method at its defaults, timed (the downscale to the method's analysis
# side included), then `stochtex synth` renders 384x384 of each into docs/images/inputs/.
# Prints the table of docs/inputs.md. Usage: bash scripts/photo_pictures.sh [build-dir]
set -euo pipefail
gallery=inputs
source "$(dirname "$0")/gallery_common.sh"
photo=$work/photo_4000x3000.jpg
/usr/bin/python3 - "$textures/rock_sandstone_512.png" "$work/photo.ppm" <<'PY'
import struct, sys, zlib
import numpy
data = open(sys.argv[1], "rb").read()
pos, idat = 8, b""
while pos < len(data):
    length, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + length]
    pos += 12 + length
    if kind == b"IHDR":
        width, height = struct.unpack(">II", body[:8])
    elif kind == b"IDAT":
        idat += body
raw, stride = zlib.decompress(idat), 3 * width
rows, previous, i = [], bytearray(stride), 0
for _ in range(height):  # PNG filters (8-bit RGB)
    kind, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
    i += 1 + stride
    for x in range(stride):
        a = line[x - 3] if x >= 3 else 0
        b = previous[x]
        c = previous[x - 3] if x >= 3 else 0
        if kind == 1: line[x] = (line[x] + a) & 255
        elif kind == 2: line[x] = (line[x] + b) & 255
        elif kind == 3: line[x] = (line[x] + (a + b) // 2) & 255
        elif kind == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(bytes(line))
    previous = line
# The crop's 512x384 pixels, enlarged bilinearly to 4000x3000 (pixel centres aligned).
image = numpy.frombuffer(b"".join(rows[:384]), dtype=numpy.uint8).reshape(384, 512, 3) / 1.0
out_width, out_height = 4000, 3000
def axis(size, out):
    position = (numpy.arange(out) + 0.5) * size / out - 0.5
    low = numpy.clip(numpy.floor(position).astype(int), 0, size - 1)
    return low, numpy.minimum(low + 1, size - 1), numpy.clip(position - low, 0.0, 1.0)
y0, y1, fy = axis(384, out_height)
x0, x1, fx = axis(512, out_width)
rows_lerped = image[y0] * (1 - fy)[:, None, None] + image[y1] * fy[:, None, None]
big = rows_lerped[:, x0] * (1 - fx)[None, :, None] + rows_lerped[:, x1] * fx[None, :, None]
with open(sys.argv[2], "wb") as f:
    f.write(b"P6\n%d %d\n255\n" % (out_width, out_height))
    f.write(numpy.round(big).astype(numpy.uint8).tobytes())
PY
cjpeg -quality 90 "$work/photo.ppm" >"$photo"
echo "| method | analysed as | analyse (s) |"
echo "|---|---|---|"
for method in $("$stochtex" methods | sed -n 's/^\([a-z]*\): .*/\1/p'); do
  start=$(date +%s.%N)
  "$stochtex" analyze "$photo" --method "$method" -o "$work/$method.stx" 2>"$work/log"
  end=$(date +%s.%N)
  size=$(sed -n 's/.*downscaled to \([0-9]*x[0-9]*\).*/\1/p' "$work/log")
  chose=$(sed -n 's/.*--method auto chose \([a-z]*\):.*/ (chose \1)/p' "$work/log")
  awk -v m="$method$chose" -v s="${size:-4000x3000}" -v t0="$start" -v t1="$end" \
    'BEGIN { printf "| %s | %s | %.1f |\n", m, s, t1 - t0 }'
  # auto's picture is the chosen method's.
  [ "$method" = auto ] && continue
  "$stochtex" render "$work/$method.stx" -o "$out/photo_$method.png" --size 384x384 --seed 1 \
    2>/dev/null
done
echo "pictures written to $out"
