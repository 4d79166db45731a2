#pragma once
// The range of a model's array values (docs/design.md §7), one bound for every method, so that
// every model that loads renders finite values.

#include <algorithm>
#include <cmath>
#include <span>

namespace stochtex {

// Analysis of exemplars within +-kMaxExemplarValue (1e6, stochtex.hpp) writes arrays up to about
// 1e7 (measured on grass_lawn_128 scaled to +-1e6: gabor's colour matrix 9.5e6, tiling's look-up
// table 7.4e5, lrp's amplitudes 3.2e4), so 1e12 leaves a margin of 1e5. Evaluation multiplies at
// most two array values and sums at most ~1e5 terms: 1e12^2 * 1e5 = 1e29 stays far below float's
// 3.4e38, where values near 1e38 overflowed to Inf and NaN (issue 19's fuzzing).
inline constexpr float kMaxModelValue = 1e12f;

// True when every value is finite and within +-kMaxModelValue (false for NaN).
inline bool within_model_range(std::span<const float> values) {
  return std::all_of(values.begin(), values.end(),
                     [](float v) { return std::abs(v) <= kMaxModelValue; });
}

}  // namespace stochtex
