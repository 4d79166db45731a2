#!/usr/bin/env bash
# Mix: texton noise mixing (texton paper section 7), its GPU twin and shader export.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

grey=$textures/metal_grey_256.png
mixfast=(-p support=16 -p iterations=5 --steps 3 "${data[@]}")
if expect_ok "mix" "$stochtex" mix "$exemplar" "$textures/wood_planks_256.png" "${mixfast[@]}" \
  --ramp 0,64 --direction 1,1 -o "$models/mix.stx"; then
  expect_file "mix writes the model" "$models/mix.stx"
fi
expect_ok "info of a mix" "$stochtex" info "$models/mix.stx" && if ! grep -q "texton_mix" \
  "$work/stdout" || ! grep -q "steps = 3" "$work/stdout"; then
  fail "info of a mix" "no method or steps line"
fi
expect_ok "render a mix, 1 thread" "$stochtex" render "$models/mix.stx" -o "$models/m1.pfm" \
  --size 48x20 --seed 5 --threads 1
expect_ok "render a mix, 2 threads" "$stochtex" render "$models/mix.stx" -o "$models/m2.pfm" \
  --size 48x20 --seed 5 --threads 2 --tile 16
if cmp -s "$models/m1.pfm" "$models/m2.pfm"; then pass; else
  fail "a mix renders the same bytes whatever the threads" "m1.pfm and m2.pfm differ"
fi
expect_ok "mix with a mask" "$stochtex" mix "$grey" "$textures/nuts_grey_256.png" "${mixfast[@]}" \
  --mask "$grey" --mask-scale 0.5 -o "$models/mask.stx"
expect_error "mix of grey with colour" 1 "nuts_grey_256.png" "$stochtex" mix \
  "$textures/nuts_grey_256.png" "$exemplar" "${mixfast[@]}" -o "$out/x.stx"
expect_error "mix with a colour mask" 1 "grass_lawn_128.png" "$stochtex" mix "$grey" \
  "$textures/nuts_grey_256.png" "${mixfast[@]}" --mask "$exemplar" -o "$out/x.stx"
expect_error "mix --ramp nan" 2 "--ramp" "$stochtex" mix "$grey" "$grey" --ramp nan,4 \
  -o "$out/x.stx"
expect_error "mix --ramp inf" 2 "--ramp" "$stochtex" mix "$grey" "$grey" --ramp 0,1e999 \
  -o "$out/x.stx"
expect_error "mix --ramp of one point" 2 "ramp_end" "$stochtex" mix "$grey" "$grey" --ramp 3,3 \
  -o "$out/x.stx"
expect_error "mix --direction 0,0" 2 "direction" "$stochtex" mix "$grey" "$grey" \
  --direction 0,0 -o "$out/x.stx"
expect_error "mix --steps 1" 2 "steps" "$stochtex" mix "$grey" "$grey" --steps 1 -o "$out/x.stx"
expect_error "mix -p mni=nan" 2 "mni" "$stochtex" mix "$grey" "$grey" -p mni=nan -o "$out/x.stx"
expect_error "mix of a missing file" 1 "missing.png" "$stochtex" mix "$grey" \
  "$inputs/missing.png" -o "$out/x.stx"
# Beyond the memory budget (docs/design.md §9), refused before any work: 4096² colour exemplars
# analysed at full size (--scale-input 1; by default they are downscaled to texton's side, as in
# cli_photos.sh), and 2048² ones into 256 textons of 1024² (about 23 GB of textons).
expect_error "mix beyond the memory budget" 2 "ramp_4096.png" "$stochtex" mix \
  "$inputs/ramp_4096.png" "$inputs/ramp_4096.png" --scale-input 1 -o "$out/x.stx"
expect_error "mix into textons beyond the memory budget" 2 "--steps" "$stochtex" mix \
  "$inputs/ramp_2048.png" "$inputs/ramp_2048.png" --steps 256 -p support=1024 --scale-input 1 \
  -o "$out/x.stx"
if [[ -e $out/x.stx ]]; then fail "a refused mix writes nothing" "x.stx exists"; else pass; fi
# The GPU twin: both fields on the gl backend (both --gl-filter values run the exact path), and
# the export in every language. The mix model's exact render is the one GL render of texton_mix
# that STOCHTEX_CLI_GL=one-per-method keeps.
for field in mix mask; do
  if [[ $field == mix ]] || ! gl_skipped 1 "render a $field model on the gl backend"; then
    expect_ok "render a $field model on the gl backend" "$stochtex" render "$models/$field.stx" \
      -o "$models/$field-gl.png" --size 48x20 --seed 5 --backend gl --scale 2
  fi
  if ! gl_skipped 2 "render a $field model, --gl-filter hardware"; then
    expect_ok "render a $field model, --gl-filter hardware" "$stochtex" render \
      "$models/$field.stx" -o "$models/$field-glh.png" --size 48x20 --seed 5 --backend gl \
      --gl-filter hardware --scale 2
    if cmp -s "$models/$field-gl.png" "$models/$field-glh.png"; then pass; else
      fail "a $field model's hardware filter is its exact path" \
        "$field-gl.png and $field-glh.png differ"
    fi
  fi
  for language in $languages; do
    expect_ok "export-shader of a $field model, $language" "$stochtex" export-shader \
      "$models/$field.stx" -o "$out/$field-$language" --language "$language"
    expect_file "the $field export's README" "$out/$field-$language/README.md"
  done
done
expect_file "the mask export's mask data" "$out/mask-glsl/texton_mix_mask.exr"

summary
