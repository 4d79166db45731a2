// Texton noise, one sample per SIMD lane (simd.hpp). Compiled once per SIMD target by Highway's
// foreach_target.h; sum_impulses_simd dispatches to the best one at run time. Every vector
// operation below is the scalar reference's (evaluate.hpp) in its order: no fused multiply-add
// (the build sets -ffp-contract=off), the same constants (BsplineKernel's weights are one source
// for both), truncating conversions. A lane that the reference would skip (a cell outside its
// range, a point outside the texton's support) gets weight 0 for that point: it adds w * h = +-0,
// which leaves its sum as it was, since a sum that starts at +0 is never -0 (round to nearest
// gives +0 for an exact zero sum of non-zero terms) and the texels it reads are finite.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/texton/simd.cpp"
#include "methods/texton/simd.hpp"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace stochtex::texton::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;
constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);
static_assert(kMaxLanes <= 32, "lane sets are 32-bit masks");

#include "methods/texton/bspline_weights.inc"

// bspline_weights' operations in every lane.
struct VectorOps {
  static VF constant(float c) { return hn::Set(DF(), c); }
  static VF floor(VF v) { return hn::Floor(v); }
  static VI to_int(VF v) { return hn::ConvertTo(DI(), v); }
  static VI int_constant(int i) { return hn::Set(DI(), i); }
};

// The texels of one tap in every lane: values[c] = level.coefficients[index + c] (index per lane,
// 0 for lanes outside `inside`). When the lanes read consecutive texels (neighbouring samples of
// a grid at the level's spacing), a few loads replace Channels gathers: the same values.
template <int Channels>
HWY_INLINE void load_texels(const float* coefficients, VI index, bool consecutive, MF inside,
                            VF (&values)[Channels]) {
  const DF df;
  const DI di;
  if (consecutive) {
    const float* first = coefficients + hn::GetLane(index);
    if constexpr (Channels == 1) {
      values[0] = hn::LoadU(df, first);
      return;
    } else if constexpr (Channels == 2) {
      hn::LoadInterleaved2(df, first, values[0], values[1]);
      return;
    } else if constexpr (Channels == 3) {
      hn::LoadInterleaved3(df, first, values[0], values[1], values[2]);
      return;
    } else if constexpr (Channels == 4) {
      hn::LoadInterleaved4(df, first, values[0], values[1], values[2], values[3]);
      return;
    }
  }
  const VI safe = hn::IfThenElseZero(hn::RebindMask(di, inside), index);
  for (int c = 0; c < Channels; ++c) values[c] = hn::GatherIndex(df, coefficients + c, safe);
}

// accumulate_texton (evaluate.hpp) in the lanes of `lanes`: adds weight * h_level(dx, dy).
template <int Order, int Channels>
HWY_INLINE void accumulate_lanes(const PyramidLevel& level, VF dx, VF dy, float weight, MF lanes,
                                 VF (&acc)[Channels]) {
  const DF df;
  const DI di;
  const VF half_width = hn::Set(df, level.half_width);
  const MF inside =
      hn::And(lanes, hn::And(hn::Lt(hn::Abs(dx), half_width), hn::Lt(hn::Abs(dy), half_width)));
  if (hn::AllFalse(df, inside)) return;
  constexpr int kTaps = BsplineKernel<Order>::kTaps;
  VF wx[kTaps];
  VF wy[kTaps];
  const VF inverse_spacing = hn::Set(df, 1.0f / level.spacing);
  const VF first_texel = hn::Set(df, level.first_texel);
  const VI x0 = bspline_weights<Order>(VectorOps{}, (dx - first_texel) * inverse_spacing, wx);
  const VI y0 = bspline_weights<Order>(VectorOps{}, (dy - first_texel) * inverse_spacing, wy);
  const VI padding = hn::Set(di, kPadding);
  const VI base =
      ((y0 + padding) * hn::Set(di, level.stride) + (x0 + padding)) * hn::Set(di, Channels);
  // Consecutive texels in every lane, and every tap's loads within the level.
  const std::int32_t row = level.stride * Channels;
  const std::int32_t first = hn::GetLane(base);
  const auto lane_count = static_cast<std::int32_t>(hn::Lanes(df));
  const bool consecutive =
      hn::AllTrue(di, hn::Eq(base, hn::Iota(di, 0) * hn::Set(di, Channels) + hn::Set(di, first))) &&
      first >= 0 &&
      static_cast<std::size_t>(first + (kTaps - 1) * (row + Channels) + lane_count * Channels) <=
          level.coefficients.size();
  const float* coefficients = level.coefficients.data();
  const VF w_lanes = hn::Set(df, weight);
  for (int j = 0; j < kTaps; ++j) {
    const VF weight_row = w_lanes * wy[j];
    for (int i = 0; i < kTaps; ++i) {
      const VF w = hn::IfThenElseZero(inside, weight_row * wx[i]);
      VF values[Channels];
      load_texels<Channels>(coefficients, base + hn::Set(di, j * row + i * Channels), consecutive,
                            inside, values);
      for (int c = 0; c < Channels; ++c) acc[c] = acc[c] + w * values[c];
    }
  }
}

