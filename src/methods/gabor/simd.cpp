// Gabor noise's kernel sums, one impulse per SIMD lane (simd.hpp). Compiled once per SIMD target by
// Highway's foreach_target.h; impulse_sum dispatches to the best one at run time. The kernel's
// arithmetic is the scalar reference's own source (kernel.inc); every other vector operation below
// is the reference's (evaluate.hpp, model.cpp, core/hash.hpp) in its order: no fused multiply-add
// (the build sets -ffp-contract=off), the same constants, truncating conversions; the values of
// one sample are then added in the reference's order.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/gabor/simd.cpp"
#include "methods/gabor/simd.hpp"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "core/cpu_target.hpp"
#include "core/simd_math.hpp"

HWY_BEFORE_NAMESPACE();
namespace stochtex::gabor::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using stochtex::HWY_NAMESPACE::CosTurns;
using stochtex::HWY_NAMESPACE::CounterDraw;
using stochtex::HWY_NAMESPACE::ExpFloat;
using stochtex::HWY_NAMESPACE::UniformFromDraw;

using DF = hn::ScalableTag<float>;
using DU = hn::RebindToUnsigned<DF>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VU = hn::Vec<DU>;
using VI = hn::Vec<DI>;
constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);
constexpr std::size_t kCapacity = ImpulseCache::kCapacity;

#include "methods/gabor/kernel.inc"

// kernel.inc's operations in every lane.
struct VectorOps {
  static VF constant(float c) { return hn::Set(DF(), c); }
  static VF min(VF a, VF b) { return hn::Min(a, b); }
  static VF neg(VF v) { return hn::Neg(v); }
  static VF exp(VF v) { return ExpFloat(DF(), v); }
  static VF cos(VF v) { return CosTurns(DF(), v); }
};

// Impulses first .. first + n - 1 of cell (x, y) into `list` (simd.hpp's five lists): the draws of
// texton::CellCache (positions, after the count's `chunks` uniforms) and of GridKernels::draw
// (column word, coin, phase: three draws per impulse), each impulse's draws by their counters.
void draw_impulses(const ImpulseCache& cache, std::int64_t x, std::int64_t y, std::uint32_t first,
                   std::uint32_t n, float* list) {
  const DF df;
  const DU du;
  const DI di;
  const std::size_t lanes = hn::Lanes(df);
  const std::uint32_t points = cell_key(x, y, cache.level_seed, Stream::points);
  const std::uint32_t kernels = cell_key(x, y, cache.level_seed, Stream::kernels);
  const VU chunks = hn::Set(du, cache.cell_count->chunks());
  const VF cell_size = hn::Set(df, cache.cell_size);
  const GridKernels& grid = cache.kernels;
  HWY_ALIGN std::uint32_t words[kMaxLanes];
  HWY_ALIGN std::int32_t columns[kMaxLanes];
  for (std::uint32_t j = 0; j < n; j += static_cast<std::uint32_t>(lanes)) {
    const VU index = hn::Iota(du, first + j);
    const VU position = hn::Add(chunks, hn::Add(index, index));
    const VF u = UniformFromDraw(df, CounterDraw(du, points, position));
    const VF v = UniformFromDraw(df, CounterDraw(du, points, hn::Add(position, hn::Set(du, 1u))));
    const VU kernel = hn::Mul(index, hn::Set(du, 3u));
    hn::Store(CounterDraw(du, kernels, kernel), du, words);
    const VF coin = UniformFromDraw(df, CounterDraw(du, kernels, hn::Add(kernel, hn::Set(du, 1u))));
    const VF phase =
        UniformFromDraw(df, CounterDraw(du, kernels, hn::Add(kernel, hn::Set(du, 2u))));
    hn::Store(hn::Mul(u, cell_size), df, list + j);
    hn::Store(hn::Mul(v, cell_size), df, list + kCapacity + j);
    hn::Store(phase, df, list + 4 * kCapacity + j);
    // alias_pick in every lane; the columns' 32 x 32-bit high products one lane at a time.
    for (std::size_t lane = 0; lane < lanes; ++lane)
      columns[lane] = static_cast<std::int32_t>(alias_column(words[lane], grid.count));
    const VI column = hn::Load(di, columns);
    const auto keep =
        hn::RebindMask(di, hn::Lt(coin, hn::GatherIndex(df, grid.probability, column)));
    const VI pick =
        hn::IfThenElse(keep, column, hn::BitCast(di, hn::GatherIndex(du, grid.alias, column)));
    hn::Store(hn::GatherIndex(df, grid.frequency_x, pick), df, list + 2 * kCapacity + j);
    hn::Store(hn::GatherIndex(df, grid.frequency_y, pick), df, list + 3 * kCapacity + j);
  }
}

