#!/usr/bin/env bash
# `render --periodic` (docs/render.md "Periodic renders"): every method's tileable bake of a size
# that is no multiple of its cells or of the exemplar tiles (analysed as an exemplar, its wrap
# steps are the interior's) where the default render does not; --region and --threads give the
# same bytes; synth takes it too; what cannot be periodic is refused in one sentence, by render
# and by render-mesh.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

# Zoomed in (--scale 0.5) neighbouring pixels are close, so a seam stands out: the default
# renders of grass step 1.6 to 2.9 times the interior at their wrap (1.1 to 1.4 at --scale 1).
bake=(--size 200x136 --seed 5 --scale 0.5)
rock=$textures/../materials/rock_sandstone
# The wrap steps of an image as `stochtex info` says them for a model analysed from it.
wrap_of() {
  "$stochtex" analyze "$1" -m tiling -o "$1.stx" >/dev/null 2>&1 && "$stochtex" info "$1.stx" |
    grep "^wrap step"
}
for method in texton tiling lrp gabor; do
  expect_ok "render --periodic ($method)" "$stochtex" render "$models/every_$method.stx" \
    -o "$models/periodic_$method.png" "${bake[@]}" --periodic &&
    if wrap_of "$models/periodic_$method.png" | grep -q "the exemplar tiles"; then pass; else
      fail "the $method bake tiles" "$(wrap_of "$models/periodic_$method.png")"
    fi
  expect_ok "render ($method)" "$stochtex" render "$models/every_$method.stx" \
    -o "$models/default_$method.png" "${bake[@]}" &&
    if wrap_of "$models/default_$method.png" | grep -q "is not tileable"; then pass; else
      fail "the default $method render does not tile" "$(wrap_of "$models/default_$method.png")"
    fi
done

# A region of the bake and other threads: the same bytes as the whole bake's pixels.
expect_ok "render --periodic .pfm" "$stochtex" render "$models/every_texton.stx" \
  -o "$models/whole.pfm" "${bake[@]}" --periodic --threads 1
expect_ok "render --periodic --threads 3 --tile 17" "$stochtex" render "$models/every_texton.stx" \
  -o "$models/threads.pfm" "${bake[@]}" --periodic --threads 3 --tile 17
if cmp -s "$models/whole.pfm" "$models/threads.pfm"; then pass; else
  fail "--periodic renders the same bytes whatever the threads and tiles" "the files differ"
fi
expect_ok "render --periodic --region" "$stochtex" render "$models/every_tiling.stx" \
  -o "$models/region.pfm" "${bake[@]}" --periodic --region 150,100,50,36
expect_ok "render --periodic (tiling)" "$stochtex" render "$models/every_tiling.stx" \
  -o "$models/tiling_whole.pfm" "${bake[@]}" --periodic
if /usr/bin/python3 - "$models/tiling_whole.pfm" "$models/region.pfm" <<'PY'; then pass; else
import sys
def read(path):
    data = open(path, "rb").read()
    header = data.split(b"\n", 3)
    width, height = map(int, header[1].split())
    channels = 3 if header[0] == b"PF" else 1
    return width, height, channels, data[len(b"\n".join(header[:3])) + 1:]
w, h, c, whole = read(sys.argv[1])
rw, rh, _, region = read(sys.argv[2])
row = 4 * c
# PFM rows run bottom to top: region row y (from its top) is whole row 100 + y.
for y in range(rh):
    a = whole[((h - 1 - (100 + y)) * w + 150) * row:][: rw * row]
    b = region[((rh - 1 - y) * rw) * row:][: rw * row]
    if a != b:
        sys.exit(1)
PY
  fail "a --periodic region equals the whole bake's pixels" "the pixels differ"
fi

expect_ok "synth --periodic" "$stochtex" synth "$exemplar" "${fast[@]}" -o "$models/synth.png" \
  "${bake[@]}" --periodic --supersample 2 &&
  if wrap_of "$models/synth.png" | grep -q "the exemplar tiles"; then pass; else
    fail "the supersampled synth bake tiles" "$(wrap_of "$models/synth.png")"
  fi

# A material: each map tiles, the normal map derived from the periodic height too.
expect_ok "analyze a material with a derived normal map" "$stochtex" analyze \
  --map normal="$rock/normal.png" --map height="$rock/height.png" -m texton -p iterations=3 \
  -p support=32 -o "$models/material.stx"
expect_ok "render --periodic a material" "$stochtex" render "$models/material.stx" \
  -o "$models/material_{map}.png" "${bake[@]}" --periodic
for map in normal height; do
  if wrap_of "$models/material_$map.png" | grep -q "the exemplar tiles"; then pass; else
    fail "the material's $map map tiles" "$(wrap_of "$models/material_$map.png")"
  fi
done

expect_error "--periodic on the GL backend" 2 "--backend cpu" \
  "$stochtex" render "$model" -o "$out/gl.png" "${bake[@]}" --periodic --backend gl
expect_ok "mix" "$stochtex" mix "$exemplar" "$textures/wood_planks_256.png" -p support=16 \
  -p iterations=5 --steps 3 "${data[@]}" -o "$models/mix.stx"
expect_error "--periodic of a texton mix" 2 "texton mix cannot render periodic" \
  "$stochtex" render "$models/mix.stx" -o "$out/mix.png" "${bake[@]}" --periodic
expect_ok "analyze lrp with a structure component" "$stochtex" analyze "$exemplar" -m lrp \
  -p ratio=0.2 -p cosines=4 -p strata=2 -o "$models/structure.stx"
expect_error "--periodic of an lrp structure" 2 "structure component cannot render periodic" \
  "$stochtex" render "$models/structure.stx" -o "$out/structure.png" "${bake[@]}" --periodic
# render-mesh --periodic (docs/meshes.md) refuses them with the same sentences, before the mesh
# is read.
expect_error "render-mesh --periodic of a texton mix" 2 "texton mix cannot render periodic" \
  "$stochtex" render-mesh "$inputs/missing.obj" --model "$models/mix.stx" -o "$out/mix.png" \
  --mapping uv --periodic
expect_error "render-mesh --periodic of an lrp structure" 2 \
  "structure component cannot render periodic" "$stochtex" render-mesh "$inputs/missing.obj" \
  --model "$models/structure.stx" -o "$out/structure.png" --mapping uv --periodic

summary
