// Histogram-preserving tiling and blending, one sample per SIMD lane (simd.hpp). Compiled once per
// SIMD target by Highway's foreach_target.h; evaluate_lanes dispatches to the best one at run
// time. The blend weights, the bilinear fetch, erf and the look-up tables are the scalar
// reference's own source (kernel.inc); every other vector operation below is the reference's
// (evaluate.hpp, evaluator.cpp) in its order: no fused multiply-add (the build sets
// -ffp-contract=off), the same constants and float or double types, truncating conversions, IEEE
// division and square root, and selection where the scalar code branches. The double-precision
// steps (the lattice, the wrap, erf) run on half as many lanes at a time.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/tiling/simd.cpp"
#include "methods/tiling/simd.hpp"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>

#include "core/cpu_target.hpp"
#include "core/hash.hpp"
#include "core/simd_math.hpp"
#include "methods/tiling/evaluate.hpp"

HWY_BEFORE_NAMESPACE();
namespace stochtex::tiling::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using stochtex::HWY_NAMESPACE::PcgHash;

using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using DU = hn::RebindToUnsigned<DF>;
using DD = hn::ScalableTag<double>;
using DFH = hn::Rebind<float, DD>;  // as many float lanes as DD has
using DIH = hn::Rebind<std::int32_t, DD>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using VU = hn::Vec<DU>;
using VD = hn::Vec<DD>;
using MF = hn::Mask<DF>;
constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);

// cell_key(x, y, seed, stream) (core/hash.hpp: pcg4d's first word) in every lane; x, y are the
// low 32 bits of the cell.
HWY_INLINE VU cell_key(DU du, VU x, VU y, std::uint32_t seed, Stream stream) {
  const VU a = hn::Set(du, 1664525u);
  const VU b = hn::Set(du, 1013904223u);
  VU v0 = hn::Add(hn::Mul(x, a), b);
  VU v1 = hn::Add(hn::Mul(y, a), b);
  VU v2 = hn::Set(du, seed * 1664525u + 1013904223u);
  VU v3 = hn::Set(du, static_cast<std::uint32_t>(stream) * 1664525u + 1013904223u);
  v0 = hn::Add(v0, hn::Mul(v1, v3));
  v1 = hn::Add(v1, hn::Mul(v2, v0));
  v2 = hn::Add(v2, hn::Mul(v0, v1));
  v3 = hn::Add(v3, hn::Mul(v1, v2));
  v0 = hn::Xor(v0, hn::ShiftRight<16>(v0));
  v1 = hn::Xor(v1, hn::ShiftRight<16>(v1));
  v3 = hn::Xor(v3, hn::ShiftRight<16>(v3));
  return hn::Add(v0, hn::Mul(v1, v3));
}

// floor(u * size / 2^32) for size <= 65536 (vertex_offset's 64-bit product) in 32-bit lanes:
// with u = a 2^16 + b, it is (a size + floor(b size / 2^16)) / 2^16, every term below 2^32.
HWY_INLINE VU scale_draw(DU du, VU u, std::uint32_t size) {
  const VU s = hn::Set(du, size);
  const VU high = hn::Mul(hn::ShiftRight<16>(u), s);
  const VU low = hn::ShiftRight<16>(hn::Mul(hn::And(u, hn::Set(du, 0xffffu)), s));
  return hn::ShiftRight<16>(hn::Add(high, low));
}

// The low 32 bits of the integer-valued double c (static_cast<std::uint32_t> of the int64 cell),
// as a signed lane: c mod 2^32 is exact in double, and shifted by 2^31 it fits an int32.
HWY_INLINE hn::Vec<DIH> low_bits(DD dd, VD c) {
  const VD period = hn::Set(dd, 4294967296.0);
  const VD wrapped = hn::Sub(c, hn::Mul(period, hn::Floor(hn::Div(c, period))));
  return hn::DemoteTo(DIH(), hn::Sub(wrapped, hn::Set(dd, 2147483648.0)));
}

#include "methods/tiling/kernel.inc"

