#!/usr/bin/env bash
# Bad inputs: missing, truncated, degenerate and corrupt files, out-of-range parameters and sizes,
# unwritable outputs; each refused with its exit code and one sentence, nothing written.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

expect_error "missing input file" 1 "missing.png" \
  "$stochtex" analyze "$inputs/missing.png" -m texton "${analyze_to[@]}"
expect_error "text file named .png" 1 "x.png" \
  "$stochtex" analyze "$inputs/x.png" -m texton "${analyze_to[@]}"
expect_error "truncated PNG" 1 "truncated.png" \
  "$stochtex" analyze "$inputs/truncated.png" -m texton "${analyze_to[@]}"
expect_error "1x1 PNG" 1 "one_pixel.png" \
  "$stochtex" analyze "$inputs/one_pixel.png" -m texton "${analyze_to[@]}"
expect_error "constant PNG" 1 "constant.png" \
  "$stochtex" analyze "$inputs/constant.png" -m texton "${analyze_to[@]}"
expect_error "PFM with a NaN" 1 "nan.pfm" \
  "$stochtex" analyze "$inputs/nan.pfm" -m texton "${analyze_to[@]}"
# 2048² in colour, every pixel asked for: about 4.1 GB for gabor's analysis (docs/design.md §9),
# refused before any work (by default it would be analysed downscaled to 512², cli_photos.sh).
expect_error "analysis beyond the memory budget" 2 "ramp_2048.png" \
  "$stochtex" analyze "$inputs/ramp_2048.png" -m gabor --scale-input 1 "${analyze_to[@]}"
expect_error "synth of a truncated PNG" 1 "truncated.png" \
  "$stochtex" synth "$inputs/truncated.png" "${fast[@]}" -o "$out/synth.png" "${size[@]}"
expect_error "gaussian of a constant PNG" 1 "constant.png" \
  "$stochtex" gaussian "$inputs/constant.png" -o "$out/gaussian.png" "${size[@]}"
expect_error "compare with a missing image" 1 "missing.png" \
  "$stochtex" compare "$exemplar" "$inputs/missing.png"

expect_error "unknown method" 2 "nosuch" \
  "$stochtex" analyze "$exemplar" -m nosuch "${analyze_to[@]}"
for param in support=1 mni=0 order=2; do
  expect_error "out-of-range -p $param" 2 "${param%%=*}" \
    "$stochtex" analyze "$exemplar" -m texton -p "$param" "${analyze_to[@]}"
done
expect_error "non-numeric -p mni=abc" 2 "mni" \
  "$stochtex" analyze "$exemplar" -m texton -p mni=abc "${analyze_to[@]}"
# Enumerations take their names; a wrong name is refused with the list of names.
expect_error "unknown choice -p blend=foo" 2 "histogram, variance, linear" \
  "$stochtex" analyze "$exemplar" -m tiling -p blend=foo "${analyze_to[@]}"
expect_error "unknown parameter" 2 "nosuch" \
  "$stochtex" analyze "$exemplar" -m texton -p nosuch=1 "${analyze_to[@]}"
expect_error "-p without =" 2 "support" \
  "$stochtex" analyze "$exemplar" -m texton -p support "${analyze_to[@]}"
# Usage errors come before reading files: a bad parameter wins over a missing input.
expect_error "bad parameter and missing input" 2 "support" \
  "$stochtex" analyze "$inputs/missing.png" -m texton -p support=1 "${analyze_to[@]}"

for bad_size in 0x10 abc 100000x100000; do
  expect_error "render --size $bad_size" 2 "$bad_size" \
    "$stochtex" render "$model" -o "$out/render.png" --size "$bad_size"
done
expect_error "synth --size 0x10" 2 "0x10" \
  "$stochtex" synth "$exemplar" "${fast[@]}" -o "$out/synth.png" --size 0x10
expect_error "gaussian --size abc" 2 "abc" \
  "$stochtex" gaussian "$exemplar" -o "$out/gaussian.png" --size abc
expect_error "render --origin abc" 2 "abc" \
  "$stochtex" render "$model" -o "$out/render.png" "${size[@]}" --origin abc

expect_parse_error "unknown subcommand" "$stochtex" nosuch
expect_parse_error "analyze without --method" "$stochtex" analyze "$exemplar" "${analyze_to[@]}"
expect_parse_error "render without --size" "$stochtex" render "$model" -o "$out/render.png"
expect_parse_error "render --threads -1" \
  "$stochtex" render "$model" -o "$out/render.png" "${size[@]}" --threads -1
expect_parse_error "render --scale 0" \
  "$stochtex" render "$model" -o "$out/render.png" "${size[@]}" --scale 0

