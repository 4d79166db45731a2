#pragma once
// Building blocks of the LRP noise evaluator, in the restricted subset of docs/design.md §4
// (uint32/float, flat arrays, no allocation) so that they can be mirrored in GLSL.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/float_math.hpp"
#include "core/hash.hpp"
#include "core/periodic.hpp"
#include "methods/lrp/window.hpp"
#include "stochtex/model.hpp"

namespace stochtex::lrp {

// Limits on a stratum a model file may hold (model.cpp, structure_model.cpp): its lattice spacing
// Delta_S = T sqrt(J_S / (2 |S|)) >= 1/2 for any stratum, and its amplitude.
inline constexpr double kMinSpacing = 0.25;
inline constexpr double kMaxSpacing = 1e6;
inline constexpr double kMaxAmplitude = 1e6;

// Frequency clamping (section 6.4): the weight of a cosine of `cycles` cycles per output pixel
// along the footprint's longer axis. A frequency below the Nyquist limit 1/2 is kept whole, so a
// render at scale 1 keeps the exemplar's whole spectrum (no frequency of the model exceeds 1/2
// cycle per exemplar pixel); above it the weight falls linearly to 0 at one cycle per pixel:
// cosines that the sampling rate cannot represent fade out instead of aliasing at full strength.
// One draw per cosine (section 4.3): its low kPickBits bits pick a frequency of the sub-stratum by
// multiply-shift, its top 32 - kPickBits bits are the phase, on a grid of kPhaseStep turns.
inline constexpr std::uint32_t kPickBits = 20;
inline constexpr std::uint32_t kPickMask = (1u << kPickBits) - 1u;
inline constexpr float kPhaseStep = 1.0f / static_cast<float>(1u << (32u - kPickBits));

inline constexpr float kClampStart = 0.5f;
inline constexpr float kClampEnd = 1.0f;

// The arithmetic that the scalar reference and the vectorised evaluator (simd.cpp) share, source
// for source: the window, frequency clamping, a node's cosines and a stratum's term.
#include "methods/lrp/kernel.inc"

// kernel.inc's operations on single values: the scalar reference.
struct ScalarOps {
  static float constant(float c) noexcept { return c; }
  static float abs(float v) noexcept { return std::abs(v); }
  static float sqrt(float v) noexcept { return std::sqrt(v); }
  static float min(float a, float b) noexcept { return std::min(a, b); }
  static float cos(float v) noexcept { return cos_turns(v); }
  static float select(bool condition, float a, float b) noexcept { return condition ? a : b; }
  static bool none(bool condition) noexcept { return !condition; }
};

inline float clamp_weight(float cycles) noexcept {
  return clamp_weight(ScalarOps{}, cycles);
}

// w at squared distance `r2` (in units of the lattice spacing) from the polynomial form
// (window.hpp), 0 beyond the window's radius.
inline float window_from_square(const std::array<float, kWindowTerms>& coefficients,
                                float r2) noexcept {
  return window_from_square(ScalarOps{}, coefficients, r2);
}

// The lattice node nearest (u, v), in lattice units, as 64-bit indices, and the offset from it,
// formed in double before going to float: p = 1e7 is as precise as p = 0 (docs/design.md §4).
struct NearestNode {
  std::int64_t x;
  std::int64_t y;
  float offset_x;
  float offset_y;
};

inline NearestNode nearest_node(double u, double v) noexcept {
  const double node_x = std::floor(u + 0.5);
  const double node_y = std::floor(v + 0.5);
  return {static_cast<std::int64_t>(node_x), static_cast<std::int64_t>(node_y),
          static_cast<float>(u - node_x), static_cast<float>(v - node_y)};
}

// The tables of a set of random strata (model.hpp's LrpData, or the turbulence's).
struct StratumTables {
  const std::uint32_t* substratum_first;
  const std::uint32_t* substratum_count;
  const float* frequencies;  // (f_x, f_y) pairs, cycles per pixel
  const float* weights;      // one amplitude factor per frequency, or nullptr for 1
};

// The frequency that `draw` picks from sub-stratum k: its low kPickBits bits, uniformly by
// multiply-shift (section 4.3; bias <= count / 2^20).
inline std::uint32_t pick_frequency(const StratumTables& tables, std::uint32_t k,
                                    std::uint32_t draw) noexcept {
  return tables.substratum_first[k] +
         static_cast<std::uint32_t>(
             (static_cast<std::uint64_t>(draw & kPickMask) * tables.substratum_count[k]) >>
             kPickBits);
}

// The phase in turns that `draw` gives: its top 32 - kPickBits bits, on a grid of kPhaseStep.
inline float draw_phase(std::uint32_t draw) noexcept {
  return static_cast<float>(draw >> kPickBits) * kPhaseStep;
}

// Lattice spacing, cosine count and sub-strata of one random stratum, and its random stream.
struct StratumDraw {
  double inverse_spacing;
  float spacing;
  std::uint32_t first_substratum;
  std::uint32_t cosines;
  std::uint32_t stream;  // cell_key(..., Stream::phases) of the stratum
};

struct StratumSum {
  float sum;            // sum_i w_i sum_j a_j cos(2 pi f_ij.(x - x_i) + phi_ij), equation (1)
  float window_square;  // sum_i w_i^2, for the envelope normalisation
};

// The cosines of one lattice node of a stratum, sum_j a_j cos(2 pi f_ij.(x - x_i) + phi_ij), drawn
// from the node's key; (px, py) = x - x_i. Phases are taken relative to the node: with phi uniform
// this is the same random field as cos(2 pi f.x + phi) (section 3.2's Gabor convention), and
// x - x_i stays small wherever x is. `axes` (Filtered only) as stratum_sum's.
template <bool Filtered>
inline float node_sum(const StratumTables& tables, const StratumDraw& stratum, std::uint32_t key,
                      float px, float py, const std::array<float, 4>& axes) noexcept {
  CounterRng rng(key);
  float local = 0.0f;
  for (std::uint32_t j = 0; j < stratum.cosines; ++j) {
    // One draw per cosine, in its own statement (hash.hpp): its top 12 bits are the phase (a
    // 1/4096 turn grid), its low kPickBits = 20 bits pick one frequency of sub-stratum j
    // uniformly by multiply-shift (section 4.3; bias <= count / 2^20).
    const std::uint32_t draw = rng.next();
    const std::uint32_t pick = pick_frequency(tables, stratum.first_substratum + j, draw);
    const float fx = tables.frequencies[2 * pick];
    const float fy = tables.frequencies[2 * pick + 1];
    float c = node_cosine(ScalarOps{}, fx, fy, draw_phase(draw), px, py);
    if constexpr (Filtered) c *= frequency_clamp(ScalarOps{}, fx, fy, axes.data());
    local += tables.weights != nullptr ? tables.weights[pick] * c : c;
  }
  return local;
}

// One random stratum of equation (1) at p, before its amplitude A_S. Lattice nodes on the integer
// multiples of Delta_S (section 3.4), the nearest one found by nearest_node. With |offset| <= 1/2
// per axis the window (radius 1.5) reaches the 3 x 3 nodes around it only:
// I = 9. `axes` (Filtered only): the footprint's axes dpdx, dpdy for frequency clamping (section
// 6.4).
template <bool Filtered>
inline StratumSum stratum_sum(const StratumTables& tables, const StratumDraw& stratum,
                              const std::array<float, kWindowTerms>& window, Vec2d p,
                              const std::array<float, 4>& axes) noexcept {
  const auto [cell_x, cell_y, offset_x, offset_y] =
      nearest_node(p.x * stratum.inverse_spacing, p.y * stratum.inverse_spacing);
  StratumSum result{0.0f, 0.0f};
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const float rx = offset_x - static_cast<float>(dx);
      const float ry = offset_y - static_cast<float>(dy);
      const float w = window_from_square(window, rx * rx + ry * ry);
      if (w <= 0.0f) continue;
      const float local = node_sum<Filtered>(
          tables, stratum, cell_key(cell_x + dx, cell_y + dy, stratum.stream, Stream::phases),
          rx * stratum.spacing, ry * stratum.spacing, axes);
      result.sum += w * local;
      result.window_square += w * w;
    }
  }
  return result;
}

