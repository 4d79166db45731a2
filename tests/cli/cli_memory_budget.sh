#!/usr/bin/env bash
# Memory budget and hostile sizes (docs/design.md §9).
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

# Requests beyond the memory budget are refused before any work, naming the option to change, and
# tiny files declaring huge contents are refused without allocating them.
expect_parse_error "render --threads 1024" "$stochtex" render "$gabor_model" -o "$out/x.png" \
  --size 64x64 --threads 1024
expect_error "render --supersample 64 on 8 threads" 2 "--threads" \
  "$stochtex" render "$gabor_model" -o "$out/x.png" --size 512x512 --supersample 64 --threads 8
expect_error "synth --supersample 64 on 8 threads" 2 "--supersample" \
  "$stochtex" synth "$exemplar" -m gabor -o "$out/x.png" --size 512x512 --supersample 64 \
  --threads 8
expect_error "gaussian --size 8192x8192" 2 "--size" \
  "$stochtex" gaussian "$exemplar" -o "$out/x.png" --size 8192x8192
python3 - "$inputs" <<'PY'
import struct, sys, zlib
folder = sys.argv[1]
def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))
signature = b'\x89PNG\r\n\x1a\n'
ihdr = chunk(b'IHDR', struct.pack('>IIBBBBB', 1, 1, 8, 0, 0, 0, 0))
with open(folder + '/text_bomb.png', 'wb') as f:  # a tEXt chunk declaring 2^31 - 1 bytes
    f.write(signature + ihdr + struct.pack('>I', 0x7fffffff) + b'tEXt')
with open(folder + '/huge_rgba16.png', 'wb') as f:  # 8192x8192 RGBA16 in 68 bytes
    f.write(signature + chunk(b'IHDR', struct.pack('>IIBBBBB', 8192, 8192, 16, 6, 0, 0, 0)) +
            chunk(b'IDAT', zlib.compress(bytes(16))) + chunk(b'IEND', b''))
PY
for hostile in text_bomb.png huge_rgba16.png; do
  expect_error "gaussian of $hostile" 1 "$hostile" \
    "$stochtex" gaussian "$inputs/$hostile" -o "$out/x.png" --size 16x16
done

summary
