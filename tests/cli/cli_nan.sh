#!/usr/bin/env bash
# NaN, infinities and huge values (issue 19).
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

# Every numeric option refuses NaN, infinities and out-of-range values with one sentence (exit 2,
# nothing written); positions stay within +-2^32, the precise range (docs/design.md §4), for every
# method; exemplar values beyond +-1e6 are refused naming the file (exit 1).
for method in $methods; do
  each=$models/every_$method.stx
  [[ -s $each ]] || continue
  render_each=("$stochtex" render "$each" -o "$out/x.pfm" --size 16x16)
  expect_error "render $method --scale nan" 2 "--scale nan" "${render_each[@]}" --scale nan
  expect_error "render $method --scale -nan" 2 "--scale" "${render_each[@]}" --scale -nan
  expect_parse_error "render $method --scale inf" "${render_each[@]}" --scale inf
  expect_error "render $method --origin 1e300,-1e300" 2 "1e300" \
    "${render_each[@]}" --origin 1e300,-1e300
  expect_error "render $method --origin 1e19,0" 2 "1e19" "${render_each[@]}" --origin 1e19,0
  expect_error "render $method --origin past 2^32 by the grid" 2 "4294967296" \
    "${render_each[@]}" --origin 4294967000,0 --scale 100
  for origin in nan,0 0,inf -inf,0 1e400,0; do
    expect_error "render $method --origin $origin" 2 "$origin" "${render_each[@]}" --origin "$origin"
  done
  expect_error "render $method --backend gl --scale nan" 2 "--scale" \
    "${render_each[@]}" --scale nan --backend gl
  # At the edge of the range the render is finite.
  if expect_ok "render $method at the edge of the range" "$stochtex" render "$each" \
    -o "$models/edge_$method.pfm" --size 8x8 --origin 4294967000,-4294967000 --scale 10; then
    if python3 - "$models/edge_$method.pfm" <<'PY'; then
import array, math, sys
data = open(sys.argv[1], "rb").read().split(b"\n", 3)[3]  # after "PF", the size, the scale
values = array.array("f", data)
assert len(values) > 0 and all(math.isfinite(v) for v in values)
PY
      pass
    else
      fail "render $method at the edge of the range is finite" "non-finite values"
    fi
  fi
done
for value in nan inf -1 1e99 4294967296; do
  expect_parse_error "render --seed $value" "$stochtex" render "$model" -o "$out/x.png" \
    "${size[@]}" --seed "$value"
  expect_parse_error "gaussian --seed $value" "$stochtex" gaussian "$exemplar" -o "$out/x.png" \
    "${size[@]}" --seed "$value"
  expect_parse_error "analyze --analysis-seed $value" "$stochtex" analyze "$exemplar" \
    "${analyze_to[@]}" -m texton --analysis-seed "$value"
  expect_parse_error "report --seed $value" "$stochtex" report "$exemplar" -o "$out/report" \
    --seed "$value"
done
for option in --threads --supersample --tile; do
  for value in nan inf 1e99; do
    expect_parse_error "render $option $value" "$stochtex" render "$model" -o "$out/x.png" \
      "${size[@]}" "$option" "$value"
  done
done
for option in --threads --thumbnail; do
  for value in nan inf; do
    expect_parse_error "report $option $value" "$stochtex" report "$exemplar" -o "$out/report" \
      "$option" "$value"
  done
done
expect_error "synth --scale nan" 2 "--scale" "$stochtex" synth "$exemplar" "${fast[@]}" \
  -o "$out/x.png" "${size[@]}" --scale nan
expect_error "synth --origin 1e300,0" 2 "1e300" "$stochtex" synth "$exemplar" "${fast[@]}" \
  -o "$out/x.png" "${size[@]}" --origin 1e300,0
for value in nanxnan infx16 16x1e9; do
  expect_error "render --size $value" 2 "$value" "$stochtex" render "$model" -o "$out/x.png" \
    --size "$value"
  expect_error "gaussian --size $value" 2 "$value" "$stochtex" gaussian "$exemplar" \
    -o "$out/x.png" --size "$value"
  expect_error "report --size $value" 2 "$value" "$stochtex" report "$exemplar" \
    -o "$out/report" --size "$value"
done
for value in nan inf -inf 1e300; do
  expect_error "-p mni=$value" 2 "mni" "$stochtex" analyze "$exemplar" "${analyze_to[@]}" \
    -m texton -p mni="$value"
  expect_error "--target ring radius $value" 2 "radius" "$stochtex" analyze --method lrp \
    "${analyze_to[@]}" --target "ring:radius=$value,width=0.02"
  expect_error "--target ring mean $value" 2 "mean" "$stochtex" analyze --method lrp \
    "${analyze_to[@]}" --target "ring:radius=0.2,width=0.02,mean=$value"
  expect_error "--target ring variance $value" 2 "variance" "$stochtex" analyze --method lrp \
    "${analyze_to[@]}" --target "ring:radius=0.2,width=0.02,variance=$value"
done
if [[ -s $gabor_model ]]; then
  for option in --rotate --scale --magnitude --bandwidth; do
    for value in nan inf -inf; do
      expect_error "edit $option $value" 2 "$option" "$stochtex" edit "$gabor_model" \
        "${edit_to[@]}" "$option" "$value"
    done
  done
  for option in --magnitude --bandwidth; do
    expect_error "edit $option 1e300" 2 "$option" "$stochtex" edit "$gabor_model" \
      "${edit_to[@]}" "$option" 1e300
  done
  for value in nan,0 0,inf 1e300,0; do
    expect_error "edit --translate $value" 2 "$value" "$stochtex" edit "$gabor_model" \
      "${edit_to[@]}" --translate "$value"
  done
fi
# nan.pfm with its NaN pixel made 3e38: finite, but beyond the exemplar value range.
python3 -c 'import struct, sys
data = open(sys.argv[1], "rb").read()
open(sys.argv[2], "wb").write(data.replace(struct.pack("<f", float("nan")), struct.pack("<f", 3e38)))' \
  "$inputs/nan.pfm" "$inputs/huge.pfm"
expect_error "gaussian of a PFM with 3e38" 1 "huge.pfm' has a value beyond" \
  "$stochtex" gaussian "$inputs/huge.pfm" -o "$out/x.png" --size 16x16
for method in $methods; do
  expect_error "synth -m $method of a PFM with 3e38" 1 "huge.pfm' has a value beyond" \
    "$stochtex" synth "$inputs/huge.pfm" -m "$method" -o "$out/x.png" --size 16x16
done

summary