// kernel.inc's operations in every lane; erf in double on half the lanes at a time.
struct VectorOps {
  using F = VF;
  using I = VI;
  using D = VD;
  static VF f(float c) { return hn::Set(DF(), c); }
  static VI i(std::int32_t c) { return hn::Set(DI(), c); }
  static VD d(double c) { return hn::Set(DD(), c); }
  static VF floor(VF v) { return hn::Floor(v); }
  static VD floor(VD v) { return hn::Floor(v); }
  static VI to_int(VF v) { return hn::ConvertTo(DI(), v); }
  static VF to_float(VI v) { return hn::ConvertTo(DF(), v); }
  template <class M, class V>
  static V select(M condition, V a, V b) {
    return hn::IfThenElse(condition, a, b);
  }
  static VI add_where(hn::Mask<DI> condition, VI x, VI y) {
    return hn::IfThenElse(condition, x + y, x);
  }
  static VI subtract_unless(hn::Mask<DI> condition, VI x, VI y) {
    return hn::IfThenElse(condition, x, x - y);
  }
  static VF sqrt(VF v) { return hn::Sqrt(v); }
  static VF erf(VF x) {
    const DF df;
    const DD dd;
    const DFH dfh;
    HWY_ALIGN float lanes[kMaxLanes];
    hn::Store(x, df, lanes);
    for (std::size_t i = 0; i < hn::Lanes(df); i += hn::Lanes(dd))
      hn::StoreU(
          hn::DemoteTo(dfh, erf_ratio(VectorOps{}, hn::PromoteTo(dd, hn::LoadU(dfh, lanes + i)))),
          dfh, lanes + i);
    return hn::Load(df, lanes);
  }
  static VF gather(const float* base, VI index) { return hn::GatherIndex(DF(), base, index); }
};

// TilingModel::inverse_at_level in every lane, each at its own level.
void inverse_at_level(const SimdTiling& m, const VF* g, VI level, VF* out) {
  const VectorOps ops;
  const VI tables = level * ops.i(m.table_floats);
  for (const TableGroup& group : m.groups) {
    const VF* gg = g + group.first;
    VF* o = out + group.first;
    if (group.transform == GroupTransform::lut) {
      const VI lut = level * ops.i(m.lut_floats);
      lut_value(
          ops, m.lut_size, gg,
          [&](VI corner, int offset)
              HWY_ATTR { return ops.gather(m.luts, lut + corner + ops.i(offset)); },
          o);
    } else if (group.transform == GroupTransform::decorrelated) {
      const int cc = group.channels;
      VF decorrelated[kMaxChannels];
      for (int c = 0; c < cc; ++c)
        decorrelated[c] =
            table_lookup(ops, m.tables, tables + ops.i((group.first_table + c) * m.table_size),
                         m.table_size, gg[c]);
      from_decorrelated(ops, cc, m.colour_basis + group.first_basis,
                        m.colour_mean + group.first_mean, decorrelated, o);
    } else {
      o[0] = table_lookup(ops, m.tables, tables + ops.i(group.first_table * m.table_size),
                          m.table_size, gg[0]);
    }
  }
}

// One pyramid level per lane (TilingModel::level): its shape and its first texel in the pyramid.
struct LevelLanes {
  BilinearLevel<VectorOps> shape;
  VI first;
};

LevelLanes level_lanes(DF df, const SimdTiling& m, VI level, bool uniform) {
  const DI di;
  LevelLanes l;
  BilinearLevel<VectorOps>& shape = l.shape;
  if (uniform) {
    const auto i = static_cast<std::size_t>(hn::GetLane(level));
    shape.texels_per_pixel_x = hn::Set(df, m.texels_per_pixel_x[i]);
    shape.texels_per_pixel_y = hn::Set(df, m.texels_per_pixel_y[i]);
    shape.width = hn::Set(di, m.level_width[i]);
    shape.height = hn::Set(di, m.level_height[i]);
    l.first = hn::Set(di, m.level_first[i]);
  } else {
    shape.texels_per_pixel_x = hn::GatherIndex(df, m.texels_per_pixel_x.data(), level);
    shape.texels_per_pixel_y = hn::GatherIndex(df, m.texels_per_pixel_y.data(), level);
    shape.width = hn::GatherIndex(di, m.level_width.data(), level);
    shape.height = hn::GatherIndex(di, m.level_height.data(), level);
    l.first = hn::GatherIndex(di, m.level_first.data(), level);
  }
  shape.width_f = hn::ConvertTo(df, shape.width);
  shape.height_f = hn::ConvertTo(df, shape.height);
  return l;
}