render_to=(-o "$out/render.png" "${size[@]}")
expect_error "render of a missing model" 1 "missing.stx" \
  "$stochtex" render "$inputs/missing.stx" "${render_to[@]}"
expect_error "info of a missing model" 1 "missing.stx" "$stochtex" info "$inputs/missing.stx"
expect_error "render of an image as a model" 1 "x.png" \
  "$stochtex" render "$inputs/x.png" "${render_to[@]}"
if [[ -s $model ]]; then
  head -c 100 "$model" >"$inputs/truncated.stx"
  expect_error "render of a truncated model" 1 "truncated.stx" \
    "$stochtex" render "$inputs/truncated.stx" "${render_to[@]}"
  # One byte flipped in the magic, the version, the header length, the arrays and the checksum.
  model_bytes=$(wc -c <"$model")
  for offset in 0 8 12 $((model_bytes / 2)) $((model_bytes - 1)); do
    corrupt=$inputs/corrupt_$offset.stx
    cp "$model" "$corrupt"
    byte=$(od -An -tu1 -j "$offset" -N 1 "$corrupt" | tr -d ' ')
    # shellcheck disable=SC2059 # the format is the escaped byte itself
    printf "$(printf '\\%03o' $((byte ^ 255)))" |
      dd of="$corrupt" bs=1 seek="$offset" count=1 conv=notrunc status=none
    expect_error "render of a model with byte $offset flipped" 1 "corrupt_$offset.stx" \
      "$stochtex" render "$corrupt" "${render_to[@]}"
  done
else
  fail "truncated and corrupt models" "analyze wrote no model to damage"
fi

expect_error "render into a missing folder" 1 "missing" \
  "$stochtex" render "$model" -o "$out/missing/render.png" "${size[@]}"
expect_error "analyze into a missing folder" 1 "missing" \
  "$stochtex" analyze "$exemplar" "${fast[@]}" -o "$out/missing/model.stx"
expect_error "gaussian into a missing folder" 1 "missing" \
  "$stochtex" gaussian "$exemplar" -o "$out/missing/gaussian.png" "${size[@]}"
expect_error "render to an unknown extension" 2 "render.bmpx" \
  "$stochtex" render "$model" -o "$out/render.bmpx" "${size[@]}"

expect_error "edit of a texton model" 2 "texton" "$stochtex" edit "$model" "${edit_to[@]}"
expect_error "edit of a missing model" 1 "missing.stx" \
  "$stochtex" edit "$inputs/missing.stx" "${edit_to[@]}"
expect_error "edit without -o" 2 "-o" "$stochtex" edit "$gabor_model" --rotate 10
expect_error "edit --bandwidth 3" 2 "--bandwidth" \
  "$stochtex" edit "$gabor_model" "${edit_to[@]}" --bandwidth 3
expect_error "edit --translate abc" 2 "abc" \
  "$stochtex" edit "$gabor_model" "${edit_to[@]}" --translate abc
expect_error "edit --magnitude -1" 2 "--magnitude" \
  "$stochtex" edit "$gabor_model" "${edit_to[@]}" --magnitude -1
expect_error "edit removing every Gaussian" 2 "no Gaussian" \
  "$stochtex" edit "$gabor_model" "${edit_to[@]}" --magnitude 0
expect_error "edit into a missing folder" 1 "missing" \
  "$stochtex" edit "$gabor_model" -o "$out/missing/edited.stx"
expect_parse_error "edit --group nosuch" "$stochtex" edit "$gabor_model" "${edit_to[@]}" \
  --group nosuch
expect_error "report of a missing exemplar" 1 "missing.png" \
  "$stochtex" report "$exemplar" "$inputs/missing.png" -o "$out/report"
expect_error "report of a truncated PNG" 1 "truncated.png" \
  "$stochtex" report "$inputs/truncated.png" -o "$out/report"
expect_error "report of a constant PNG" 1 "constant.png" \
  "$stochtex" report "$inputs/constant.png" -o "$out/report"
expect_error "report into a folder under a file" 1 "x.png" \
  "$stochtex" report "$exemplar" -o "$inputs/x.png/report"
expect_error "report with an unknown method" 2 "nosuch" \
  "$stochtex" report "$exemplar" -o "$out/report" --methods texton,nosuch
expect_error "report --size 8x8" 2 "8x8" "$stochtex" report "$exemplar" -o "$out/report" --size 8x8
expect_parse_error "report without exemplars" "$stochtex" report -o "$out/report"
expect_parse_error "report without -o" "$stochtex" report "$exemplar"

summary
