// LRP noise's random strata, one sample per SIMD lane (simd.hpp). Compiled once per SIMD target by
// Highway's foreach_target.h; random_strata_noise dispatches to the best one at run time.
// The window, frequency clamping, the cosines and a stratum's term are the scalar reference's own
// source (kernel.inc); every other vector operation below is the reference's (evaluate.hpp,
// model.cpp) in its order: no fused multiply-add (the build sets -ffp-contract=off), the same
// constants, truncating conversions, and lanes that skip a node keep their sums by selection.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/lrp/simd.cpp"
#include "methods/lrp/simd.hpp"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "core/cpu_target.hpp"
#include "core/simd_math.hpp"

HWY_BEFORE_NAMESPACE();
namespace stochtex::lrp::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using stochtex::HWY_NAMESPACE::CosTurns;

using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);

#include "methods/lrp/kernel.inc"

// kernel.inc's operations in every lane.
struct VectorOps {
  static VF constant(float c) { return hn::Set(DF(), c); }
  static VF abs(VF v) { return hn::Abs(v); }
  static VF sqrt(VF v) { return hn::Sqrt(v); }
  static VF min(VF a, VF b) { return hn::Min(a, b); }
  static VF cos(VF v) { return CosTurns(DF(), v); }
  static VF select(hn::Mask<DF> condition, VF a, VF b) { return hn::IfThenElse(condition, a, b); }
  static bool none(hn::Mask<DF> condition) { return hn::AllFalse(DF(), condition); }
};

// At most this many distinct nodes in one pass are read by selection between broadcasts; more
// are gathered (a gather of 16 lanes costs more than the cosine it feeds).
constexpr int kMaxBlendedNodes = 3;

// The lists a pass reads: list `which[lane]` of `lists` for each lane, at data + offset[lane].
struct PassLists {
  const float* data;
  int lists;
  const float* list[kMaxBlendedNodes];
  const std::int32_t* which;
  const std::int32_t* offset;
};

// sum_j a_j cos(2 pi f_j.(x - x_i) + phi_j) of one node in every lane (stratum_sum's `local`).
// Lists: 1 = one list for every lane, 2 or 3 = selected per lane, 0 = gathered per lane.
template <int Lists, bool Filtered>
HWY_INLINE VF node_sum(DF df, const PassLists& pass, std::uint32_t count, VF px, VF py,
                       const VF (&axes)[4]) {
  const DI di;
  const auto offset = hn::Load(di, pass.offset);
  const auto which = hn::Load(di, pass.which);
  const auto second = hn::RebindMask(df, hn::Eq(which, hn::Set(di, 1)));
  const auto third = hn::RebindMask(df, hn::Eq(which, hn::Set(di, 2)));
  const auto field = [&](std::uint32_t at) {
    if constexpr (Lists == 0) {
      return hn::GatherIndex(df, pass.data + at, offset);
    } else {
      VF value = hn::Set(df, pass.list[0][at]);
      if constexpr (Lists >= 2)
        value = hn::IfThenElse(second, hn::Set(df, pass.list[1][at]), value);
      if constexpr (Lists >= 3) value = hn::IfThenElse(third, hn::Set(df, pass.list[2][at]), value);
      return value;
    }
  };
  const VectorOps ops;
  VF local = hn::Zero(df);
  for (std::uint32_t j = 0; j < count; ++j) {
    const VF fx = field(j);
    const VF fy = field(count + j);
    VF clamp = hn::Set(df, 1.0f);
    if constexpr (Filtered) {
      // A cosine faded out in every lane adds +-0 to `local`, which starts at +0 and so is never
      // -0: skipping it changes no bit.
      clamp = frequency_clamp(ops, fx, fy, axes);
      if (hn::AllTrue(df, hn::Eq(clamp, hn::Zero(df)))) continue;
    }
    VF c = node_cosine(ops, fx, fy, field(2 * count + j), px, py);
    if constexpr (Filtered) c = c * clamp;
    local = local + field(3 * count + j) * c;
  }
  return local;
}

template <bool Filtered>
HWY_INLINE VF node_sum(DF df, const PassLists& pass, std::uint32_t count, VF px, VF py,
                       const VF (&axes)[4]) {
  switch (pass.lists) {
    case 1:
      return node_sum<1, Filtered>(df, pass, count, px, py, axes);
    case 2:
      return node_sum<2, Filtered>(df, pass, count, px, py, axes);
    case 3:
      return node_sum<3, Filtered>(df, pass, count, px, py, axes);
    default:
      return node_sum<0, Filtered>(df, pass, count, px, py, axes);
  }
}

