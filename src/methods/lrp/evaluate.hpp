#pragma once
// Building blocks of the LRP noise evaluator, in the restricted subset of DESIGN.md section 4
// (uint32/float, flat arrays, no allocation) so that they can be mirrored in GLSL.

#include <cmath>
#include <cstdint>

namespace stochtex::lrp {

// cos(2 pi t) for t in turns. The argument is reduced to [0, 1/2] by dropping its integer part
// (a truncating conversion: std::floor and std::nearbyint are library calls on baseline x86-64)
// and by the symmetries of the cosine, folded to [0, 1/4], and the even Taylor polynomial of
// degree 12 is evaluated there (|2 pi t| <= pi / 2; truncation error (pi/2)^14 / 14! = 6e-9, below
// float rounding). Several times faster than std::cos and exactly reproducible in GLSL. Valid for
// |t| < 2^31 (the evaluator's arguments stay below a few thousand turns).
inline float cos_turns(float t) noexcept {
  t -= static_cast<float>(static_cast<std::int32_t>(t));
  t = std::abs(t);
  t = t > 0.5f ? 1.0f - t : t;
  const float sign = t > 0.25f ? -1.0f : 1.0f;
  t = t > 0.25f ? 0.5f - t : t;
  constexpr float two_pi = 6.283185307179586f;
  const float x = two_pi * t;
  const float x2 = x * x;
  const float p =
      1.0f +
      x2 * (-1.0f / 2.0f +
            x2 * (1.0f / 24.0f + x2 * (-1.0f / 720.0f + x2 * (1.0f / 40320.0f +
                                                              x2 * (-1.0f / 3628800.0f +
                                                                    x2 * (1.0f / 479001600.0f))))));
  return sign * p;
}

// Frequency clamping (section 6.4): the weight of a cosine of `cycles` cycles per output pixel
// along the footprint's longer axis. A frequency below the Nyquist limit 1/2 is kept whole, so a
// render at scale 1 keeps the exemplar's whole spectrum (no frequency of the model exceeds 1/2
// cycle per exemplar pixel); above it the weight falls linearly to 0 at one cycle per pixel:
// cosines that the sampling rate cannot represent fade out instead of aliasing at full strength.
inline constexpr float kClampStart = 0.5f;
inline constexpr float kClampEnd = 1.0f;
inline float clamp_weight(float cycles) noexcept {
  const float weight = (kClampEnd - cycles) * (1.0f / (kClampEnd - kClampStart));
  return weight <= 0.0f ? 0.0f : (weight >= 1.0f ? 1.0f : weight);
}

}  // namespace stochtex::lrp
