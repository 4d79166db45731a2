#!/usr/bin/env bash
# The comparison report (a part of the good paths, on its own as its longest run): every method on
# two exemplars, its pages and pictures, its JSON numbers, and the same pictures whatever the
# threads.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

# The comparison report: two small exemplars, every method, small renders. The pages and pictures
# must exist and the JSON summary must hold finite, plausible numbers for every synthesis, and
# --method auto's choice for every exemplar.
report=$models/report
second=$textures/nuts_grey_256.png
if expect_json "report --json" "$stochtex" report "$exemplar" "$second" -o "$report" \
  --size 32x32 --json; then
  for file in index.html report.json grass_lawn_128.html nuts_grey_256.html \
    grass_lawn_128/exemplar.png grass_lawn_128/gaussian_spectrum.png \
    nuts_grey_256/gabor.png nuts_grey_256/tiling_histogram.png; do
    expect_file "report writes $file" "$report/$file"
  done
  if python3 - "$work/stdout" $methods <<'PY'; then
import json, math, sys
doc = json.load(open(sys.argv[1]))
assert [e["name"] for e in doc["exemplars"]] == ["grass_lawn_128", "nuts_grey_256"]
assert doc["failures"] == 0 and doc["wall_seconds"] > 0 and doc["cpu_seconds"] > 0
for exemplar in doc["exemplars"]:
    names = [s["name"] for s in exemplar["syntheses"]]
    assert names == ["gaussian"] + sys.argv[2:], names
    assert 0 < exemplar["histogram_error_floor"] < 0.5
    for synthesis in exemplar["syntheses"]:
        for key in ("spectral_error", "histogram_error", "mean_error", "covariance_error",
                    "nonstationarity"):
            assert math.isfinite(synthesis[key]) and 0 <= synthesis[key] < 5, (key, synthesis)
        if synthesis["name"] != "gaussian":
            assert synthesis["analysis_seconds"] > 0 and synthesis["ns_per_sample"] > 0, synthesis
        assert math.isfinite(synthesis["structure_error"]), synthesis
# --method auto's choice per exemplar; the structure error of the Gaussian version: near 0 for
# the Gaussian grass, 1 - 3 / 4.9 = 0.39 for the nuts' edges (band-pass kurtosis 4.9).
grass, nuts = doc["exemplars"]
assert grass["auto"]["method"] == "texton" and nuts["auto"]["method"] == "tiling", doc
assert nuts["auto"]["reason"].startswith("tiling: far from Gaussian ("), nuts["auto"]
assert grass["syntheses"][0]["structure_error"] < 0.2 < nuts["syntheses"][0]["structure_error"]
PY
    pass
  else
    fail "report JSON numbers" "the summary's numbers are not sane"
  fi
  # No number is marked best (the lowest spectral error can be a blur); auto's reason is shown.
  if ! grep -q "<b>[0-9]" "$report/index.html" &&
    grep -qF "tiling: far from Gaussian (" "$report/index.html" &&
    grep -qF "chose tiling: far from Gaussian (" "$report/nuts_grey_256.html"; then pass; else
    fail "report pages" "a value is bolded as best, or auto's choice is missing"
  fi
fi
# Same inputs and seed, other threads and the exemplar twice: the same pictures, byte for byte.
if expect_ok "report --threads 1, an exemplar twice" "$stochtex" report "$exemplar" "$exemplar" \
  -o "$models/report1" --size 32x32 --methods tiling,texton --threads 1 --thumbnail 16; then
  expect_file "report --thumbnail writes thumbnails" \
    "$models/report1/thumbnails/grass_lawn_128_2_tiling.png"
  for picture in tiling.png texton.png texton_spectrum.png gaussian.png; do
    if cmp -s "$report/grass_lawn_128/$picture" "$models/report1/grass_lawn_128/$picture" &&
      cmp -s "$report/grass_lawn_128/$picture" "$models/report1/grass_lawn_128_2/$picture"; then
      pass
    else
      fail "report is deterministic ($picture)" "the pictures differ between runs"
    fi
  done
fi

summary
