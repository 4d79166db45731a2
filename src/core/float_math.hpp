#pragma once
// Float special functions as short polynomials, for evaluators whose vectorised twins must return
// the same bytes on every SIMD target (docs/design.md §4): libm's cosf and expf have no
// bit-identical vector version; these are written once (core/float_math.inc) for floats here and
// for SIMD vectors in core/simd_math.hpp, and are accurate to float rounding. Truncating
// conversions only: std::floor and std::nearbyint are library calls on baseline x86-64.

#include <bit>
#include <cmath>
#include <cstdint>

namespace stochtex {

inline constexpr float kTwoPi = 6.283185307179586f;

inline constexpr float kExpFloor = -87.0f;
inline constexpr float kExpCeiling = 88.0f;

// float_math.inc's operations on single floats.
struct FloatOps {
  static float constant(float c) noexcept { return c; }
  static float truncate(float v) noexcept {
    return static_cast<float>(static_cast<std::int32_t>(v));
  }
  static float abs(float v) noexcept { return std::abs(v); }
  static float above(float a, float b, float x, float y) noexcept { return a > b ? x : y; }
  static float below(float a, float b, float x, float y) noexcept { return a < b ? x : y; }
  static std::int32_t to_int(float v) noexcept { return static_cast<std::int32_t>(v); }
  static float to_float(std::int32_t i) noexcept { return static_cast<float>(i); }
  static float power_of_two(std::int32_t i) noexcept {
    return std::bit_cast<float>(static_cast<std::uint32_t>(i + 127) << 23u);
  }
};

#include "core/float_math.inc"

// cos(2 pi t) for t in turns, |t| < 2^31 (float_math.inc).
inline float cos_turns(float t) noexcept {
  return cos_turns_of(FloatOps{}, t);
}

// e^x within 2 ulp for -87 <= x <= 88, 0 below, e^88 above; x must not be NaN (float_math.inc).
inline float exp_float(float x) noexcept {
  return exp_float_of(FloatOps{}, x);
}

}  // namespace stochtex
