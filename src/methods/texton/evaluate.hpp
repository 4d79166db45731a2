#pragma once
// The texton noise evaluator (sections 3.3, 5 and 8 of the paper), written in the restricted
// subset of docs/design.md §4 (uint32/float, flat arrays, no allocation) so that it can be
// mirrored in GLSL.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/cell_count.hpp"
#include "core/hash.hpp"
#include "core/level_of_detail.hpp"
#include "core/periodic.hpp"
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

// Most probes along the major axis of an anisotropic footprint, as GPU 8x anisotropic filtering.
inline constexpr int kMaxProbes = 8;
// The level of detail of a footprint of width w is log2(w) - kLodBias (core/level_of_detail.hpp).

// How a footprint is filtered (section 5): the pyramid level(s) and the probes along the major
// axis, as GPU trilinear + anisotropic filtering would choose them. Default = point sample.
struct FilterSetup {
  int level = 0;
  float level_blend = 0.0f;  // weight of level + 1
  int probes = 1;
  float probe_x = 0.0f;  // distance between probes, exemplar pixels
  float probe_y = 0.0f;
  float fade = 1.0f;  // beyond the coarsest level, the fluctuation is faded towards the mean
};

inline FilterSetup filter_setup(const Footprint& footprint, int top_level) noexcept {
  FilterSetup setup;
  const double length_x = std::hypot(footprint.dpdx.x, footprint.dpdx.y);
  const double length_y = std::hypot(footprint.dpdy.x, footprint.dpdy.y);
  const double major = std::max(length_x, length_y);
  const double minor = std::min(length_x, length_y);
  if (!(major > 1.0)) return setup;
  setup.probes =
      static_cast<int>(std::min<double>(kMaxProbes, std::ceil(major / std::max(minor, 1.0))));
  const double width = std::max({major / setup.probes, minor, 1.0});
  double lod = std::max(0.0, std::log2(width) - kLodBias);
  if (lod >= top_level) {
    // Beyond the coarsest level the texton is a single blob: the filtered fluctuation decays like
    // 1 / width (the variance of a box-filtered noise of finite correlation length falls as
    // 1 / area), so it is faded towards the mean.
    setup.fade = static_cast<float>(std::exp2(top_level - lod));
    lod = top_level;
  }
  setup.level = std::min(static_cast<int>(lod), top_level);
  setup.level_blend = setup.level == top_level ? 0.0f : static_cast<float>(lod - setup.level);
  const Vec2d axis = length_x >= length_y ? footprint.dpdx : footprint.dpdy;
  setup.probe_x = static_cast<float>(axis.x / setup.probes);
  setup.probe_y = static_cast<float>(axis.y / setup.probes);
  return setup;
}

// A probe of a footprint: the texton read at (dx, dy) + (x, y) when shifted, else at (dx, dy).
struct ProbeShift {
  bool shifted;
  float x;
  float y;
};

// The pieces of the evaluator that the scalar reference and the vectorised evaluator (simd.cpp)
// share, source for source: bspline_weights and for_each_read.
#include "methods/texton/kernel.inc"

// Interpolation weights of the texton's B-spline kernel psi of order Order (eq. 3 and section 10)
// at continuous texel coordinate u (texel i is centred on the integer i): returns the first texel
// read and fills Order + 1 weights.
template <int Order>
struct BsplineKernel {
  static constexpr int kTaps = Order + 1;

  static int weights(float u, float* w) noexcept {
    return bspline_weights<Order>(ScalarOps{}, u, w);
  }

 private:
  struct ScalarOps {
    static float constant(float c) noexcept { return c; }
    static float floor(float v) noexcept { return std::floor(v); }
    static int to_int(float v) noexcept { return static_cast<int>(v); }
    static int int_constant(int i) noexcept { return i; }
  };
};

