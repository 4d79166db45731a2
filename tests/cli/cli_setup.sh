#!/usr/bin/env bash
# The setup of the other sections (CTest fixture cli_shared): the test images of "inputs" and the
# models several sections read, made once and saved into SHARED_DIR, each made by a check of its
# own: the registry's methods, the texton model most checks render, every method's default model
# and the gabor model that edit works on.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

# A setup that fails leaves nothing for the sections to read, not the folder of an earlier run.
rm -rf "$shared/in" "$shared/models" "$shared/methods"

# --- inputs -------------------------------------------------------------------------------------

printf 'this is not an image\n' >"$inputs/x.png"
head -c 2000 "$exemplar" >"$inputs/truncated.png"
# Minimal 8-bit PNGs: a 1x1 grey image, a constant 16x16 one, and 2048² and 4096² colour ramps.
python3 - "$inputs" <<'EOF'
import struct, sys, zlib

def png(path, width, height, row, colour_type=0):
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n"
                + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress((b"\x00" + row) * height))
                + chunk(b"IEND", b""))

png(sys.argv[1] + "/one_pixel.png", 1, 1, bytes([128]))
png(sys.argv[1] + "/constant.png", 16, 16, bytes([128]) * 16)
png(sys.argv[1] + "/ramp_2048.png", 2048, 2048, bytes(range(256)) * 24, colour_type=2)
png(sys.argv[1] + "/ramp_4096.png", 4096, 4096, bytes(range(256)) * 48, colour_type=2)
EOF
# A 4x4 greyscale PFM (negative scale: little-endian) alternating 0.25 and 0.75, one pixel NaN.
{
  printf 'Pf\n4 4\n-1.0\n'
  for i in $(seq 0 15); do
    if [[ $i -eq 5 ]]; then
      printf '\x00\x00\xc0\x7f'
    elif ((i % 2)); then
      printf '\x00\x00\x40\x3f'
    else
      printf '\x00\x00\x80\x3e'
    fi
  done
} >"$inputs/nan.pfm"


# --- models -------------------------------------------------------------------------------------

expect_json "methods --json" "$stochtex" methods --json
# Every method of the registry, never a list written here: a new method is covered by itself.
methods=$(python3 -c 'import json, sys; print(" ".join(m["name"] for m in json.load(sys.stdin)))' \
  <"$work/stdout")
if [[ -z $methods ]]; then fail "methods --json lists methods" "no method names"; fi
expect_ok "languages" "$stochtex" languages && if ! grep -q "^glsl: GLSL 4.50" "$work/stdout"; then
  fail "languages lists glsl" "stdout does not start a line with glsl: GLSL 4.50"
fi
expect_json "languages --json" "$stochtex" languages --json
# Every export language of the table (src/gl/languages.hpp), never a list written here.
languages=$(python3 -c 'import json, sys; print(" ".join(l["name"] for l in json.load(sys.stdin)))' \
  <"$work/stdout")
if [[ -z $languages ]]; then fail "languages --json lists languages" "no language names"; fi
if expect_ok "analyze" "$stochtex" analyze "$exemplar" "${fast[@]}" -o "$model"; then
  expect_file "analyze writes the model" "$model"
fi
for method in $methods; do
  expect_ok "analyze -m $method" "$stochtex" analyze "$exemplar" -m "$method" \
    -o "$models/every_$method.stx"
done
expect_ok "analyze gabor" "$stochtex" analyze "$exemplar" -m gabor -p iterations=30 \
  "${data[@]}" -o "$gabor_model"

# Saved only when every check passed; the list of methods, written last, says the folder is whole.
if [[ ${#failed[@]} -eq 0 ]]; then
  if ! mkdir -p "$shared" || ! cp -R "$inputs" "$shared/in" || ! cp -R "$models" "$shared/models" ||
    ! echo "$languages" >"$shared/languages" || ! echo "$methods" >"$shared/methods"; then
    echo "$script: cannot write $shared" >&2
    exit 2
  fi
fi

summary