// The cells of the grid that a lane's sum visits (sum_impulses): [x0, x1] x [y0, y1].
struct CellRange {
  std::int64_t x0, x1, y0, y1;
};

// sum_impulses for positions[first, first + lane count) (the last position repeated in lanes past
// the end), into acc (Channels per position). The lanes are summed in passes: a pass takes the
// first lane left and every other lane whose cells lie within one cell of its own, and visits the
// union of their cells in the reference's order (rows, then columns, then points), each lane
// taking the cells of its own range.
template <int Order, int Channels>
void sum_lanes(std::span<const Vec2d> positions, std::size_t first,
               const FilteredTexton<Order, Channels>& texton, double cell_size, CellCache& cells,
               const ImpulseSource& impulses, float* acc_out) {
  const DF df;
  const DI di;
  const std::size_t lanes = hn::Lanes(df);
  const std::size_t count = std::min(lanes, positions.size() - first);
  const float cell_size_float = static_cast<float>(cell_size);
  const double reach = texton.reach();
  Vec2d p[kMaxLanes];
  CellRange range[kMaxLanes];
  for (std::size_t lane = 0; lane < lanes; ++lane) {
    p[lane] = positions[first + std::min(lane, count - 1)];
    range[lane] = {static_cast<std::int64_t>(std::floor((p[lane].x - reach) / cell_size)),
                   static_cast<std::int64_t>(std::floor((p[lane].x + reach) / cell_size)),
                   static_cast<std::int64_t>(std::floor((p[lane].y - reach) / cell_size)),
                   static_cast<std::int64_t>(std::floor((p[lane].y + reach) / cell_size))};
  }
  VF acc[Channels];
  for (int c = 0; c < Channels; ++c) acc[c] = hn::Zero(df);
  HWY_ALIGN float offset_x[kMaxLanes];
  HWY_ALIGN float offset_y[kMaxLanes];
  HWY_ALIGN std::int32_t takes_row[kMaxLanes];
  HWY_ALIGN std::int32_t takes_cell[kMaxLanes];
  std::uint32_t remaining = count == 32 ? ~0u : (1u << count) - 1u;
  while (remaining != 0) {
    const CellRange& lead = range[static_cast<std::size_t>(__builtin_ctz(remaining))];
    std::uint32_t pass = 0;
    CellRange all = lead;
    for (std::size_t lane = 0; lane < count; ++lane) {
      const CellRange& r = range[lane];
      if ((remaining >> lane & 1u) == 0 || r.x0 < lead.x0 - 1 || r.x1 > lead.x1 + 1 ||
          r.y0 < lead.y0 - 1 || r.y1 > lead.y1 + 1)
        continue;
      pass |= 1u << lane;
      all = {std::min(all.x0, r.x0), std::max(all.x1, r.x1), std::min(all.y0, r.y0),
             std::max(all.y1, r.y1)};
    }
    remaining &= ~pass;
    for (std::int64_t cell_y = all.y0; cell_y <= all.y1; ++cell_y) {
      for (std::size_t lane = 0; lane < lanes; ++lane) {
        offset_y[lane] = static_cast<float>(p[lane].y - static_cast<double>(cell_y) * cell_size);
        takes_row[lane] =
            (pass >> lane & 1u) != 0 && range[lane].y0 <= cell_y && cell_y <= range[lane].y1 ? -1
                                                                                             : 0;
      }
      const VF oy = hn::Load(df, offset_y);
      for (std::int64_t cell_x = all.x0; cell_x <= all.x1; ++cell_x) {
        bool any = false;
        for (std::size_t lane = 0; lane < lanes; ++lane) {
          offset_x[lane] = static_cast<float>(p[lane].x - static_cast<double>(cell_x) * cell_size);
          takes_cell[lane] =
              range[lane].x0 <= cell_x && cell_x <= range[lane].x1 ? takes_row[lane] : 0;
          any = any || takes_cell[lane] != 0;
        }
        if (!any) continue;
        const MF in_cell = hn::RebindMask(df, hn::Ne(hn::Load(di, takes_cell), hn::Zero(di)));
        const VF ox = hn::Load(df, offset_x);
        std::uint32_t index = 0;
        cells.for_each_point(cell_x, cell_y, [&](float u, float v) {
          const Impulse impulse = impulses.impulse(impulses.context, cell_x, cell_y, index++, u, v);
          const VF dx = ox - hn::Set(df, u * cell_size_float);
          const VF dy = oy - hn::Set(df, v * cell_size_float);
          texton.for_each_probe(
              impulse.pyramid, impulse.weight,
              [&](const PyramidLevel& level, const auto& probe, float weight) {
                if (probe.shifted)
                  accumulate_lanes<Order, Channels>(level, dx + hn::Set(df, probe.x),
                                                    dy + hn::Set(df, probe.y), weight, in_cell,
                                                    acc);
                else
                  accumulate_lanes<Order, Channels>(level, dx, dy, weight, in_cell, acc);
              });
        });
      }
    }
  }
  HWY_ALIGN float sums[Channels][kMaxLanes];
  for (int c = 0; c < Channels; ++c) hn::Store(acc[c], df, sums[c]);
  for (std::size_t lane = 0; lane < count; ++lane)
    for (int c = 0; c < Channels; ++c)
      acc_out[(first + lane) * Channels + static_cast<std::size_t>(c)] = sums[c][lane];
}

void SumImpulses(int order, int lanes, std::span<const Vec2d> positions,
                 const std::vector<PyramidLevel>& shape, const FilterSetup& filter,
                 double cell_size, CellCache& cells, const ImpulseSource& impulses, float* acc) {
  with_order_and_channels(order, lanes, [&]<int Order, int Channels>() {
    const FilteredTexton<Order, Channels> texton(shape, filter);
    for (std::size_t first = 0; first < positions.size(); first += hn::Lanes(DF()))
      sum_lanes<Order, Channels>(positions, first, texton, cell_size, cells, impulses, acc);
  });
}

}  // namespace stochtex::texton::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::texton {

HWY_EXPORT(SumImpulses);

void sum_impulses_simd(int order, int lanes, std::span<const Vec2d> positions,
                       const std::vector<PyramidLevel>& shape, const FilterSetup& filter,
                       double cell_size, CellCache& cells, const ImpulseSource& impulses,
                       float* acc) noexcept {
  HWY_DYNAMIC_DISPATCH(SumImpulses)
  (order, lanes, positions, shape, filter, cell_size, cells, impulses, acc);
}

}  // namespace stochtex::texton
#endif  // HWY_ONCE