// The texels of `channels` interleaved channels (1 to 4) at p, p + channels, ... in lanes 0, 1,
// ...: one lane per texel, channel c in out[c].
HWY_INLINE void load_texels(const float* p, int channels, VF* out) {
  const DF df;
  switch (channels) {
    case 1:
      out[0] = hn::LoadU(df, p);
      return;
    case 2:
      hn::LoadInterleaved2(df, p, out[0], out[1]);
      return;
    case 3:
      hn::LoadInterleaved3(df, p, out[0], out[1], out[2]);
      return;
    default:
      hn::LoadInterleaved4(df, p, out[0], out[1], out[2], out[3]);
      return;
  }
}

// fetch_bilinear (evaluate.hpp) in every lane: acc[c] += weight * level(x, y)[c] where `take`.
// Where the lanes read neighbouring texels of the same two rows, left to right without a wrap (a
// row of point samples within one patch at scale 1), vector loads replace the gathers: the same
// texels, so the same sums.
HWY_INLINE void fetch_bilinear(const SimdTiling& m, const LevelLanes& l, VF x, VF y, VF weight,
                               MF take, VF* acc) {
  const DI di;
  const VectorOps ops;
  const BilinearTaps<VectorOps> taps = bilinear_taps(ops, l.shape, x, y, weight);
  const VI channels = ops.i(m.channels);
  const VI row = l.shape.width * channels;
  const VI r0 = l.first + taps.y0 * row;
  const VI r1 = l.first + taps.y1 * row;
  const VI x0 = taps.x0 * channels;
  const VI x1 = taps.x1 * channels;
  const std::int32_t first_x = hn::GetLane(taps.x0);
  const std::int32_t row_0 = hn::GetLane(r0);
  const std::int32_t row_1 = hn::GetLane(r1);
  if (m.channels <= 4 && hn::AllTrue(di, hn::Eq(taps.x0, hn::Iota(di, first_x))) &&
      hn::AllTrue(di, hn::Eq(taps.x1, hn::Iota(di, first_x + 1))) &&
      hn::AllTrue(di, hn::Eq(r0, hn::Set(di, row_0))) &&
      hn::AllTrue(di, hn::Eq(r1, hn::Set(di, row_1)))) {
    VF t00[4], t10[4], t01[4], t11[4];
    const float* top = m.pyramid + row_0 + first_x * m.channels;
    const float* bottom = m.pyramid + row_1 + first_x * m.channels;
    load_texels(top, m.channels, t00);
    load_texels(top + m.channels, m.channels, t10);
    load_texels(bottom, m.channels, t01);
    load_texels(bottom + m.channels, m.channels, t11);
    for (int c = 0; c < m.channels; ++c) {
      const VF sum = bilinear_sum(taps, t00[c], t10[c], t01[c], t11[c]);
      acc[c] = hn::IfThenElse(take, acc[c] + sum, acc[c]);
    }
    return;
  }
  for (int c = 0; c < m.channels; ++c) {
    const VI k = ops.i(c);
    const VF sum =
        bilinear_sum(taps, ops.gather(m.pyramid, r0 + x0 + k), ops.gather(m.pyramid, r0 + x1 + k),
                     ops.gather(m.pyramid, r1 + x0 + k), ops.gather(m.pyramid, r1 + x1 + k));
    acc[c] = hn::IfThenElse(take, acc[c] + sum, acc[c]);
  }
}

// The per-lane inputs that the double-precision steps give: triangle_lattice's cell (low 32
// bits) and fraction, and wrap_position.
struct LatticeLanes {
  HWY_ALIGN float fraction_x[kMaxLanes];
  HWY_ALIGN float fraction_y[kMaxLanes];
  HWY_ALIGN float wrapped_x[kMaxLanes];
  HWY_ALIGN float wrapped_y[kMaxLanes];
  HWY_ALIGN std::int32_t cell_x[kMaxLanes];  // low 32 bits - 2^31
  HWY_ALIGN std::int32_t cell_y[kMaxLanes];
};