// stratum_sum for a periodic field (core/periodic.hpp): nodes on the multiples of (x.size,
// y.size), each axis's spacing dividing the period, each node's cosines drawn from the node
// wrapped into the period. The window is taken in lattice units, so it stretches with the spacing
// (by at most half a node over the period); phases stay relative to the node.
template <bool Filtered>
inline StratumSum stratum_sum_periodic(const StratumTables& tables, const StratumDraw& stratum,
                                       PeriodicAxis x, PeriodicAxis y,
                                       const std::array<float, kWindowTerms>& window, Vec2d p,
                                       const std::array<float, 4>& axes) noexcept {
  const auto [cell_x, cell_y, offset_x, offset_y] = nearest_node(p.x / x.size, p.y / y.size);
  const auto spacing_x = static_cast<float>(x.size);
  const auto spacing_y = static_cast<float>(y.size);
  StratumSum result{0.0f, 0.0f};
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const float rx = offset_x - static_cast<float>(dx);
      const float ry = offset_y - static_cast<float>(dy);
      const float w = window_from_square(window, rx * rx + ry * ry);
      if (w <= 0.0f) continue;
      const float local = node_sum<Filtered>(
          tables, stratum,
          cell_key(x.wrap(cell_x + dx), y.wrap(cell_y + dy), stratum.stream, Stream::phases),
          rx * spacing_x, ry * spacing_y, axes);
      result.sum += w * local;
      result.window_square += w * w;
    }
  }
  return result;
}

}  // namespace stochtex::lrp