// The impulses of one sample found within the kernel's support and not yet evaluated, in the
// reference's order: their offsets from the sample (dx, dy in the plane, z1, z2 in a surface
// point's tangent frame), envelopes, frequencies and phases, and for surface noise (7 fields)
// their tent weights. Fewer than one vector's worth wait for the next cell, so the exp and cos
// polynomials run on full vectors.
template <std::size_t Fields>
struct Pending {
  static constexpr std::size_t kFields = Fields;
  HWY_ALIGN float field[kFields][2 * kMaxLanes] = {};
  std::size_t count = 0;
};
using PlanarPending = Pending<6>;
using SurfacePending = Pending<7>;

// KernelShape::at's value (surface noise: the reference's weight * KernelShape::value) for the
// first `count` pending impulses, one per lane, added to `sum` in their order.
template <bool Filtered, std::size_t Fields>
float evaluate_pending(const KernelShape& shape, const Pending<Fields>& pending, std::size_t count,
                       float sum) {
  const DF df;
  const auto field = [&](std::size_t f) HWY_ATTR { return hn::Load(df, pending.field[f]); };
  HWY_ALIGN float values[kMaxLanes] = {};
  VF value = HWY_NAMESPACE::kernel_value(VectorOps{}, shape, Filtered, field(2), field(3), field(4),
                                         field(5), field(0), field(1));
  if constexpr (Fields == SurfacePending::kFields) value = hn::Mul(field(6), value);
  hn::Store(value, df, values);
  for (std::size_t i = 0; i < count; ++i) sum += values[i];
  return sum;
}

// Appends the lanes `inside` of `fields` to `pending`, in their order, and evaluates a full
// vector of pending impulses into `sum`.
template <bool Filtered, std::size_t Fields>
float append_pending(const KernelShape& shape, const VF (&fields)[Fields], hn::Mask<DF> inside,
                     Pending<Fields>& pending, float sum) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  for (std::size_t f = 0; f < Fields; ++f)
    hn::StoreU(hn::Compress(fields[f], inside), df, pending.field[f] + pending.count);
  pending.count += hn::CountTrue(df, inside);
  if (pending.count < lanes) return sum;
  sum = evaluate_pending<Filtered>(shape, pending, lanes, sum);
  pending.count -= lanes;
  for (std::size_t f = 0; f < Fields; ++f)
    hn::Store(hn::LoadU(df, pending.field[f] + lanes), df, pending.field[f]);
  return sum;
}

// Appends the impulses of `list` (n of them) within the kernel's support at offset
// (offset_x, offset_y) from their cell's corner to `pending`, in their order, and evaluates each
// full vector of them into `sum`.
template <bool Filtered>
float add_kernels(const KernelShape& shape, const float* list, std::uint32_t n, float offset_x,
                  float offset_y, PlanarPending& pending, float sum) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  const VF ox = hn::Set(df, offset_x);
  const VF oy = hn::Set(df, offset_y);
  for (std::uint32_t j = 0; j < n; j += static_cast<std::uint32_t>(lanes)) {
    const VF dx = hn::Sub(ox, hn::Load(df, list + j));
    const VF dy = hn::Sub(oy, hn::Load(df, list + kCapacity + j));
    const VF envelope = HWY_NAMESPACE::kernel_envelope(VectorOps{}, shape, dx, dy);
    const auto inside = hn::And(hn::FirstN(df, n - j), hn::Lt(envelope, hn::Set(df, kPiF)));
    if (hn::AllFalse(df, inside)) continue;
    const VF fields[PlanarPending::kFields] = {dx,
                                               dy,
                                               envelope,
                                               hn::Load(df, list + 2 * kCapacity + j),
                                               hn::Load(df, list + 3 * kCapacity + j),
                                               hn::Load(df, list + 4 * kCapacity + j)};
    sum = append_pending<Filtered>(shape, fields, inside, pending, sum);
  }
  return sum;
}