void lattice_lanes(const SimdTiling& m, std::span<const Vec2d> positions, std::size_t first,
                   LatticeLanes& out) {
  const DD dd;
  const DFH dfh;
  const DIH dih;
  const std::size_t lanes = hn::Lanes(DF());
  HWY_ALIGN double px[kMaxLanes];
  HWY_ALIGN double py[kMaxLanes];
  // Lanes past the end repeat the last position; their results are dropped.
  for (std::size_t lane = 0; lane < lanes; ++lane) {
    const Vec2d p = positions[std::min(first + lane, positions.size() - 1)];
    px[lane] = p.x;
    py[lane] = p.y;
  }
  const VD edge = hn::Set(dd, m.edge);
  const VD width = hn::Set(dd, static_cast<double>(m.width));
  const VD height = hn::Set(dd, static_cast<double>(m.height));
  const VectorOps ops;
  for (std::size_t i = 0; i < lanes; i += hn::Lanes(dd)) {
    const VD x = hn::Load(dd, px + i);
    const VD y = hn::Load(dd, py + i);
    VD skewed_x, skewed_y;
    skew(ops, x, y, edge, skewed_x, skewed_y);
    const VD cell_x = hn::Floor(skewed_x);
    const VD cell_y = hn::Floor(skewed_y);
    hn::StoreU(hn::DemoteTo(dfh, hn::Sub(skewed_x, cell_x)), dfh, out.fraction_x + i);
    hn::StoreU(hn::DemoteTo(dfh, hn::Sub(skewed_y, cell_y)), dfh, out.fraction_y + i);
    hn::StoreU(low_bits(dd, cell_x), dih, out.cell_x + i);
    hn::StoreU(low_bits(dd, cell_y), dih, out.cell_y + i);
    hn::StoreU(hn::DemoteTo(dfh, wrap(ops, x, width)), dfh, out.wrapped_x + i);
    hn::StoreU(hn::DemoteTo(dfh, wrap(ops, y, height)), dfh, out.wrapped_y + i);
  }
}

