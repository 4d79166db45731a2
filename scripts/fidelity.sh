#!/usr/bin/env bash
# Regenerates docs/fidelity.md: runs the fidelity statistical test (tests/statistical/
# fidelity_test.cpp: every method at its defaults on every shipped gaussian and stochastic
# exemplar, 1024² renders with seeds 1 and 2, against ADSN) and tabulates the numbers it prints.
# The test fails where a method misses its bound; the page is written either way.
# Usage: bash scripts/fidelity.sh [build-dir]
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null || exit 1
cmake --build "$build" --parallel --target stochtex_statistical_tests || exit 1
lines=$(mktemp)
start=$(date +%s)
"$build/tests/stochtex_statistical_tests" --gtest_filter='Shipped/Fidelity.*' | tee "$lines" |
  grep -E '^\[ +(OK|FAILED) +\]' >&2
status=${PIPESTATUS[0]}
/usr/bin/python3 "$root/scripts/fidelity_markdown.py" "$lines" "$(($(date +%s) - start))" \
  >"$root/docs/fidelity.md.tmp" && mv "$root/docs/fidelity.md.tmp" "$root/docs/fidelity.md"
rm -f "$lines"
echo "wrote $root/docs/fidelity.md (the test exited with $status)"
