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

#include <limits>

#include "core/cpu_target.hpp"

HWY_BEFORE_NAMESPACE();
namespace stochtex::texton::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;
constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);
static_assert(kMaxLanes < 32, "lane sets are 32-bit masks");

#include "methods/texton/kernel.inc"

// bspline_weights' operations in every lane.
struct VectorOps {
  static VF constant(float c) { return hn::Set(DF(), c); }
  static VF floor(VF v) { return hn::Floor(v); }
  static VI to_int(VF v) { return hn::ConvertTo(DI(), v); }
  static VI int_constant(int i) { return hn::Set(DI(), i); }
};

// The texels of one tap in every lane: values[c] = channel c of texel index[lane] (0 in lanes
// outside `inside`) of the planes at `planes`, `plane` floats apart. When the lanes read texels
// `step` apart (1 or 2: neighbouring samples of a grid at the level's spacing or at twice it), one
// or two vector loads per channel replace a gather and give the same values.
template <int Channels>
HWY_INLINE void load_texels(const float* planes, std::size_t plane, VI index, int step, MF inside,
                            VF (&values)[Channels]) {
  const DF df;
  const DI di;
  if (step == 1) {
    const float* first = planes + hn::GetLane(index);
    for (int c = 0; c < Channels; ++c) values[c] = hn::LoadU(df, first + c * plane);
    return;
  }
#if HWY_TARGET != HWY_SCALAR  // one lane: a step is always 1
  if (step == 2) {
    const float* first = planes + hn::GetLane(index);
    for (int c = 0; c < Channels; ++c) {
      const VF even = hn::LoadU(df, first + c * plane);
      const VF odd = hn::LoadU(df, first + c * plane + hn::Lanes(df));
      values[c] = hn::ConcatEven(df, odd, even);
    }
    return;
  }
#endif
  const VI safe = hn::IfThenElseZero(hn::RebindMask(di, inside), index);
  for (int c = 0; c < Channels; ++c) values[c] = hn::GatherIndex(df, planes + c * plane, safe);
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
  const VI texel = (y0 + padding) * hn::Set(di, level.stride) + (x0 + padding);
  // Lane l reads texel first + step * l (step 1 or 2, else 0: gathers), every tap within a plane.
  const auto plane =
      static_cast<std::size_t>(level.stride) * static_cast<std::size_t>(level.stride);
  const std::int32_t first = hn::GetLane(texel);
  const auto spaced = [&](std::int32_t step) HWY_ATTR {
    return first >= 0 &&
           static_cast<std::size_t>(first + (kTaps - 1) * (level.stride + 1) +
                                    step * static_cast<std::int32_t>(hn::Lanes(df))) <= plane &&
           hn::AllTrue(di, hn::Eq(texel, hn::Set(di, first) + hn::Iota(di, 0) * hn::Set(di, step)));
  };
  const int step = spaced(1) ? 1 : spaced(2) ? 2 : 0;
  const VF w_lanes = hn::Set(df, weight);
  for (int j = 0; j < kTaps; ++j) {
    const VF weight_row = w_lanes * wy[j];
    for (int i = 0; i < kTaps; ++i) {
      const VF w = hn::IfThenElseZero(inside, weight_row * wx[i]);
      VF values[Channels];
      load_texels<Channels>(level.planes.data(), plane, texel + hn::Set(di, j * level.stride + i),
                            step, inside, values);
      for (int c = 0; c < Channels; ++c) acc[c] = acc[c] + w * values[c];
    }
  }
}

// The sums of one vector of samples: sum_impulses' acc in every lane.
template <int Order, int Channels>
struct LaneSums {
  const FilteredTexton<Order, Channels>& texton;
  const ImpulseSource& impulses;
  float cell_size;
  VF acc[Channels];

  // for_each_read's `read`: one texton read in the lanes of `lanes`.
  struct Read {
    VF dx, dy;
    MF lanes;
    VF (&acc)[Channels];
    HWY_INLINE void operator()(const PyramidLevel& level, const ProbeShift& shift,
                               float weight) const {
      const DF df;
      if (shift.shifted)
        accumulate_lanes<Order, Channels>(level, dx + hn::Set(df, shift.x),
                                          dy + hn::Set(df, shift.y), weight, lanes, acc);
      else
        accumulate_lanes<Order, Channels>(level, dx, dy, weight, lanes, acc);
    }
  };