void Lanes(const SimdTiling& m, std::span<const Vec2d> positions, std::size_t first,
           const std::int32_t* levels, const float* blends, std::uint32_t seed,
           ImageView<float> out, std::size_t out_first) {
  const DF df;
  const DI di;
  const DU du;
  const std::size_t lanes = hn::Lanes(df);
  const std::size_t count = std::min(lanes, positions.size() - first);

  LatticeLanes lattice;
  lattice_lanes(m, positions, first, lattice);
  HWY_ALIGN std::int32_t lane_levels[kMaxLanes];
  HWY_ALIGN float blend_lanes[kMaxLanes];
  bool uniform = true;
  bool any_blend = false;
  for (std::size_t lane = 0; lane < lanes; ++lane) {
    const std::size_t i = first + std::min(lane, count - 1);
    lane_levels[lane] = levels[i];
    blend_lanes[lane] = blends[i];
    uniform = uniform && levels[i] == levels[first];
    any_blend = any_blend || blends[i] > 0.0f;
  }
  const VI level = hn::Load(di, lane_levels);
  const VF blend = hn::Load(df, blend_lanes);
  const MF blended = hn::Gt(blend, hn::Zero(df));
  const VI coarse_level = hn::Min(hn::Add(level, hn::Set(di, 1)), hn::Set(di, m.level_count - 1));

  // triangle_lattice: the weights and the vertices' cells.
  const VectorOps ops;
  const VF one = ops.f(1.0f);
  VF weight[3];
  const MF lower = triangle_weights(ops, hn::Load(df, lattice.fraction_x),
                                    hn::Load(df, lattice.fraction_y), weight);
  const VU sign = hn::Set(du, 0x80000000u);
  const VU base_x = hn::Xor(hn::BitCast(du, hn::Load(di, lattice.cell_x)), sign);
  const VU base_y = hn::Xor(hn::BitCast(du, hn::Load(di, lattice.cell_y)), sign);
  const VU upper_step = hn::IfThenZeroElse(hn::RebindMask(du, lower), hn::Set(du, 1u));
  const VU lower_step = hn::Sub(hn::Set(du, 1u), upper_step);
  const VU vertex_x[3] = {hn::Add(base_x, upper_step), hn::Add(base_x, lower_step),
                          hn::Add(base_x, upper_step)};
  const VU vertex_y[3] = {hn::Add(base_y, upper_step), hn::Add(base_y, upper_step),
                          hn::Add(base_y, lower_step)};
  const VF wrapped_x = hn::Load(df, lattice.wrapped_x);
  const VF wrapped_y = hn::Load(df, lattice.wrapped_y);

  const LevelLanes fine = level_lanes(df, m, level, uniform);
  const LevelLanes coarse = level_lanes(df, m, coarse_level, uniform);
  const MF all = hn::FirstN(df, lanes);
  const VU draw_0 = hn::Set(du, stochtex::pcg_hash(0u));
  const VU draw_1 = hn::Set(du, stochtex::pcg_hash(1u));
  VF acc[kMaxChannels];
  for (int c = 0; c < m.channels; ++c) acc[c] = hn::Zero(df);
  VF weight_squares = hn::Zero(df);
  for (int v = 0; v < 3; ++v) {
    const VF w = weight[v];
    weight_squares = hn::Add(weight_squares, hn::Mul(w, w));
    // vertex_offset: two draws from the vertex's key, scaled to the exemplar's period.
    const VU key = cell_key(du, vertex_x[v], vertex_y[v], seed, Stream::offsets);
    const VU offset_x =
        scale_draw(du, PcgHash(du, hn::Xor(key, draw_0)), static_cast<std::uint32_t>(m.width));
    const VU offset_y =
        scale_draw(du, PcgHash(du, hn::Xor(key, draw_1)), static_cast<std::uint32_t>(m.height));
    const VF x = hn::Add(wrapped_x, hn::ConvertTo(df, hn::BitCast(di, offset_x)));
    const VF y = hn::Add(wrapped_y, hn::ConvertTo(df, hn::BitCast(di, offset_y)));
    fetch_bilinear(m, fine, x, y, w * (one - blend), all, acc);
    if (any_blend) fetch_bilinear(m, coarse, x, y, w * blend, blended, acc);
  }
  VF g[kMaxChannels];
  blend_to_gaussian(ops, m.channels, m.linear, m.blend_mean, weight_squares, acc, g);

  VF value[kMaxChannels];
  if (m.inverse) {
    inverse_at_level(m, g, level, value);
    if (any_blend) {
      VF coarse_value[kMaxChannels];
      inverse_at_level(m, g, coarse_level, coarse_value);
      for (int c = 0; c < m.channels; ++c)
        value[c] = hn::IfThenElse(blended, interpolate(value[c], coarse_value[c], blend), value[c]);
    }
  } else {
    for (int c = 0; c < m.channels; ++c) value[c] = g[c];
  }

  const auto width = static_cast<std::size_t>(out.width);
  const std::size_t start = out_first + first;
  if (count == lanes && start % width + lanes <= width && out.channels == m.channels &&
      (m.channels == 3 || m.channels == 4)) {
    // A full vector of samples within one row of out: interleaved stores.
    float* pixel = &out.at(static_cast<int>(start % width), static_cast<int>(start / width), 0);
    if (m.channels == 3)
      hn::StoreInterleaved3(value[0], value[1], value[2], df, pixel);
    else
      hn::StoreInterleaved4(value[0], value[1], value[2], value[3], df, pixel);
    return;
  }
  HWY_ALIGN float result[kMaxChannels][kMaxLanes];
  for (int c = 0; c < m.channels; ++c) hn::Store(value[c], df, result[c]);
  for (std::size_t lane = 0; lane < count; ++lane) {
    const std::size_t index = out_first + first + lane;
    float* pixel = &out.at(static_cast<int>(index % width), static_cast<int>(index / width), 0);
    for (int c = 0; c < m.channels; ++c) pixel[c] = result[c][lane];
  }
}