template <bool Filtered>
float impulse_sum_typed(ImpulseCache& cache, const KernelShape& shape, const CellRange& cells,
                        Vec2d p, double cell_size) {
  float sum = 0.0f;
  PlanarPending pending;
  for (std::int64_t cell_y = cells.first_y; cell_y <= cells.last_y; ++cell_y) {
    const float offset_y = cell_offset(p.y, cell_y, cell_size);
    for (std::int64_t cell_x = cells.first_x; cell_x <= cells.last_x; ++cell_x) {
      const float offset_x = cell_offset(p.x, cell_x, cell_size);
      const std::size_t slot = ImpulseCache::slot(cell_x, cell_y);
      std::uint32_t count;
      float* list = cache.lists(slot);
      if (cache.valid[slot] && cache.x[slot] == cell_x && cache.y[slot] == cell_y) {
        count = cache.count[slot];
      } else {
        CounterRng rng(cell_key(cell_x, cell_y, cache.level_seed, Stream::points));
        count = (*cache.cell_count)(rng);
        if (count <= kCapacity) {
          draw_impulses(cache, cell_x, cell_y, 0, count, list);
          cache.valid[slot] = true;
          cache.x[slot] = cell_x;
          cache.y[slot] = cell_y;
          cache.count[slot] = count;
        }
      }
      if (count <= kCapacity) {
        sum = add_kernels<Filtered>(shape, list, count, offset_x, offset_y, pending, sum);
        continue;
      }
      for (std::uint32_t first = 0; first < count; first += kCapacity) {
        const std::uint32_t block = std::min<std::uint32_t>(kCapacity, count - first);
        draw_impulses(cache, cell_x, cell_y, first, block, cache.scratch);
        sum = add_kernels<Filtered>(shape, cache.scratch, block, offset_x, offset_y, pending, sum);
      }
    }
  }
  return pending.count == 0 ? sum : evaluate_pending<Filtered>(shape, pending, pending.count, sum);
}

