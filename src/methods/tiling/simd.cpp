// Histogram-preserving tiling and blending, one sample per SIMD lane (simd.hpp). Compiled once per
// SIMD target by Highway's foreach_target.h; evaluate_lanes dispatches to the best one at run
// time. Every vector operation below is the scalar reference's (evaluate.hpp, model.cpp) in its
// order: no fused multiply-add (the build sets -ffp-contract=off), the same constants and float
// or double types, truncating conversions, IEEE division and square root, and selection where the
// scalar code branches. The double-precision steps (the lattice, the wrap, erf) run on half as
// many lanes at a time.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/tiling/simd.cpp"
#include "methods/tiling/simd.hpp"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "core/cpu_target.hpp"
#include "core/hash.hpp"
#include "methods/tiling/evaluate.hpp"

HWY_BEFORE_NAMESPACE();
namespace stochtex::tiling::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

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

// pcg_hash (core/hash.hpp) in every lane.
HWY_INLINE VU pcg_hash(DU du, VU v) {
  const VU state = hn::Add(hn::Mul(v, hn::Set(du, 747796405u)), hn::Set(du, 2891336453u));
  const VU shift = hn::Add(hn::ShiftRight<28>(state), hn::Set(du, 4u));
  const VU word = hn::Mul(hn::Xor(hn::Shr(state, shift), state), hn::Set(du, 277803737u));
  return hn::Xor(hn::ShiftRight<22>(word), word);
}

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

// erf_rational (evaluate.hpp) in every lane, in double on half the lanes at a time.
HWY_INLINE VF erf_rational(DF df, VF x) {
  const DD dd;
  const DFH dfh;
  HWY_ALIGN float lanes[kMaxLanes];
  hn::Store(x, df, lanes);
  const VD low = hn::Set(dd, -kErfClamp);
  const VD high = hn::Set(dd, kErfClamp);
  for (std::size_t i = 0; i < hn::Lanes(df); i += hn::Lanes(dd)) {
    VD t = hn::PromoteTo(dd, hn::LoadU(dfh, lanes + i));
    t = hn::IfThenElse(hn::Lt(t, low), low, hn::IfThenElse(hn::Gt(t, high), high, t));
    const VD t2 = hn::Mul(t, t);
    VD p = hn::Set(dd, kErfNumerator[0]);
    for (std::size_t k = 1; k < std::size(kErfNumerator); ++k)
      p = hn::Add(hn::Mul(p, t2), hn::Set(dd, kErfNumerator[k]));
    VD q = hn::Set(dd, kErfDenominator[0]);
    for (std::size_t k = 1; k < std::size(kErfDenominator); ++k)
      q = hn::Add(hn::Mul(q, t2), hn::Set(dd, kErfDenominator[k]));
    hn::StoreU(hn::DemoteTo(dfh, hn::Div(hn::Mul(t, p), q)), dfh, lanes + i);
  }
  return hn::Load(df, lanes);
}

// table_coordinate(gaussian_to_uniform(g), size) (evaluate.hpp) in every lane: the fraction,
// and the first cell in `first`.
HWY_INLINE VF table_coordinate(DF df, VF g, int size, VI& first) {
  const DI di;
  const VF half = hn::Set(df, 0.5f);
  const VF u =
      hn::Add(half, hn::Mul(half, erf_rational(df, hn::Mul(hn::Sub(g, hn::Set(df, kGaussianMean)),
                                                           hn::Set(df, kErfScale)))));
  const VF last = hn::Set(df, static_cast<float>(size - 1));
  VF x = hn::Sub(hn::Mul(u, hn::Set(df, static_cast<float>(size))), half);
  x = hn::IfThenElse(hn::Lt(x, hn::Zero(df)), hn::Zero(df),
                     hn::IfThenElse(hn::Gt(x, last), last, x));
  first = hn::ConvertTo(di, x);
  const VI top = hn::Set(di, size - 2);
  first = hn::IfThenElse(hn::Gt(first, top), top, first);
  return hn::Sub(x, hn::ConvertTo(df, first));
}