// Adds weight * h_level(d) to acc, where h_level is the (prefiltered) texton of one pyramid level
// and d the offset from the impact point in exemplar pixels. Zero outside the level's support.
// The channel count is a template parameter so that `acc` stays in registers.
template <int Order, int Channels>
inline void accumulate_texton(const PyramidLevel& level, float dx, float dy, float weight,
                              float (&acc)[Channels]) noexcept {
  constexpr int channels = Channels;
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

// The texton filtered for one footprint (section 5), summed at impact offsets: the pyramid
// level(s) and probes that filter_setup chose. The planar evaluator, the surface evaluator
// (docs/surface.md) and texton noise mixing (each impulse its own texton, same support and order)
// sum the same filtered textons; only their impulses differ.
template <int Order, int Channels>
class FilteredTexton {
 public:
  // `shape`: any of the textons' pyramids (they share support and order, hence the reach).
  FilteredTexton(const std::vector<PyramidLevel>& shape, const FilterSetup& filter) noexcept
      : filter_(filter),
        fine_level_(filter.level),
        coarse_level_(std::min(filter.level + 1, static_cast<int>(shape.size()) - 1)),
        probe_weight_(1.0f / static_cast<float>(filter.probes)) {
    const PyramidLevel& fine = shape[static_cast<std::size_t>(fine_level_)];
    const PyramidLevel& coarse = shape[static_cast<std::size_t>(coarse_level_)];
    const float probe_extent = 0.5f * static_cast<float>(filter.probes - 1) *
                               std::max(std::abs(filter.probe_x), std::abs(filter.probe_y));
    const float kernel_reach =
        filter.level_blend > 0.0f ? std::max(fine.half_width, coarse.half_width) : fine.half_width;
    reach_ = static_cast<double>(kernel_reach + probe_extent);
  }

  // Half side of the square outside which an impact adds nothing: the kernel's support plus the
  // spread of the probes.
  double reach() const noexcept { return reach_; }
  float fade() const noexcept { return filter_.fade; }

  // Adds weight * (filtered texton)(dx, dy) to acc, (dx, dy) = x - x_i in exemplar pixels, for
  // the texton whose pyramid starts at `pyramid`.
  void add(const PyramidLevel* pyramid, float dx, float dy, float weight,
           float (&acc)[Channels]) const noexcept {
    for_each_read(filter_, pyramid[fine_level_], pyramid[coarse_level_], probe_weight_, weight,
                  [&](const PyramidLevel& level, const ProbeShift& shift, float read_weight) {
                    accumulate_texton<Order, Channels>(level, shift.shifted ? dx + shift.x : dx,
                                                       shift.shifted ? dy + shift.y : dy,
                                                       read_weight, acc);
                  });
  }

  // What add() passes to for_each_read, for the vectorised evaluator's instance of it.
  const FilterSetup& filter() const noexcept { return filter_; }
  int fine_level() const noexcept { return fine_level_; }
  int coarse_level() const noexcept { return coarse_level_; }
  float probe_weight() const noexcept { return probe_weight_; }

  // The noise's value from the sum: (acc - offset) * scale + mean, with constant = mean - offset
  // * scale, and `fade` (filter_setup) scaling the fluctuation only.
  float output(float acc, float scale, float constant, float mean) const noexcept {
    const float noise = acc * scale + constant - mean;
    return mean + filter_.fade * noise;
  }

 private:
  FilterSetup filter_;
  int fine_level_;
  int coarse_level_;
  float probe_weight_;
  double reach_ = 0.0;
};

// The random sign eps_j in {-1, +1} (section 7) of the index-th point of a cell whose sign key is
// cell_key(cell, seed, Stream::signs): the signs come from the cell's own stream, so the points
// are the same with or without them.
inline float point_sign(std::uint32_t sign_key, std::uint32_t index) noexcept {
  return (pcg_hash(sign_key ^ pcg_hash(index)) >> 31u) != 0u ? -1.0f : 1.0f;
}
inline float impulse_sign(std::int64_t cell_x, std::int64_t cell_y, std::uint32_t index,
                          std::uint32_t seed) noexcept {
  return point_sign(cell_key(cell_x, cell_y, seed, Stream::signs), index);
}

// Generators of the shifted rank-1 lattice of the balanced points in a cell: the R2 sequence's
// (1/g, 1/g^2, g the plastic number, the root of g^3 = g + 1), whose first n points are well
// spread in the unit square for every n.
inline constexpr float kLatticeStepU = 0.7548776662f;
inline constexpr float kLatticeStepV = 0.5698402910f;

// Point i of the lattice shifted by `shift` (Cranley-Patterson rotation), coordinate by
// coordinate: uniform in [0, 1) for a uniform shift. x - floor(x) is exact in float.
inline float lattice_point(float shift, std::uint32_t i, float step) noexcept {
  const float x = shift + static_cast<float>(i) * step;
  return x - std::floor(x);
}

// The points of the grid cells (section 8): cell (x, y) holds `count` points (a Poisson or a
// balanced number, core/cell_count.hpp), all drawn from cell_key(x, y, seed, points) in a fixed
// order. The Poisson process: each point uniform in the cell (two uniforms), sign 1. The balanced
// points (`balanced`): a lattice of steps kLatticeStepU/V shifted by two uniforms, so that every
// point is uniform in the cell but the cell's points are evenly spread, each point with the sign
// point_sign gives. The draws are a pure function of the cell, so neighbouring samples of a batch,
// which visit the same cells, can reuse them: the cache keeps the points of recently visited cells
// and gives exactly the numbers a fresh draw gives, so the output does not depend on the batch (a
// GLSL port simply draws every time). Fixed size, on the stack: no allocation during evaluation.
class CellCache {
 public:
  static constexpr int kEntries = 32;
  static constexpr std::uint32_t kMaxPoints = 128;  // cells with more points are drawn each time

  CellCache(std::uint32_t seed, const CellCount& count, bool balanced = false) noexcept
      : seed_(seed), count_(count), balanced_(balanced) {}

  // The points of a cell in the cache: (u[i], v[i]) in [0, 1)^2 relative to the cell corner and
  // sign[i], i < count; the arrays are null when the cell holds more than kMaxPoints points.
  struct Points {
    const float* u;
    const float* v;
    const float* sign;
    std::uint32_t count;
  };

  // The points of the cell, drawn into the cache if absent.
  Points points(std::int64_t cell_x, std::int64_t cell_y) noexcept {
    // Cell (x, y) lives in slot (x mod 8, y mod 4): the cells a batch visits together, a window of
    // at most 8 x 4 neighbours, never evict one another.
    const auto slot = static_cast<std::size_t>((static_cast<std::uint64_t>(cell_x) & 7u) |
                                               (static_cast<std::uint64_t>(cell_y) & 3u) << 3);
    Entry& entry = entries_[slot];
    if (!entry.valid || entry.x != cell_x || entry.y != cell_y) {
      CounterRng rng(cell_key(cell_x, cell_y, seed_, Stream::points));
      const std::uint32_t impacts = count_(rng);
      if (impacts > kMaxPoints) return {nullptr, nullptr, nullptr, impacts};
      entry.valid = true;
      entry.x = cell_x;
      entry.y = cell_y;
      entry.count = impacts;
      PointDraws draws(rng, balanced_);
      const std::uint32_t sign_key = sign_key_of(cell_x, cell_y);
      for (std::uint32_t i = 0; i < impacts; ++i) {
        draws.next(rng, i, entry.u[i], entry.v[i]);
        entry.sign[i] = balanced_ ? point_sign(sign_key, i) : 1.0f;
      }
    }
    return {entry.u, entry.v, entry.sign, entry.count};
  }

  // Calls f(u, v, sign) for each point of the cell, (u, v) in [0, 1)^2 relative to the cell
  // corner.
  template <typename F>
  void for_each_point(std::int64_t cell_x, std::int64_t cell_y, F&& f) noexcept {
    const Points cached = points(cell_x, cell_y);
    if (cached.u != nullptr) {
      for (std::uint32_t i = 0; i < cached.count; ++i) f(cached.u[i], cached.v[i], cached.sign[i]);
      return;
    }
    // Too many to keep: the count's draws again, then the points'.
    CounterRng rng(cell_key(cell_x, cell_y, seed_, Stream::points));
    count_(rng);
    PointDraws draws(rng, balanced_);
    const std::uint32_t sign_key = sign_key_of(cell_x, cell_y);
    for (std::uint32_t i = 0; i < cached.count; ++i) {
      float u, v;
      draws.next(rng, i, u, v);
      f(u, v, balanced_ ? point_sign(sign_key, i) : 1.0f);
    }
  }

 private:
  struct Entry {
    bool valid = false;
    std::int64_t x = 0;
    std::int64_t y = 0;
    std::uint32_t count = 0;
    float u[kMaxPoints];
    float v[kMaxPoints];
    float sign[kMaxPoints];
  };
  static_assert(kEntries == 32, "the slot index is (x mod 8, y mod 4)");

  // The positions of a cell's points after its count's draws: two uniforms per point, or the
  // lattice's shift once (`lattice`: the balanced points).
  struct PointDraws {
    bool lattice;
    float shift_u = 0.0f;
    float shift_v = 0.0f;
    PointDraws(CounterRng& rng, bool lattice_points) noexcept : lattice(lattice_points) {
      if (!lattice) return;
      shift_u = rng.uniform();
      shift_v = rng.uniform();
    }
    void next(CounterRng& rng, std::uint32_t i, float& u, float& v) const noexcept {
      if (lattice) {
        u = lattice_point(shift_u, i, kLatticeStepU);
        v = lattice_point(shift_v, i, kLatticeStepV);
      } else {
        u = rng.uniform();
        v = rng.uniform();
      }
    }
  };

  std::uint32_t sign_key_of(std::int64_t cell_x, std::int64_t cell_y) const noexcept {
    return balanced_ ? cell_key(cell_x, cell_y, seed_, Stream::signs) : 0u;
  }

  std::uint32_t seed_;
  const CellCount& count_;
  bool balanced_;
  std::array<Entry, kEntries> entries_{};
};

// Calls f.template operator()<Order, Channels>() for the texton's interpolation order (0, 1, 3, 5)
// and channel count: Channels is the lane count texton_lanes(channels) (1 to 4, then 8, 12, 16 up
// to MaxChannels; the pyramid holds that many values per texel). One concrete loop per pair, so
// the inner loops unroll and the accumulators stay in registers. Dispatch happens once per batch.
template <int MaxChannels = kMaxChannels, typename F>
inline void with_order_and_channels(int order, int channels, F&& f) noexcept {
  static_assert(MaxChannels == 4 || MaxChannels == kMaxChannels);
  const auto with_order = [&]<int Order>() {
    const int lanes = texton_lanes(std::min(channels, MaxChannels));
    if constexpr (MaxChannels > 4) {
      if (lanes == 8) return f.template operator()<Order, 8>();
      if (lanes == 12) return f.template operator()<Order, 12>();
      if (lanes == 16) return f.template operator()<Order, 16>();
    }
    switch (lanes) {
      case 1:
        return f.template operator()<Order, 1>();
      case 2:
        return f.template operator()<Order, 2>();
      case 3:
        return f.template operator()<Order, 3>();
      default:
        return f.template operator()<Order, 4>();
    }
  };
  switch (order) {
    case 0:
      return with_order.template operator()<0>();
    case 1:
      return with_order.template operator()<1>();
    case 3:
      return with_order.template operator()<3>();
    default:
      return with_order.template operator()<5>();
  }
}

// One impulse of the shot noise: the pyramid of the texton it scatters and its weight (texton
// noise: the one texton, weight 1; mixing, section 7: the texton of its region, a random sign);
// the balanced points multiply it by their own sign (CellCache).
struct Impulse {
  const PyramidLevel* pyramid;
  float weight;
};

// The impulses of texton noise: every point scatters the one texton with weight 1 (times the
// point's sign, which the cell cache gives).
struct OneTexton {
  const PyramidLevel* pyramid;
  Impulse operator()(std::int64_t, std::int64_t, std::uint32_t, float, float) const noexcept {
    return {pyramid, 1.0f};
  }
};

// The shot-noise sum at p (eq. 1), filtered as section 5 says: the impulses of the grid cells that
// meet p + [-reach, reach]^2, each adding weight * sign * h(p - x_j) through `texton`. `impulses`
// maps a point (cell, index in the cell, (u, v) in the cell) to its Impulse. The one loop of texton
// noise and texton noise mixing.
template <int Order, int Channels, typename Impulses>
inline void sum_impulses(Vec2d p, const FilteredTexton<Order, Channels>& texton,
                         double cell_size_double, CellCache& cells, Impulses&& impulses,
                         float (&acc)[Channels]) noexcept {
  const float cell_size = static_cast<float>(cell_size_double);
  const double reach = texton.reach();
  // The Poisson process is simulated on the grid cells that meet p + [-reach, reach]^2. Cell
  // indices are 64-bit integers and offsets are taken relative to the cell corner in double
  // before going to float, so p = 1e7 is as precise as p = 0 (docs/design.md §4).
  const auto first_cell_x = static_cast<std::int64_t>(std::floor((p.x - reach) / cell_size_double));
  const auto last_cell_x = static_cast<std::int64_t>(std::floor((p.x + reach) / cell_size_double));
  const auto first_cell_y = static_cast<std::int64_t>(std::floor((p.y - reach) / cell_size_double));
  const auto last_cell_y = static_cast<std::int64_t>(std::floor((p.y + reach) / cell_size_double));
  for (std::int64_t cell_y = first_cell_y; cell_y <= last_cell_y; ++cell_y) {
    const float offset_y = static_cast<float>(p.y - static_cast<double>(cell_y) * cell_size_double);
    for (std::int64_t cell_x = first_cell_x; cell_x <= last_cell_x; ++cell_x) {
      const float offset_x =
          static_cast<float>(p.x - static_cast<double>(cell_x) * cell_size_double);
      std::uint32_t index = 0;
      cells.for_each_point(cell_x, cell_y, [&](float u, float v, float sign) {
        const Impulse impulse = impulses(cell_x, cell_y, index++, u, v);
        texton.add(impulse.pyramid, offset_x - u * cell_size, offset_y - v * cell_size,
                   impulse.weight * sign, acc);
      });
    }
  }
}

// sum_impulses for a periodic field (core/periodic.hpp): cells of side (x.size, y.size), each
// axis's cells dividing the period, whose points are those of the cell wrapped into the period;
// `cells` draws them with the count of a cell of that area. The loop of evaluate_periodic.
template <int Order, int Channels>
inline void sum_impulses_periodic(Vec2d p, const FilteredTexton<Order, Channels>& texton,
                                  PeriodicAxis x, PeriodicAxis y, CellCache& cells,
                                  const PyramidLevel* pyramid, float (&acc)[Channels]) noexcept {
  const auto size_x = static_cast<float>(x.size);
  const auto size_y = static_cast<float>(y.size);
  const double reach = texton.reach();
  const auto first_cell_x = static_cast<std::int64_t>(std::floor((p.x - reach) / x.size));
  const auto last_cell_x = static_cast<std::int64_t>(std::floor((p.x + reach) / x.size));
  const auto first_cell_y = static_cast<std::int64_t>(std::floor((p.y - reach) / y.size));
  const auto last_cell_y = static_cast<std::int64_t>(std::floor((p.y + reach) / y.size));
  for (std::int64_t cell_y = first_cell_y; cell_y <= last_cell_y; ++cell_y) {
    const auto offset_y = static_cast<float>(p.y - static_cast<double>(cell_y) * y.size);
    for (std::int64_t cell_x = first_cell_x; cell_x <= last_cell_x; ++cell_x) {
      const auto offset_x = static_cast<float>(p.x - static_cast<double>(cell_x) * x.size);
      cells.for_each_point(x.wrap(cell_x), y.wrap(cell_y), [&](float u, float v, float sign) {
        texton.add(pyramid, offset_x - u * size_x, offset_y - v * size_y, sign, acc);
      });
    }
  }
}

}  // namespace stochtex::texton