template <bool Filtered>
void strata_lanes(const RandomStrata& strata, int channels, std::span<const Vec2d> positions,
                  std::span<const Footprint> footprints, std::size_t first, NodeCache& cache,
                  float* noise) {
  const DF df;
  const DI di;
  const std::size_t lanes = hn::Lanes(df);
  const std::size_t count = std::min(lanes, positions.size() - first);
  // Lanes past the end repeat the last position; their results are dropped.
  const auto position = [&](std::size_t lane) { return first + std::min(lane, count - 1); };

  VF axes[4] = {hn::Zero(df), hn::Zero(df), hn::Zero(df), hn::Zero(df)};
  if constexpr (Filtered) {
    HWY_ALIGN float axis[4][kMaxLanes];
    for (std::size_t lane = 0; lane < lanes; ++lane) {
      const Footprint& f = footprints[position(lane)];
      axis[0][lane] = static_cast<float>(f.dpdx.x);
      axis[1][lane] = static_cast<float>(f.dpdx.y);
      axis[2][lane] = static_cast<float>(f.dpdy.x);
      axis[3][lane] = static_cast<float>(f.dpdy.y);
    }
    for (int a = 0; a < 4; ++a) axes[a] = hn::Load(df, axis[a]);
  }

  HWY_ALIGN float channel_noise[kMaxChannels][kMaxLanes];
  for (int c = 0; c < channels; ++c) hn::Store(hn::Zero(df), df, channel_noise[c]);

  HWY_ALIGN float offset_x[kMaxLanes];
  HWY_ALIGN float offset_y[kMaxLanes];
  HWY_ALIGN float weight_lanes[kMaxLanes];
  HWY_ALIGN std::int32_t list_offset[kMaxLanes];
  std::int64_t node_x[kMaxLanes];
  std::int64_t node_y[kMaxLanes];
  for (std::size_t s = 0; s < strata.strata.size(); ++s) {
    const SimdStratum& stratum = strata.strata[s];
    const StratumDraw& draw = stratum.draw;
    for (std::size_t lane = 0; lane < lanes; ++lane) {
      const Vec2d p = positions[position(lane)];
      const NearestNode node = nearest_node(p.x * draw.inverse_spacing, p.y * draw.inverse_spacing);
      node_x[lane] = node.x;
      node_y[lane] = node.y;
      offset_x[lane] = node.offset_x;
      offset_y[lane] = node.offset_y;
    }
    const VF ox = hn::Load(df, offset_x);
    const VF oy = hn::Load(df, offset_y);
    VF sum = hn::Zero(df);
    VF window_square = hn::Zero(df);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const VF rx = hn::Sub(ox, hn::Set(df, static_cast<float>(dx)));
        const VF ry = hn::Sub(oy, hn::Set(df, static_cast<float>(dy)));
        const VF w = window_from_square(VectorOps{}, *strata.window, rx * rx + ry * ry);
        hn::Store(w, df, weight_lanes);
        const VF px = hn::Mul(rx, hn::Set(df, draw.spacing));
        const VF py = hn::Mul(ry, hn::Set(df, draw.spacing));
        // The lanes that see this node (w > 0), in passes of lanes whose nodes share the cache.
        std::uint32_t remaining = 0;
        for (std::size_t lane = 0; lane < lanes; ++lane)
          if (weight_lanes[lane] > 0.0f) remaining |= 1u << lane;
        while (remaining != 0) {
          cache.next_pass();
          HWY_ALIGN std::int32_t in_pass[kMaxLanes];
          HWY_ALIGN std::int32_t which[kMaxLanes];
          PassLists pass{cache.data(), 0, {}, which, list_offset};
          std::int32_t distinct[kMaxLanes];
          for (std::size_t lane = 0; lane < lanes; ++lane) {
            in_pass[lane] = 0;
            list_offset[lane] = 0;
            which[lane] = 0;
            if ((remaining & (1u << lane)) == 0) continue;
            // Neighbouring lanes mostly share a node: one look-up per run of them.
            const bool same_node = lane > 0 && in_pass[lane - 1] != 0 &&
                                   node_x[lane] == node_x[lane - 1] &&
                                   node_y[lane] == node_y[lane - 1];
            const std::int32_t found = same_node ? list_offset[lane - 1]
                                                 : cache.find(s, stratum, strata.tables,
                                                              node_x[lane] + dx, node_y[lane] + dy);
            if (found < 0) continue;
            in_pass[lane] = -1;
            list_offset[lane] = found;
            remaining &= ~(1u << lane);
            int list = 0;
            while (list < pass.lists && distinct[list] != found) ++list;
            if (list == pass.lists) distinct[pass.lists++] = found;
            which[lane] = list;
          }
          if (pass.lists <= kMaxBlendedNodes) {
            for (int list = 0; list < pass.lists; ++list)
              pass.list[list] = cache.data() + distinct[list];
          } else {
            pass.lists = 0;
          }
          const VF local = node_sum<Filtered>(df, pass, draw.cosines, px, py, axes);
          const auto take = hn::RebindMask(df, hn::Ne(hn::Load(di, in_pass), hn::Zero(di)));
          sum = hn::IfThenElse(take, hn::Add(sum, hn::Mul(w, local)), sum);
          window_square =
              hn::IfThenElse(take, hn::Add(window_square, hn::Mul(w, w)), window_square);
        }
      }
    }
    float* lane_noise = channel_noise[stratum.channel];
    hn::Store(
        hn::Load(df, lane_noise) + stratum_term(VectorOps{}, stratum.amplitude, strata.normalise,
                                                strata.mean_envelope, window_square, sum),
        df, lane_noise);
  }
  for (std::size_t lane = 0; lane < count; ++lane)
    for (int c = 0; c < channels; ++c)
      noise[(first + lane) * kMaxChannels + static_cast<std::size_t>(c)] = channel_noise[c][lane];
}

