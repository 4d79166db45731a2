#pragma once
// The texton noise evaluator (sections 3.3, 5 and 8 of the paper), written in the restricted
// subset of DESIGN.md section 4 (uint32/float, flat arrays, no allocation) so that it can be
// mirrored in GLSL.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/hash.hpp"
#include "methods/texton/model.hpp"

namespace stochtex::texton {

// B-spline of degree n centred at 0, from the explicit formula
//   beta_n(x) = 1/n! sum_{j=0}^{n+1} (-1)^j C(n+1, j) (x + (n+1)/2 - j)_+^n.
// Used by the analysis (sampled autocorrelation b of the interpolation kernel) and by tests.
inline double bspline(int degree, double x) {
  if (degree == 0) return std::abs(x) < 0.5 ? 1.0 : (std::abs(x) == 0.5 ? 0.5 : 0.0);
  double sum = 0.0;
  double binomial = 1.0;
  double factorial = 1.0;
  for (int i = 2; i <= degree; ++i) factorial *= i;
  for (int j = 0; j <= degree + 1; ++j) {
    const double t = x + 0.5 * (degree + 1) - j;
    if (t > 0.0) sum += ((j % 2 == 0) ? 1.0 : -1.0) * binomial * std::pow(t, degree);
    binomial = binomial * (degree + 1 - j) / (j + 1);
  }
  return sum / factorial;
}

// Interpolation weights of the texton's B-spline kernel psi of order Order (eq. 3 and section 10)
// at continuous texel coordinate u (texel i is centred on the integer i): returns the first texel
// read and fills Order + 1 weights.
template <int Order>
struct BsplineKernel {
  static constexpr int kTaps = Order + 1;

  static int weights(float u, float* w) noexcept {
    if constexpr (Order == 0) {
      w[0] = 1.0f;
      return static_cast<int>(std::floor(u + 0.5f));
    } else {
      const float cell = std::floor(u);
      const float t = u - cell;
      const int first = static_cast<int>(cell) - (Order - 1) / 2;
      if constexpr (Order == 1) {
        w[0] = 1.0f - t;
        w[1] = t;
      } else if constexpr (Order == 3) {
        const float s = 1.0f - t;
        const float t2 = t * t;
        const float t3 = t2 * t;
        w[0] = s * s * s * (1.0f / 6.0f);
        w[1] = (4.0f - 6.0f * t2 + 3.0f * t3) * (1.0f / 6.0f);
        w[2] = (1.0f + 3.0f * t + 3.0f * t2 - 3.0f * t3) * (1.0f / 6.0f);
        w[3] = t3 * (1.0f / 6.0f);
      } else {
        static_assert(Order == 5, "texton interpolation orders are 0, 1, 3 and 5");
        const float s = 1.0f - t;
        const float t2 = t * t;
        const float t3 = t2 * t;
        const float t4 = t3 * t;
        const float t5 = t4 * t;
        w[0] = s * s * s * s * s * (1.0f / 120.0f);
        w[1] = (26.0f - 50.0f * t + 20.0f * t2 + 20.0f * t3 - 20.0f * t4 + 5.0f * t5) *
               (1.0f / 120.0f);
        w[2] = (66.0f - 60.0f * t2 + 30.0f * t4 - 10.0f * t5) * (1.0f / 120.0f);
        w[3] = (26.0f + 50.0f * t + 20.0f * t2 - 20.0f * t3 - 20.0f * t4 + 10.0f * t5) *
               (1.0f / 120.0f);
        w[4] =
            (1.0f + 5.0f * t + 10.0f * t2 + 10.0f * t3 + 5.0f * t4 - 5.0f * t5) * (1.0f / 120.0f);
        w[5] = t5 * (1.0f / 120.0f);
      }
      return first;
    }
  }
};

// Adds weight * h_level(d) to acc, where h_level is the (prefiltered) texton of one pyramid level
// and d the offset from the impact point in exemplar pixels. Zero outside the level's support.
template <int Order>
inline void accumulate_texton(const PyramidLevel& level, int channels, float dx, float dy,
                              float weight, float* acc) noexcept {
  if (std::abs(dx) >= level.half_width || std::abs(dy) >= level.half_width) return;
  constexpr int kTaps = BsplineKernel<Order>::kTaps;
  float wx[kTaps];
  float wy[kTaps];
  const float inverse_spacing = 1.0f / level.spacing;
  const int x0 = BsplineKernel<Order>::weights((dx - level.first_texel) * inverse_spacing, wx);
  const int y0 = BsplineKernel<Order>::weights((dy - level.first_texel) * inverse_spacing, wy);
  const float* base =
      level.coefficients.data() +
      (static_cast<std::ptrdiff_t>(y0 + kPadding) * level.stride + (x0 + kPadding)) * channels;
  for (int j = 0; j < kTaps; ++j) {
    const float* row = base + static_cast<std::ptrdiff_t>(j) * level.stride * channels;
    for (int i = 0; i < kTaps; ++i) {
      const float w = weight * wy[j] * wx[i];
      for (int c = 0; c < channels; ++c) acc[c] += w * row[i * channels + c];
    }
  }
}

}  // namespace stochtex::texton
