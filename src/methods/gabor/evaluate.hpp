#pragma once
// Building blocks of the Gabor noise evaluator (GaborModel::evaluate and its vectorised twin,
// simd.hpp), in the restricted subset of docs/design.md §4 (uint32/float, flat arrays, no
// allocation) that the GLSL twin mirrors.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/float_math.hpp"
#include "core/hash.hpp"
#include "methods/gabor/alias.hpp"
#include "methods/gabor/model.hpp"
#include "stochtex/model.hpp"

namespace stochtex::gabor {

// The kernel of one grid filtered by one footprint, as the evaluator uses it: envelope
// exp(-x^T E x), frequency map omega' = F omega, attenuation exp(-omega^T D omega), amplitude
// gain, the radius the envelope reaches and the thinning level. Shared by the planar and the
// surface evaluators (the latter with the footprint projected on the tangent plane).
struct KernelFilter {
  double e00, e01, e11;
  double f00 = 1.0, f01 = 0.0, f11 = 1.0;
  double d00 = 0.0, d01 = 0.0, d11 = 0.0;
  double gain = 1.0;
  double reach = 0.0;
  bool filtered = false;
  bool skip = true;  // the filtered grid adds nothing at this footprint
  int level = 0;
};

// The kernel parameters of one grid (section 6.2): its frequencies and alias table.
struct GridKernels {
  const float* frequency_x;
  const float* frequency_y;
  const float* probability;
  const std::uint32_t* alias;
  std::uint32_t count;

  // The draws of one impulse's kernel (draw_alias's two, the phase's one): a caller that rejects
  // the impulse before its kernel skips them (CounterRng::skip).
  static constexpr std::uint32_t kDraws = 3;
  // One impulse's kernel: a frequency by the alias method, then a uniform phase, in this order.
  void draw(CounterRng& rng, float& wx, float& wy, float& phase) const noexcept {
    const std::uint32_t k = draw_alias(probability, alias, count, rng);
    phase = rng.uniform();
    wx = frequency_x[k];
    wy = frequency_y[k];
  }
};

// The cells of a grid that meet p + [-reach, reach]^2, cells of side `cell_size`: 64-bit indices
// (docs/design.md §4).
struct CellRange {
  std::int64_t first_x, last_x, first_y, last_y;
};

inline CellRange cell_range(Vec2d p, double reach, double cell_size) noexcept {
  return {static_cast<std::int64_t>(std::floor((p.x - reach) / cell_size)),
          static_cast<std::int64_t>(std::floor((p.x + reach) / cell_size)),
          static_cast<std::int64_t>(std::floor((p.y - reach) / cell_size)),
          static_cast<std::int64_t>(std::floor((p.y + reach) / cell_size))};
}

// The offset of p from the corner of cell `cell` along one axis, taken in double before going to
// float, so p = 1e7 is as precise as p = 0 (docs/design.md §4).
inline float cell_offset(double p, std::int64_t cell, double cell_size) noexcept {
  return static_cast<float>(p - static_cast<double>(cell) * cell_size);
}

// KernelFilter in float, for the inner loop.
struct KernelShape {
  float ex, exy, ey;
  float fxx, fxy, fyy;
  float dxx, dxy, dyy;
  bool filtered;

  explicit KernelShape(const KernelFilter& k)
      : ex(static_cast<float>(k.e00)),
        exy(static_cast<float>(2.0 * k.e01)),
        ey(static_cast<float>(k.e11)),
        fxx(static_cast<float>(k.f00)),
        fxy(static_cast<float>(k.f01)),
        fyy(static_cast<float>(k.f11)),
        dxx(static_cast<float>(k.d00)),
        dxy(static_cast<float>(2.0 * k.d01)),
        dyy(static_cast<float>(k.d11)),
        filtered(k.filtered) {}

  // The filtered kernel of frequency (wx, wy) and phase at offset (dx, dy) = x - x_i, into
  // `value`, tapered to 0 at the cut (kTaperScale); false where the envelope is truncated (beyond
  // e^-pi). exp and cos are the float polynomials of core/float_math.hpp, which the vectorised and
  // GLSL twins share.
  bool at(float wx, float wy, float phase, float dx, float dy, float& value) const noexcept;
  // at() in two halves, for a caller that decides on the envelope before it draws the kernel: the
  // envelope's exponent at offset (dx, dy) (truncated from kPiF up), then the kernel there.
  float envelope(float dx, float dy) const noexcept;
  float value(float envelope, float wx, float wy, float phase, float dx, float dy) const noexcept;
};

// The kernel's arithmetic that the scalar reference and the vectorised evaluator (simd.cpp)
// share, source for source: kernel_envelope and kernel_value.
#include "methods/gabor/kernel.inc"

// kernel.inc's operations on single values: the scalar reference.
struct ScalarOps {
  static float constant(float c) noexcept { return c; }
  static float min(float a, float b) noexcept { return std::min(a, b); }
  static float neg(float v) noexcept { return -v; }
  static float exp(float v) noexcept { return exp_float(v); }
  static float cos(float v) noexcept { return cos_turns(v); }
};

inline float KernelShape::envelope(float dx, float dy) const noexcept {
  return kernel_envelope(ScalarOps{}, *this, dx, dy);
}

inline float KernelShape::value(float envelope, float wx, float wy, float phase, float dx,
                                float dy) const noexcept {
  return kernel_value(ScalarOps{}, *this, filtered, envelope, wx, wy, phase, dx, dy);
}

inline bool KernelShape::at(float wx, float wy, float phase, float dx, float dy,
                            float& value) const noexcept {
  const float e = envelope(dx, dy);
  if (e >= kPiF) return false;
  value = this->value(e, wx, wy, phase, dx, dy);
  return true;
}

}  // namespace stochtex::gabor