void RandomStrataNoise(const RandomStrata& strata, int channels, std::span<const Vec2d> positions,
                       std::span<const Footprint> footprints, NodeCache& cache, float* noise) {
  const std::size_t lanes = hn::Lanes(DF());
  for (std::size_t first = 0; first < positions.size(); first += lanes) {
    if (footprints.empty())
      strata_lanes<false>(strata, channels, positions, footprints, first, cache, noise);
    else
      strata_lanes<true>(strata, channels, positions, footprints, first, cache, noise);
  }
}

}  // namespace stochtex::lrp::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::lrp {

HWY_EXPORT(RandomStrataNoise);

void random_strata_noise(const RandomStrata& strata, int channels, std::span<const Vec2d> positions,
                         std::span<const Footprint> footprints, NodeCache& cache,
                         float* noise) noexcept {
  HWY_DYNAMIC_DISPATCH(RandomStrataNoise)(strata, channels, positions, footprints, cache, noise);
  end_simd_call();
}

std::unique_ptr<NodeCache> NodeCache::make(std::span<const SimdStratum> strata) noexcept {
  constexpr std::size_t kMaxWidth = 32;
  constexpr std::size_t kMaxFloats = std::size_t{1} << 20;  // 4 MiB
  std::size_t cosines = 0;
  for (const SimdStratum& stratum : strata) cosines += stratum.draw.cosines;
  std::size_t width = kMaxWidth;
  while (width >= 4 && width * 4 * 4 * cosines > kMaxFloats) width /= 2;
  if (width < 4) return nullptr;
  try {
    auto cache = std::make_unique<NodeCache>();
    cache->width_ = static_cast<std::uint32_t>(width);
    const std::size_t slots = width * 4;
    cache->slots_.resize(slots * strata.size());
    std::uint32_t next_float = 0;
    for (const SimdStratum& stratum : strata) {
      cache->first_float_.push_back(next_float);
      next_float += static_cast<std::uint32_t>(slots * 4 * stratum.draw.cosines);
    }
    cache->floats_.resize(next_float);
    return cache;
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}

std::int32_t NodeCache::find(std::size_t s, const SimdStratum& stratum, const StratumTables& tables,
                             std::int64_t x, std::int64_t y) noexcept {
  const std::uint32_t slot_in_stratum = (static_cast<std::uint32_t>(x) & (width_ - 1u)) +
                                        width_ * (static_cast<std::uint32_t>(y) & 3u);
  Slot& slot = slots_[s * width_ * 4 + slot_in_stratum];
  const std::uint32_t cosines = stratum.draw.cosines;
  const std::uint32_t offset = first_float_[s] + slot_in_stratum * 4u * cosines;
  if (slot.found_in == 0 || slot.x != x || slot.y != y) {
    if (slot.found_in == pass_) return -1;
    // stratum_sum's draws for this node (evaluate.hpp), into fx, fy, phase, weight.
    float* list = floats_.data() + offset;
    CounterRng rng(cell_key(x, y, stratum.draw.stream, Stream::phases));
    for (std::uint32_t j = 0; j < cosines; ++j) {
      const std::uint32_t draw = rng.next();
      const std::uint32_t pick = pick_frequency(tables, stratum.draw.first_substratum + j, draw);
      list[j] = tables.frequencies[2 * pick];
      list[cosines + j] = tables.frequencies[2 * pick + 1];
      list[2 * cosines + j] = draw_phase(draw);
      list[3 * cosines + j] = tables.weights[pick];
    }
    slot.x = x;
    slot.y = y;
  }
  slot.found_in = pass_;
  return static_cast<std::int32_t>(offset);
}

}  // namespace stochtex::lrp
#endif  // HWY_ONCE