void EvaluateLanes(const SimdTiling& m, std::span<const Vec2d> positions,
                   const std::int32_t* levels, const float* blends, std::uint32_t seed,
                   ImageView<float> out, std::size_t first) {
  const std::size_t lanes = hn::Lanes(DF());
  for (std::size_t i = 0; i < positions.size(); i += lanes)
    Lanes(m, positions, i, levels, blends, seed, out, first);
}

void TableCoordinates(const float* g, std::size_t count, int size, std::int32_t* cells,
                      float* fractions) {
  const DF df;
  const DI di;
  const VectorOps ops;
  const std::size_t lanes = hn::Lanes(df);
  HWY_ALIGN float in[kMaxLanes] = {};
  HWY_ALIGN float t[kMaxLanes];
  HWY_ALIGN std::int32_t c[kMaxLanes];
  for (std::size_t i = 0; i < count; i += lanes) {
    const std::size_t n = std::min(lanes, count - i);
    std::copy_n(g + i, n, in);
    VI cell;
    hn::Store(table_coordinate(ops, gaussian_to_uniform(ops, hn::Load(df, in)), size, cell), df, t);
    hn::Store(cell, di, c);
    std::copy_n(t, n, fractions + i);
    std::copy_n(c, n, cells + i);
  }
}

// apply_rows: the sums of a block of kSums double vectors of neighbouring j run side by side
// (enough to hide the latency of the additions); the j the blocks leave take the scalar loop.
void ApplyRows(const SparseRows& m, const float* in, float* out, std::size_t width) {
  constexpr std::size_t kSums = 8;
  const DD dd;
  const DFH dfh;
  const std::size_t half = hn::Lanes(dd);
  const std::size_t block = kSums * half;
  for (std::size_t i = 0; i < m.rows; ++i) {
    float* row = out + i * width;
    std::size_t j = 0;
    for (; j + block <= width; j += block) {
      VD sums[kSums];
      for (VD& sum : sums) sum = hn::Zero(dd);
      for (std::size_t k = m.first[i]; k < m.first[i + 1]; ++k) {
        const auto weight = hn::Set(dfh, m.weights[k]);
        const float* from = in + static_cast<std::size_t>(m.cells[k]) * width + j;
        for (std::size_t s = 0; s < kSums; ++s)
          sums[s] =
              hn::Add(sums[s], hn::PromoteTo(dd, hn::Mul(weight, hn::LoadU(dfh, from + s * half))));
      }
      for (std::size_t s = 0; s < kSums; ++s)
        hn::StoreU(hn::DemoteTo(dfh, sums[s]), dfh, row + j + s * half);
    }
    for (; j < width; ++j) {
      double sum = 0.0;
      for (std::size_t k = m.first[i]; k < m.first[i + 1]; ++k)
        sum += m.weights[k] * in[static_cast<std::size_t>(m.cells[k]) * width + j];
      row[j] = static_cast<float>(sum);
    }
  }
}

}  // namespace stochtex::tiling::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::tiling {

HWY_EXPORT(EvaluateLanes);

void evaluate_lanes(const SimdTiling& model, std::span<const Vec2d> positions,
                    const std::int32_t* levels, const float* blends, std::uint32_t seed,
                    ImageView<float> out, std::size_t first) noexcept {
  HWY_DYNAMIC_DISPATCH(EvaluateLanes)(model, positions, levels, blends, seed, out, first);
  end_simd_call();
}

HWY_EXPORT(TableCoordinates);

void table_coordinates(const float* g, std::size_t count, int size, std::int32_t* cells,
                       float* fractions) noexcept {
  HWY_DYNAMIC_DISPATCH(TableCoordinates)(g, count, size, cells, fractions);
  end_simd_call();
}

HWY_EXPORT(ApplyRows);

void apply_rows(const SparseRows& matrix, const float* in, float* out, std::size_t width) noexcept {
  HWY_DYNAMIC_DISPATCH(ApplyRows)(matrix, in, out, width);
  end_simd_call();
}

}  // namespace stochtex::tiling
#endif  // HWY_ONCE