  // Point `index` (u, v, its sign) of cell (cell_x, cell_y), for the lanes of `lanes` at offsets
  // (ox, oy) from the cell corner. `near` bounds u * cell_size and v * cell_size: outside it the
  // point is beyond the reach of every lane (the reads would all add nothing) and is passed over.
  HWY_INLINE void point(std::int64_t cell_x, std::int64_t cell_y, std::uint32_t index, float u,
                        float v, float sign, VF ox, VF oy, MF lanes, const float (&near)[4]) {
    const DF df;
    const float impact_x = u * cell_size;
    const float impact_y = v * cell_size;
    if (impact_x < near[0] || impact_x > near[1] || impact_y < near[2] || impact_y > near[3])
      return;
    const Impulse impulse = impulses.impulse == nullptr
                                ? Impulse{impulses.pyramid, 1.0f}
                                : impulses.impulse(impulses.context, cell_x, cell_y, index, u, v);
    const Read read{ox - hn::Set(df, impact_x), oy - hn::Set(df, impact_y), lanes, acc};
    HWY_NAMESPACE::for_each_read(texton.filter(), impulse.pyramid[texton.fine_level()],
                                 impulse.pyramid[texton.coarse_level()], texton.probe_weight(),
                                 impulse.weight * sign, read);
  }
};

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
  const double reach = texton.reach();
  // Beyond reach + 1 pixel of every lane, a point reads nothing, whatever the float rounding.
  const float far = static_cast<float>(reach) + 1.0f;
  Vec2d p[kMaxLanes];
  CellRange range[kMaxLanes];
  for (std::size_t lane = 0; lane < lanes; ++lane) {
    p[lane] = positions[first + std::min(lane, count - 1)];
    range[lane] = {static_cast<std::int64_t>(std::floor((p[lane].x - reach) / cell_size)),
                   static_cast<std::int64_t>(std::floor((p[lane].x + reach) / cell_size)),
                   static_cast<std::int64_t>(std::floor((p[lane].y - reach) / cell_size)),
                   static_cast<std::int64_t>(std::floor((p[lane].y + reach) / cell_size))};
  }
  LaneSums<Order, Channels> sums{texton, impulses, static_cast<float>(cell_size), {}};
  for (int c = 0; c < Channels; ++c) sums.acc[c] = hn::Zero(df);
  HWY_ALIGN float offset_x[kMaxLanes];
  HWY_ALIGN float offset_y[kMaxLanes];
  HWY_ALIGN std::int32_t takes_cell[kMaxLanes];
  bool takes_row[kMaxLanes];
  std::uint32_t remaining = (1u << count) - 1u;
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
      float near[4];  // the bounds LaneSums::point passes over points beyond
      near[2] = std::numeric_limits<float>::max();
      near[3] = std::numeric_limits<float>::lowest();
      for (std::size_t lane = 0; lane < lanes; ++lane) {
        offset_y[lane] = static_cast<float>(p[lane].y - static_cast<double>(cell_y) * cell_size);
        takes_row[lane] =
            (pass >> lane & 1u) != 0 && range[lane].y0 <= cell_y && cell_y <= range[lane].y1;
        if (!takes_row[lane]) continue;
        near[2] = std::min(near[2], offset_y[lane] - far);
        near[3] = std::max(near[3], offset_y[lane] + far);
      }
      const VF oy = hn::Load(df, offset_y);
      for (std::int64_t cell_x = all.x0; cell_x <= all.x1; ++cell_x) {
        near[0] = std::numeric_limits<float>::max();
        near[1] = std::numeric_limits<float>::lowest();
        for (std::size_t lane = 0; lane < lanes; ++lane) {
          offset_x[lane] = static_cast<float>(p[lane].x - static_cast<double>(cell_x) * cell_size);
          const bool takes =
              takes_row[lane] && range[lane].x0 <= cell_x && cell_x <= range[lane].x1;
          takes_cell[lane] = takes ? -1 : 0;
          if (!takes) continue;
          near[0] = std::min(near[0], offset_x[lane] - far);
          near[1] = std::max(near[1], offset_x[lane] + far);
        }
        if (near[0] > near[1]) continue;  // no lane takes the cell
        const MF in_cell = hn::RebindMask(df, hn::Ne(hn::Load(di, takes_cell), hn::Zero(di)));
        const VF ox = hn::Load(df, offset_x);
        const CellCache::Points points = cells.points(cell_x, cell_y);
        if (points.u != nullptr) {
          for (std::uint32_t i = 0; i < points.count; ++i)
            sums.point(cell_x, cell_y, i, points.u[i], points.v[i], points.sign[i], ox, oy, in_cell,
                       near);
        } else {
          std::uint32_t index = 0;
          cells.for_each_point(cell_x, cell_y, [&](float u, float v, float sign) HWY_ATTR {
            sums.point(cell_x, cell_y, index++, u, v, sign, ox, oy, in_cell, near);
          });
        }
      }
    }
  }
  HWY_ALIGN float lane_sums[Channels][kMaxLanes];
  for (int c = 0; c < Channels; ++c) hn::Store(sums.acc[c], df, lane_sums[c]);
  for (std::size_t lane = 0; lane < count; ++lane)
    for (int c = 0; c < Channels; ++c)
      acc_out[(first + lane) * Channels + static_cast<std::size_t>(c)] = lane_sums[c][lane];
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
  end_simd_call();
}

}  // namespace stochtex::texton
#endif  // HWY_ONCE
