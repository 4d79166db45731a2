#pragma once
// Float special functions as short polynomials, for evaluators whose vectorised twins must return
// the same bytes on every SIMD target (docs/design.md §4): libm's cosf and expf have no
// bit-identical vector version, these are one statement each in both (core/simd_math.hpp) and are
// accurate to float rounding. Truncating conversions only: std::floor and std::nearbyint are
// library calls on baseline x86-64.

#include <bit>
#include <cmath>
#include <cstdint>

namespace stochtex {

inline constexpr float kTwoPi = 6.283185307179586f;

// cos(2 pi t) for t in turns. The argument is reduced to [0, 1/2] by dropping its integer part and
// by the symmetries of the cosine, folded to [0, 1/4], and the even Taylor polynomial of degree 12
// is evaluated there (|2 pi t| <= pi / 2; truncation error (pi/2)^14 / 14! = 6e-9, below float
// rounding). The reduction in turns is exact. Valid for |t| < 2^31.
inline float cos_turns(float t) noexcept {
  t -= static_cast<float>(static_cast<std::int32_t>(t));
  t = std::abs(t);
  t = t > 0.5f ? 1.0f - t : t;
  const float sign = t > 0.25f ? -1.0f : 1.0f;
  t = t > 0.25f ? 0.5f - t : t;
  const float x = kTwoPi * t;
  const float x2 = x * x;
  const float p =
      1.0f +
      x2 * (-1.0f / 2.0f +
            x2 * (1.0f / 24.0f + x2 * (-1.0f / 720.0f + x2 * (1.0f / 40320.0f +
                                                              x2 * (-1.0f / 3628800.0f +
                                                                    x2 * (1.0f / 479001600.0f))))));
  return sign * p;
}

// e^x as Cephes' expf (S. L. Moshier, Cephes Mathematical Library, "expf.c"): x = k ln 2 + r with
// k the nearest integer to x / ln 2 (halves away from zero, by a truncating conversion) and ln 2
// split in two so that k ln2_hi is exact, |r| <= ln 2 / 2, then e^r by its degree-7 minimax
// polynomial and 2^k by the exponent bits. Within 2 ulp of e^x for -87 <= x <= 88; 0 below -87
// (e^-87 = 1.6e-38, the bottom of the normal floats), e^88 above 88; x must not be NaN.
inline constexpr float kExpFloor = -87.0f;
inline constexpr float kExpCeiling = 88.0f;
inline float exp_float(float x) noexcept {
  const float clamped = x < kExpFloor ? kExpFloor : (x > kExpCeiling ? kExpCeiling : x);
  const float t = clamped * 1.44269504088896341f;
  const auto k = static_cast<std::int32_t>(t + (t < 0.0f ? -0.5f : 0.5f));
  const auto kf = static_cast<float>(k);
  const float r = (clamped - kf * 0.693359375f) - kf * -2.12194440e-4f;
  const float r2 = r * r;
  const float p = ((((((1.9875691500e-4f * r + 1.3981999507e-3f) * r + 8.3334519073e-3f) * r +
                      4.1665795894e-2f) *
                         r +
                     1.6666665459e-1f) *
                        r +
                    5.0000001201e-1f) *
                       r2 +
                   r) +
                  1.0f;
  const float scale = std::bit_cast<float>(static_cast<std::uint32_t>(k + 127) << 23u);
  return x < kExpFloor ? 0.0f : p * scale;
}

}  // namespace stochtex