// table_lookup (model.cpp): the 1-D table at `table` (an index in `tables`, per lane) at g.
HWY_INLINE VF table_lookup(DF df, const float* tables, VI table, int size, VF g) {
  VI cell;
  const VF t = table_coordinate(df, g, size, cell);
  const VI index = hn::Add(table, cell);
  const VF a = hn::GatherIndex(df, tables, index);
  const VF b = hn::GatherIndex(df, tables, hn::Add(index, hn::Set(DI(), 1)));
  return hn::Add(a, hn::Mul(t, hn::Sub(b, a)));
}

// TilingModel::inverse_at_level in every lane, each at its own level.
void inverse_at_level(DF df, const SimdTiling& m, const VF* g, VI level, VF* out) {
  const DI di;
  const VI tables = hn::Mul(level, hn::Set(di, m.table_floats));
  for (const TableGroup& group : m.groups) {
    const VF* gg = g + group.first;
    VF* o = out + group.first;
    if (group.transform == GroupTransform::lut) {
      const int n = m.lut_size;
      VI cell[3];
      VF t[3];
      for (int c = 0; c < 3; ++c) t[c] = table_coordinate(df, gg[c], n, cell[c]);
      const std::int32_t step_y = n * 3;
      const std::int32_t step_z = step_y * n;
      const VI base = hn::Add(hn::Add(hn::Add(hn::Mul(level, hn::Set(di, m.lut_floats)),
                                              hn::Mul(cell[2], hn::Set(di, step_z))),
                                      hn::Mul(cell[1], hn::Set(di, step_y))),
                              hn::Mul(cell[0], hn::Set(di, 3)));
      const auto at = [&](VI p, std::int32_t offset) {
        return hn::GatherIndex(df, m.luts, hn::Add(p, hn::Set(di, offset)));
      };
      for (int c = 0; c < 3; ++c) {
        const VI p = hn::Add(base, hn::Set(di, c));
        const auto lerp = [&](VF a, VF b, VF f) { return hn::Add(a, hn::Mul(f, hn::Sub(b, a))); };
        const VF x00 = lerp(at(p, 0), at(p, 3), t[0]);
        const VF x10 = lerp(at(p, step_y), at(p, step_y + 3), t[0]);
        const VF x01 = lerp(at(p, step_z), at(p, step_z + 3), t[0]);
        const VF x11 = lerp(at(p, step_z + step_y), at(p, step_z + step_y + 3), t[0]);
        const VF y0 = lerp(x00, x10, t[1]);
        const VF y1 = lerp(x01, x11, t[1]);
        o[c] = lerp(y0, y1, t[2]);
      }
    } else if (group.transform == GroupTransform::decorrelated) {
      const int cc = group.channels;
      const float* basis = m.colour_basis + group.first_basis;
      const float* mean = m.colour_mean + group.first_mean;
      VF decorrelated[kMaxChannels];
      for (int c = 0; c < cc; ++c)
        decorrelated[c] = table_lookup(
            df, m.tables, hn::Add(tables, hn::Set(di, (group.first_table + c) * m.table_size)),
            m.table_size, gg[c]);
      for (int c = 0; c < cc; ++c) {
        VF value = hn::Set(df, mean[c]);
        for (int k = 0; k < cc; ++k)
          value = hn::Add(value, hn::Mul(hn::Set(df, basis[c * cc + k]), decorrelated[k]));
        o[c] = value;
      }
    } else {
      o[0] =
          table_lookup(df, m.tables, hn::Add(tables, hn::Set(di, group.first_table * m.table_size)),
                       m.table_size, gg[0]);
    }
  }
}

// One pyramid level per lane (TilingModel::level).
struct LevelLanes {
  VF texels_per_pixel_x, texels_per_pixel_y, width_f, height_f;
  VI width, height, first;
};

LevelLanes level_lanes(DF df, const SimdTiling& m, VI level, bool uniform) {
  const DI di;
  LevelLanes l;
  if (uniform) {
    const auto i = static_cast<std::size_t>(hn::GetLane(level));
    l.texels_per_pixel_x = hn::Set(df, m.texels_per_pixel_x[i]);
    l.texels_per_pixel_y = hn::Set(df, m.texels_per_pixel_y[i]);
    l.width = hn::Set(di, m.level_width[i]);
    l.height = hn::Set(di, m.level_height[i]);
    l.first = hn::Set(di, m.level_first[i]);
  } else {
    l.texels_per_pixel_x = hn::GatherIndex(df, m.texels_per_pixel_x.data(), level);
    l.texels_per_pixel_y = hn::GatherIndex(df, m.texels_per_pixel_y.data(), level);
    l.width = hn::GatherIndex(di, m.level_width.data(), level);
    l.height = hn::GatherIndex(di, m.level_height.data(), level);
    l.first = hn::GatherIndex(di, m.level_first.data(), level);
  }
  l.width_f = hn::ConvertTo(df, l.width);
  l.height_f = hn::ConvertTo(df, l.height);
  return l;
}