template <bool Filtered>
float surface_sum_typed(const GridKernels& grid, const KernelShape& shape, const SurfacePoint& p,
                        const SurfaceFrame& f, double reach, double depth, double cell_size,
                        const CellCount& count, std::uint32_t seed) {
  const DF df;
  const DU du;
  const DI di;
  const std::size_t lanes = hn::Lanes(df);
  // An impulse's draws: its position's three, then its kernel's (the reference's visitor draws
  // or skips them alike).
  constexpr std::uint32_t kStride = 3 + GridKernels::kDraws;
  const VF side = hn::Set(df, static_cast<float>(cell_size));
  const VF inverse_depth = hn::Set(df, static_cast<float>(1.0 / depth));
  const VF u1[3] = {hn::Set(df, f.u1[0]), hn::Set(df, f.u1[1]), hn::Set(df, f.u1[2])};
  const VF u2[3] = {hn::Set(df, f.u2[0]), hn::Set(df, f.u2[1]), hn::Set(df, f.u2[2])};
  const VF u3[3] = {hn::Set(df, f.u3[0]), hn::Set(df, f.u3[1]), hn::Set(df, f.u3[2])};
  const auto along = [](const VF(&u)[3], VF x, VF y, VF z) HWY_ATTR {
    return hn::Add(hn::Add(hn::Mul(x, u[0]), hn::Mul(y, u[1])), hn::Mul(z, u[2]));
  };
  float sum = 0.0f;
  SurfacePending pending;
  HWY_ALIGN std::uint32_t words[kMaxLanes];
  HWY_ALIGN std::int32_t columns[kMaxLanes];
  for_each_surface_cell(
      p, f, reach, depth, cell_size,
      [&](std::int64_t cx, std::int64_t cy, std::int64_t cz, float ox, float oy,
          float oz) HWY_ATTR {
        const std::uint32_t key = cell_key(cx, cy, cz, seed, Stream::points);
        CounterRng rng(key);
        const std::uint32_t n = count(rng);
        const VU first_draw = hn::Set(du, count.chunks());
        for (std::uint32_t j = 0; j < n; j += static_cast<std::uint32_t>(lanes)) {
          const VU draw = hn::Add(first_draw, hn::Mul(hn::Iota(du, j), hn::Set(du, kStride)));
          const auto uniform = [&](std::uint32_t k) HWY_ATTR {
            return UniformFromDraw(df, CounterDraw(du, key, hn::Add(draw, hn::Set(du, k))));
          };
          const VF dx = hn::Sub(hn::Set(df, ox), hn::Mul(uniform(0), side));
          const VF dy = hn::Sub(hn::Set(df, oy), hn::Mul(uniform(1), side));
          const VF dz = hn::Sub(hn::Set(df, oz), hn::Mul(uniform(2), side));
          const VF t = along(u3, dx, dy, dz);
          const VF z1 = along(u1, dx, dy, dz);
          const VF z2 = along(u2, dx, dy, dz);
          const VF weight = hn::Sub(hn::Set(df, 1.0f), hn::Mul(hn::Abs(t), inverse_depth));
          const VF envelope = hn::IfThenElse(
              hn::Gt(weight, hn::Zero(df)),
              HWY_NAMESPACE::kernel_envelope(VectorOps{}, shape, z1, z2), hn::Set(df, kPiF));
          const auto inside = hn::And(hn::FirstN(df, n - j), hn::Lt(envelope, hn::Set(df, kPiF)));
          if (hn::AllFalse(df, inside)) continue;
          // GridKernels::draw in every lane: column word, coin, phase.
          hn::Store(CounterDraw(du, key, hn::Add(draw, hn::Set(du, 3u))), du, words);
          const VF coin = uniform(4);
          const VF phase = uniform(5);
          for (std::size_t lane = 0; lane < lanes; ++lane)
            columns[lane] = static_cast<std::int32_t>(alias_column(words[lane], grid.count));
          const VI column = hn::Load(di, columns);
          const auto keep =
              hn::RebindMask(di, hn::Lt(coin, hn::GatherIndex(df, grid.probability, column)));
          const VI pick = hn::IfThenElse(keep, column,
                                         hn::BitCast(di, hn::GatherIndex(du, grid.alias, column)));
          const VF fields[SurfacePending::kFields] = {z1,
                                                      z2,
                                                      envelope,
                                                      hn::GatherIndex(df, grid.frequency_x, pick),
                                                      hn::GatherIndex(df, grid.frequency_y, pick),
                                                      phase,
                                                      weight};
          sum = append_pending<Filtered>(shape, fields, inside, pending, sum);
        }
      });
  return pending.count == 0 ? sum : evaluate_pending<Filtered>(shape, pending, pending.count, sum);
}

float SurfaceImpulseSum(const GridKernels& grid, const KernelShape& shape, const SurfacePoint& p,
                        const SurfaceFrame& f, double reach, double depth, double cell_size,
                        const CellCount& count, std::uint32_t seed) {
  return shape.filtered
             ? surface_sum_typed<true>(grid, shape, p, f, reach, depth, cell_size, count, seed)
             : surface_sum_typed<false>(grid, shape, p, f, reach, depth, cell_size, count, seed);
}

float ImpulseSum(ImpulseCache& cache, const KernelShape& shape, const CellRange& cells, Vec2d p,
                 double cell_size) {
  return shape.filtered ? impulse_sum_typed<true>(cache, shape, cells, p, cell_size)
                        : impulse_sum_typed<false>(cache, shape, cells, p, cell_size);
}

}  // namespace stochtex::gabor::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::gabor {

HWY_EXPORT(ImpulseSum);
HWY_EXPORT(SurfaceImpulseSum);

float impulse_sum(ImpulseCache& cache, const KernelShape& shape, const CellRange& cells, Vec2d p,
                  double cell_size) noexcept {
  const float sum = HWY_DYNAMIC_DISPATCH(ImpulseSum)(cache, shape, cells, p, cell_size);
  end_simd_call();
  return sum;
}

float surface_impulse_sum(const GridKernels& kernels, const KernelShape& shape,
                          const SurfacePoint& p, const SurfaceFrame& frame, double reach,
                          double depth, double cell_size, const CellCount& count,
                          std::uint32_t seed) noexcept {
  const float sum = HWY_DYNAMIC_DISPATCH(SurfaceImpulseSum)(kernels, shape, p, frame, reach, depth,
                                                            cell_size, count, seed);
  end_simd_call();
  return sum;
}

}  // namespace stochtex::gabor
#endif  // HWY_ONCE
