#!/usr/bin/env bash
# `--method auto` (docs/comparison.md "Which method?"): analyze and synth choose the method from
# the exemplar's measures and say why in one line; what auto cannot measure is refused in one
# sentence. The choice itself is tested in tests/unit/method_choice_test.cpp.
# usage and running by hand: tests/cli/common.sh.
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
load_shared

expect_ok "analyze -m auto: a Gaussian texture gets texton" \
  "$stochtex" analyze "$exemplar" -m auto -o "$models/auto_grass.stx" &&
  if grep -qF "grass_lawn_128.png: --method auto chose texton: close to Gaussian (band-pass kurtosis 3.0 at 2 px" "$work/stderr" &&
    "$stochtex" info "$models/auto_grass.stx" | grep -q "texton"; then pass; else
    fail "auto's choice and reason are said, and the model is texton's" "$(cat "$work/stderr")"
  fi
expect_ok "synth -m auto: a periodic fabric gets tiling" \
  "$stochtex" synth "$textures/plaid_fabric_256.png" -m auto --size 64x64 -o "$models/auto_plaid.png" &&
  if grep -qF -- "--method auto chose tiling: periodic (78% of its power in spectral peaks" "$work/stderr" &&
    [[ -s $models/auto_plaid.png ]]; then pass; else
    fail "the periodic reason is said and the render written" "$(cat "$work/stderr")"
  fi
expect_ok "analyze -m auto of data (a height-like grey map)" \
  "$stochtex" analyze "$textures/nuts_grey_256.png" --colour-space data -m auto -o "$models/auto_nuts.stx" &&
  if grep -qF -- "--method auto chose tiling: far from Gaussian (band-pass kurtosis 4.9 at 1 px" "$work/stderr" &&
    grep -qF "not tileable: a repeat of it steps 6.9 times" "$work/stderr"; then pass; else
    fail "the structure and the wrap are said" "$(cat "$work/stderr")"
  fi
if "$stochtex" methods | grep -q "^auto: "; then pass; else
  fail "stochtex methods lists auto" "$("$stochtex" methods | tail -n 2)"
fi

expect_error "auto with --target" 2 "--method auto" \
  "$stochtex" analyze --target "any" -m auto -o "$out/x.stx"
expect_error "auto with a material's maps" 2 "--method auto" \
  "$stochtex" analyze --map "albedo=$exemplar" -m auto -o "$out/x.stx"
expect_error "auto with -p" 2 "--method auto" \
  "$stochtex" analyze "$exemplar" -m auto -p iterations=3 -o "$out/x.stx"

summary
