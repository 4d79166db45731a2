#pragma once
// The sRGB transfer function (IEC 61966-2-1) on floats, extended beyond [0, 1] so that it stays
// invertible on the values a Gaussian model renders: below the linear segment's end it continues
// the line (negative values decode to negative light), above 1 it continues the power curve.

#include <cmath>

namespace stochtex {

// Encoded value -> linear light.
inline float srgb_decode(float v) noexcept {
  return v <= 0.04045f ? v * (1.0f / 12.92f) : std::pow((v + 0.055f) * (1.0f / 1.055f), 2.4f);
}
inline double srgb_decode(double v) noexcept {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

// Linear light -> encoded value.
inline float srgb_encode(float l) noexcept {
  return l <= 0.0031308f ? l * 12.92f : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}
inline double srgb_encode(double l) noexcept {
  return l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
}

}  // namespace stochtex