// fetch_bilinear (evaluate.hpp) in every lane: acc[c] += weight * level(x, y)[c] where `take`.
HWY_INLINE void fetch_bilinear(DF df, const SimdTiling& m, const LevelLanes& l, VF x, VF y,
                               VF weight, MF take, VF* acc) {
  const DI di;
  const VF one = hn::Set(df, 1.0f);
  const VF half = hn::Set(df, 0.5f);
  const VF u = hn::Sub(hn::Mul(x, l.texels_per_pixel_x), half);
  const VF v = hn::Sub(hn::Mul(y, l.texels_per_pixel_y), half);
  const VF cell_u = hn::Floor(u);
  const VF cell_v = hn::Floor(v);
  const VF tu = hn::Sub(u, cell_u);
  const VF tv = hn::Sub(v, cell_v);
  VI x0 =
      hn::ConvertTo(di, hn::Sub(cell_u, hn::Mul(l.width_f, hn::Floor(hn::Div(cell_u, l.width_f)))));
  VI y0 = hn::ConvertTo(
      di, hn::Sub(cell_v, hn::Mul(l.height_f, hn::Floor(hn::Div(cell_v, l.height_f)))));
  x0 = hn::IfThenElse(hn::Lt(x0, l.width), x0, hn::Sub(x0, l.width));
  y0 = hn::IfThenElse(hn::Lt(y0, l.height), y0, hn::Sub(y0, l.height));
  x0 = hn::IfThenElse(hn::Lt(x0, hn::Zero(di)), hn::Add(x0, l.width), x0);
  y0 = hn::IfThenElse(hn::Lt(y0, hn::Zero(di)), hn::Add(y0, l.height), y0);
  const VI one_i = hn::Set(di, 1);
  const VI x1 = hn::IfThenZeroElse(hn::Eq(hn::Add(x0, one_i), l.width), hn::Add(x0, one_i));
  const VI y1 = hn::IfThenZeroElse(hn::Eq(hn::Add(y0, one_i), l.height), hn::Add(y0, one_i));
  const VF w00 = hn::Mul(hn::Mul(weight, hn::Sub(one, tu)), hn::Sub(one, tv));
  const VF w10 = hn::Mul(hn::Mul(weight, tu), hn::Sub(one, tv));
  const VF w01 = hn::Mul(hn::Mul(weight, hn::Sub(one, tu)), tv);
  const VF w11 = hn::Mul(hn::Mul(weight, tu), tv);
  const VI channels = hn::Set(di, m.channels);
  const VI row = hn::Mul(l.width, channels);
  const VI r0 = hn::Add(l.first, hn::Mul(y0, row));
  const VI r1 = hn::Add(l.first, hn::Mul(y1, row));
  const VI i00 = hn::Add(r0, hn::Mul(x0, channels));
  const VI i10 = hn::Add(r0, hn::Mul(x1, channels));
  const VI i01 = hn::Add(r1, hn::Mul(x0, channels));
  const VI i11 = hn::Add(r1, hn::Mul(x1, channels));
  for (int c = 0; c < m.channels; ++c) {
    const VI k = hn::Set(di, c);
    const VF sum =
        hn::Add(hn::Add(hn::Add(hn::Mul(w00, hn::GatherIndex(df, m.pyramid, hn::Add(i00, k))),
                                hn::Mul(w10, hn::GatherIndex(df, m.pyramid, hn::Add(i10, k)))),
                        hn::Mul(w01, hn::GatherIndex(df, m.pyramid, hn::Add(i01, k)))),
                hn::Mul(w11, hn::GatherIndex(df, m.pyramid, hn::Add(i11, k))));
    acc[c] = hn::IfThenElse(take, hn::Add(acc[c], sum), acc[c]);
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
  for (std::size_t i = 0; i < lanes; i += hn::Lanes(dd)) {
    const VD x = hn::Load(dd, px + i);
    const VD y = hn::Load(dd, py + i);
    const VD skewed_x = hn::Div(hn::Sub(x, hn::Mul(y, hn::Set(dd, kInverseSqrt3))), edge);
    const VD skewed_y = hn::Div(hn::Mul(hn::Set(dd, 2.0 * kInverseSqrt3), y), edge);
    const VD cell_x = hn::Floor(skewed_x);
    const VD cell_y = hn::Floor(skewed_y);
    hn::StoreU(hn::DemoteTo(dfh, hn::Sub(skewed_x, cell_x)), dfh, out.fraction_x + i);
    hn::StoreU(hn::DemoteTo(dfh, hn::Sub(skewed_y, cell_y)), dfh, out.fraction_y + i);
    hn::StoreU(low_bits(dd, cell_x), dih, out.cell_x + i);
    hn::StoreU(low_bits(dd, cell_y), dih, out.cell_y + i);
    hn::StoreU(hn::DemoteTo(dfh, hn::Sub(x, hn::Mul(width, hn::Floor(hn::Div(x, width))))), dfh,
               out.wrapped_x + i);
    hn::StoreU(hn::DemoteTo(dfh, hn::Sub(y, hn::Mul(height, hn::Floor(hn::Div(y, height))))), dfh,
               out.wrapped_y + i);
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
  const VF one = hn::Set(df, 1.0f);
  const VF fx = hn::Load(df, lattice.fraction_x);
  const VF fy = hn::Load(df, lattice.fraction_y);
  const MF lower = hn::Lt(hn::Add(fx, fy), one);
  const VF weight[3] = {
      hn::IfThenElse(lower, hn::Sub(hn::Sub(one, fx), fy), hn::Sub(hn::Add(fx, fy), one)),
      hn::IfThenElse(lower, fx, hn::Sub(one, fx)), hn::IfThenElse(lower, fy, hn::Sub(one, fy))};
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
        scale_draw(du, pcg_hash(du, hn::Xor(key, draw_0)), static_cast<std::uint32_t>(m.width));
    const VU offset_y =
        scale_draw(du, pcg_hash(du, hn::Xor(key, draw_1)), static_cast<std::uint32_t>(m.height));
    const VF x = hn::Add(wrapped_x, hn::ConvertTo(df, hn::BitCast(di, offset_x)));
    const VF y = hn::Add(wrapped_y, hn::ConvertTo(df, hn::BitCast(di, offset_y)));
    fetch_bilinear(df, m, fine, x, y, hn::Mul(w, hn::Sub(one, blend)), all, acc);
    if (any_blend) fetch_bilinear(df, m, coarse, x, y, hn::Mul(w, blend), blended, acc);
  }
  // Eq. (8)/(13) of Heitz & Neyret 2018: (sum w G - E[G]) / sqrt(sum w^2) + E[G]; eq. (3) for
  // the linear blend.
  const VF inverse_norm = m.linear ? one : hn::Div(one, hn::Sqrt(weight_squares));
  VF g[kMaxChannels];
  for (int c = 0; c < m.channels; ++c) {
    const VF mean = hn::Set(df, m.blend_mean[c]);
    g[c] = hn::Add(hn::Mul(hn::Sub(acc[c], mean), inverse_norm), mean);
  }

  VF value[kMaxChannels];
  if (m.inverse) {
    inverse_at_level(df, m, g, level, value);
    if (any_blend) {
      VF coarse_value[kMaxChannels];
      inverse_at_level(df, m, g, coarse_level, coarse_value);
      for (int c = 0; c < m.channels; ++c)
        value[c] = hn::IfThenElse(
            blended, hn::Add(value[c], hn::Mul(blend, hn::Sub(coarse_value[c], value[c]))),
            value[c]);
    }
  } else {
    for (int c = 0; c < m.channels; ++c) value[c] = g[c];
  }

  HWY_ALIGN float result[kMaxChannels][kMaxLanes];
  for (int c = 0; c < m.channels; ++c) hn::Store(value[c], df, result[c]);
  const auto width = static_cast<std::size_t>(out.width);
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

}  // namespace stochtex::tiling
#endif  // HWY_ONCE
