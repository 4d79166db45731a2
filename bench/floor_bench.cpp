// The machine's floor under the CPU evaluators (issue 39, docs/performance.md, "The machine's
// floor"): each row renders a 128² grid of a default-parameter model of the 256² colour crop
// through `render` (one thread, the best CPU target) and, in the same run, a floor program that
// does only the operator's irreducible work on tables of the same sizes, and prints both per
// sample and their ratio. The floor keeps the memory reads and drops what the evaluator adds for
// its contract (docs/design.md §4: the scalar reference's bytes on every target): it computes in
// float with fused multiply-adds, skips the double-precision lattice and erf, hashes a vertex's
// offset with two multiplies, and has power-of-two exemplar sides (a wrap is a mask). Per sample:
//   tiling (histogram blend)  3 vertices x (offset hash + a bilinear RGB read: 12 gathers, or 4
//                             de-interleaving vector loads where the lanes read neighbouring
//                             texels of one row, as the evaluator does), the
//                             variance-preserving blend, T^-1: float erf of 3 channels and
//                             - sliced: the trilinear 32³ RGB table (24 gathers),
//                             - pca: three 1-D tables of 1024 (6 gathers) and the 3x3 basis;
//   tiling blend=variance     the reads and the blend, no T^-1;
//   texton (MNI 30)           every impulse of the cells around a row of lanes: a hashed
//                             position, a reach test and a bilinear RGB read of the texton
//                             (contiguous loads where the lanes read neighbouring texels);
// zoomed out (zoom 8), the reads and T^-1 of two pyramid levels, blended, at the level of detail
// the evaluators use (core/level_of_detail.hpp).

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bench/floor_bench.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#ifndef STOCHTEX_FLOOR_BENCH_SHARED
#define STOCHTEX_FLOOR_BENCH_SHARED
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace stochtex::bench_floor {

constexpr int kSide = 128;          // the rendered grid
constexpr int kExemplarSide = 256;  // the exemplar crop (a power of two)
constexpr int kLevels = 9;          // 256 .. 1
constexpr int kLutSize = 32;
constexpr int kTableSize = 1024;
constexpr float kMni = 30.0f;

// A pyramid of `channels` values per texel, interleaved (tiling) or one plane per channel
// (texton), levels one after the other.
struct Pyramid {
  std::vector<float> texels;
  std::array<std::int32_t, kLevels> first{};
  std::array<std::int32_t, kLevels> side{};
};

inline Pyramid make_pyramid(int channels) {
  Pyramid p;
  std::size_t total = 0;
  for (int l = 0; l < kLevels; ++l) {
    p.side[l] = kExemplarSide >> l;
    p.first[l] = static_cast<std::int32_t>(total);
    total += static_cast<std::size_t>(p.side[l]) * p.side[l] * channels;
  }
  p.texels.resize(total + 64);  // vector loads past a level's last texel stay inside
  std::uint32_t state = 12345u;
  for (float& t : p.texels) {
    state = state * 1664525u + 1013904223u;
    t = static_cast<float>(state >> 8) * (1.0f / 16777216.0f);
  }
  return p;
}

struct TilingData {
  Pyramid gaussian = make_pyramid(3);
  std::vector<float> lut;     // kLevels x 32³ x RGB
  std::vector<float> tables;  // kLevels x 3 x kTableSize
  std::array<float, 9> basis{0.58f, 0.58f, 0.58f, 0.71f, -0.71f, 0.0f, 0.41f, 0.41f, -0.82f};
  float edge = 64.0f;
  TilingData() {
    lut.resize(std::size_t{kLevels} * kLutSize * kLutSize * kLutSize * 3);
    tables.resize(std::size_t{kLevels} * 3 * kTableSize);
    for (std::size_t i = 0; i < lut.size(); ++i) lut[i] = static_cast<float>(i % 97) / 97.0f;
    for (std::size_t i = 0; i < tables.size(); ++i)
      tables[i] = static_cast<float>(i % kTableSize) / kTableSize;
  }
};

enum class Inverse { sliced, pca, none };

}  // namespace stochtex::bench_floor
#endif  // STOCHTEX_FLOOR_BENCH_SHARED

HWY_BEFORE_NAMESPACE();
namespace stochtex::bench_floor::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using DU = hn::RebindToUnsigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using VU = hn::Vec<DU>;

// The level of detail of a grid of spacing `scale` (log2 of the footprint less kLodBias).
inline void level_of(float scale, int& level, float& blend) {
  const float lod = std::log2(scale) - 0.79248125f;
  level = lod <= 0.0f ? 0 : std::min(static_cast<int>(lod), kLevels - 2);
  blend = lod <= 0.0f ? 0.0f : lod - static_cast<float>(level);
}

HWY_INLINE VU hash(VU x, VU y, std::uint32_t seed) {
  const DU du;
  VU h = hn::Mul(hn::Xor(x, hn::Set(du, seed)), hn::Set(du, 0x9E3779B1u));
  h = hn::Mul(hn::Xor(h, hn::Add(y, hn::ShiftRight<15>(h))), hn::Set(du, 0x85EBCA77u));
  return hn::Xor(h, hn::ShiftRight<13>(h));
}

// acc += weight * the bilinear RGB read of level `level` at exemplar pixel (x, y), wrapped.
HWY_INLINE void bilinear_rgb(const Pyramid& p, int level, VF x, VF y, VF weight, VF* acc) {
  const DF df;
  const DI di;
  const float texels_per_pixel = 1.0f / static_cast<float>(1 << level);
  const VF u = hn::MulSub(x, hn::Set(df, texels_per_pixel), hn::Set(df, 0.5f));
  const VF v = hn::MulSub(y, hn::Set(df, texels_per_pixel), hn::Set(df, 0.5f));
  const VF u0 = hn::Floor(u);
  const VF v0 = hn::Floor(v);
  const VF fu = hn::Sub(u, u0);
  const VF fv = hn::Sub(v, v0);
  const VI mask = hn::Set(di, p.side[level] - 1);
  const VI x0 = hn::And(hn::ConvertTo(di, u0), mask);
  const VI y0 = hn::And(hn::ConvertTo(di, v0), mask);
  const VI x1 = hn::And(hn::Add(x0, hn::Set(di, 1)), mask);
  const VI y1 = hn::And(hn::Add(y0, hn::Set(di, 1)), mask);
  const VI row = hn::Set(di, p.side[level] * 3);
  const VI first = hn::Set(di, p.first[level]);
  const VI r0 = hn::Add(hn::Mul(y0, row), first);
  const VI r1 = hn::Add(hn::Mul(y1, row), first);
  const VI c0 = hn::Mul(x0, hn::Set(di, 3));
  const VI c1 = hn::Mul(x1, hn::Set(di, 3));
  const float* base = p.texels.data();
  // Lanes on neighbouring texels of one row pair (a patch's row at scale 1): vector loads.
  const std::int32_t first_x = hn::GetLane(x0);
  if (hn::AllTrue(di, hn::Eq(x0, hn::Iota(di, first_x))) &&
      hn::AllTrue(di, hn::Eq(x1, hn::Iota(di, first_x + 1))) &&
      hn::AllTrue(di, hn::Eq(y0, hn::Set(di, hn::GetLane(y0))))) {
    VF t[4][3];
    const float* top = base + hn::GetLane(r0) + first_x * 3;
    const float* bottom = base + hn::GetLane(r1) + first_x * 3;
    hn::LoadInterleaved3(df, top, t[0][0], t[0][1], t[0][2]);
    hn::LoadInterleaved3(df, top + 3, t[1][0], t[1][1], t[1][2]);
    hn::LoadInterleaved3(df, bottom, t[2][0], t[2][1], t[2][2]);
    hn::LoadInterleaved3(df, bottom + 3, t[3][0], t[3][1], t[3][2]);
    for (int c = 0; c < 3; ++c) {
      const VF upper = hn::MulAdd(fu, hn::Sub(t[1][c], t[0][c]), t[0][c]);
      const VF lower = hn::MulAdd(fu, hn::Sub(t[3][c], t[2][c]), t[2][c]);
      acc[c] = hn::MulAdd(weight, hn::MulAdd(fv, hn::Sub(lower, upper), upper), acc[c]);
    }
    return;
  }
  for (int c = 0; c < 3; ++c) {
    const VI k = hn::Set(di, c);
    const VF a = hn::GatherIndex(df, base, hn::Add(hn::Add(r0, c0), k));
    const VF b = hn::GatherIndex(df, base, hn::Add(hn::Add(r0, c1), k));
    const VF d = hn::GatherIndex(df, base, hn::Add(hn::Add(r1, c0), k));
    const VF e = hn::GatherIndex(df, base, hn::Add(hn::Add(r1, c1), k));
    const VF top = hn::MulAdd(fu, hn::Sub(b, a), a);
    const VF bottom = hn::MulAdd(fu, hn::Sub(e, d), d);
    acc[c] = hn::MulAdd(weight, hn::MulAdd(fv, hn::Sub(bottom, top), top), acc[c]);
  }
}

// A float erf (Abramowitz and Stegun 7.1.28 form, |error| < 3e-7 after the square).
HWY_INLINE VF erf_float(VF x) {
  const DF df;
  const VF a = hn::Abs(x);
  VF p = hn::Set(df, 0.0000430638f);
  p = hn::MulAdd(p, a, hn::Set(df, 0.0002765672f));
  p = hn::MulAdd(p, a, hn::Set(df, 0.0001520143f));
  p = hn::MulAdd(p, a, hn::Set(df, 0.0092705272f));
  p = hn::MulAdd(p, a, hn::Set(df, 0.0422820123f));
  p = hn::MulAdd(p, a, hn::Set(df, 0.0705230784f));
  p = hn::MulAdd(p, a, hn::Set(df, 1.0f));
  p = hn::Mul(p, p);
  p = hn::Mul(p, p);
  p = hn::Mul(p, p);
  p = hn::Mul(p, p);
  return hn::CopySign(hn::Sub(hn::Set(df, 1.0f), hn::Div(hn::Set(df, 1.0f), p)), x);
}

// The table coordinate of Gaussian g in a table of `size` cells: its first cell and the fraction.
HWY_INLINE VF table_coordinate(VF g, int size, VI& cell) {
  const DF df;
  const DI di;
  const VF u = hn::MulAdd(erf_float(hn::Mul(hn::Sub(g, hn::Set(df, 0.5f)), hn::Set(df, 4.24f))),
                          hn::Set(df, 0.5f), hn::Set(df, 0.5f));
  const VF x =
      hn::Min(hn::Max(hn::MulSub(u, hn::Set(df, static_cast<float>(size)), hn::Set(df, 0.5f)),
                      hn::Zero(df)),
              hn::Set(df, static_cast<float>(size - 1)));
  cell = hn::Min(hn::ConvertTo(di, x), hn::Set(di, size - 2));
  return hn::Sub(x, hn::ConvertTo(df, cell));
}

HWY_INLINE VF lerp(VF a, VF b, VF t) {
  return hn::MulAdd(t, hn::Sub(b, a), a);
}

// T^-1 of level `level` at the Gaussian colour g, into out.
HWY_INLINE void inverse(const TilingData& d, Inverse kind, int level, const VF* g, VF* out) {
  const DF df;
  const DI di;
  if (kind == Inverse::sliced) {
    VI cell[3];
    VF t[3];
    for (int c = 0; c < 3; ++c) t[c] = table_coordinate(g[c], kLutSize, cell[c]);
    constexpr int kStepY = kLutSize * 3;
    constexpr int kStepZ = kStepY * kLutSize;
    const float* lut =
        d.lut.data() + std::size_t{static_cast<std::size_t>(level)} * kStepZ * kLutSize;
    const VI corner = hn::Add(
        hn::Add(hn::Mul(cell[2], hn::Set(di, kStepZ)), hn::Mul(cell[1], hn::Set(di, kStepY))),
        hn::Mul(cell[0], hn::Set(di, 3)));
    for (int c = 0; c < 3; ++c) {
      const VI p = hn::Add(corner, hn::Set(di, c));
      const auto at = [&](int offset) HWY_ATTR {
        return hn::GatherIndex(df, lut, hn::Add(p, hn::Set(di, offset)));
      };
      const VF x00 = lerp(at(0), at(3), t[0]);
      const VF x10 = lerp(at(kStepY), at(kStepY + 3), t[0]);
      const VF x01 = lerp(at(kStepZ), at(kStepZ + 3), t[0]);
      const VF x11 = lerp(at(kStepZ + kStepY), at(kStepZ + kStepY + 3), t[0]);
      out[c] = lerp(lerp(x00, x10, t[1]), lerp(x01, x11, t[1]), t[2]);
    }
    return;
  }
  VF decorrelated[3];
  for (int c = 0; c < 3; ++c) {
    VI cell;
    const VF t = table_coordinate(g[c], kTableSize, cell);
    const float* table =
        d.tables.data() + (std::size_t{static_cast<std::size_t>(level)} * 3 + c) * kTableSize;
    decorrelated[c] = lerp(hn::GatherIndex(df, table, cell),
                           hn::GatherIndex(df, table, hn::Add(cell, hn::Set(di, 1))), t);
  }
  for (int c = 0; c < 3; ++c) {
    VF v = hn::Set(df, 0.5f);
    for (int k = 0; k < 3; ++k) v = hn::MulAdd(hn::Set(df, d.basis[k * 3 + c]), decorrelated[k], v);
    out[c] = v;
  }
}

void TilingFloor(const TilingData& d, Inverse kind, float scale, float* out) {
  const DF df;
  const DI di;
  const DU du;
  const int lanes = static_cast<int>(hn::Lanes(df));
  int level = 0;
  float blend = 0.0f;
  level_of(scale, level, blend);
  const int levels = blend > 0.0f ? 2 : 1;
  const VF iota = hn::Iota(df, 0.5f);
  const float inverse_edge = 1.0f / d.edge;
  const std::size_t plane = std::size_t{kSide} * kSide;
  for (int row = 0; row < kSide; ++row) {
    const float y = (static_cast<float>(row) + 0.5f) * scale;
    const VF py = hn::Set(df, y);
    for (int column = 0; column < kSide; column += lanes) {
      const VF px =
          hn::Mul(hn::Add(iota, hn::Set(df, static_cast<float>(column))), hn::Set(df, scale));
      // The triangle lattice: skewed coordinates, the cell, the barycentric weights.
      const VF sx =
          hn::Mul(hn::MulAdd(py, hn::Set(df, -0.57735027f), px), hn::Set(df, inverse_edge));
      const VF sy = hn::Set(df, 1.15470054f * y * inverse_edge);
      const VF cx = hn::Floor(sx);
      const VF cy = hn::Floor(sy);
      const VF fx = hn::Sub(sx, cx);
      const VF fy = hn::Sub(sy, cy);
      const VF one = hn::Set(df, 1.0f);
      const auto lower = hn::Lt(hn::Add(fx, fy), one);
      const VF weight[3] = {
          hn::IfThenElse(lower, hn::Sub(hn::Sub(one, fx), fy), hn::Sub(hn::Add(fx, fy), one)),
          hn::IfThenElse(lower, fx, hn::Sub(one, fx)), hn::IfThenElse(lower, fy, hn::Sub(one, fy))};
      const VU bx = hn::BitCast(du, hn::ConvertTo(di, cx));
      const VU by = hn::BitCast(du, hn::ConvertTo(di, cy));
      const VU up = hn::IfThenZeroElse(hn::RebindMask(du, lower), hn::Set(du, 1u));
      const VU down = hn::Sub(hn::Set(du, 1u), up);
      const VU vx[3] = {hn::Add(bx, up), hn::Add(bx, down), hn::Add(bx, up)};
      const VU vy[3] = {hn::Add(by, up), hn::Add(by, up), hn::Add(by, down)};
      VF acc[2][3];
      for (auto& a : acc)
        for (VF& v : a) v = hn::Zero(df);
      VF squares = hn::Zero(df);
      for (int v = 0; v < 3; ++v) {
        squares = hn::MulAdd(weight[v], weight[v], squares);
        const VU h = hash(vx[v], vy[v], 7u);
        const VI mask = hn::Set(di, kExemplarSide - 1);
        const VF ox = hn::ConvertTo(df, hn::And(hn::BitCast(di, h), mask));
        const VF oy = hn::ConvertTo(df, hn::And(hn::BitCast(di, hn::ShiftRight<16>(h)), mask));
        for (int l = 0; l < levels; ++l)
          bilinear_rgb(d.gaussian, level + l, hn::Add(px, ox), hn::Add(py, oy), weight[v], acc[l]);
      }
      const VF factor = hn::ApproximateReciprocalSqrt(squares);
      VF value[2][3];
      for (int l = 0; l < levels; ++l) {
        VF g[3];
        for (int c = 0; c < 3; ++c)
          g[c] = hn::MulAdd(hn::Sub(acc[l][c], hn::Set(df, 0.5f)), factor, hn::Set(df, 0.5f));
        if (kind == Inverse::none)
          for (int c = 0; c < 3; ++c) value[l][c] = g[c];
        else
          inverse(d, kind, level + l, g, value[l]);
      }
      const std::size_t at = static_cast<std::size_t>(row) * kSide + column;
      for (int c = 0; c < 3; ++c) {
        const VF v = levels == 2 ? lerp(value[0][c], value[1][c], hn::Set(df, blend)) : value[0][c];
        hn::StoreU(v, df, out + c * plane + at);
      }
    }
  }
}

// Texton noise's splats: impulses in cells of the texton's side, kMni per cell, each adding a
// bilinear read of the texton (planes per channel) at the lanes in its reach.
void TextonFloor(const Pyramid& texton, float scale, float* out) {
  const DF df;
  const DI di;
  const int lanes = static_cast<int>(hn::Lanes(df));
  int level = 0;
  float blend = 0.0f;
  level_of(scale, level, blend);
  const int levels = blend > 0.0f ? 2 : 1;
  const float support = static_cast<float>(kExemplarSide);
  const int points = static_cast<int>(kMni);
  const VF iota = hn::Iota(df, 0.5f);
  const std::size_t plane = std::size_t{kSide} * kSide;
  for (int row = 0; row < kSide; ++row) {
    const float y = (static_cast<float>(row) + 0.5f) * scale;
    for (int column = 0; column < kSide; column += lanes) {
      const VF px =
          hn::Mul(hn::Add(iota, hn::Set(df, static_cast<float>(column))), hn::Set(df, scale));
      const float x_first = (static_cast<float>(column) + 0.5f) * scale;
      const float x_last = x_first + static_cast<float>(lanes - 1) * scale;
      VF acc[2][3];
      for (auto& a : acc)
        for (VF& v : a) v = hn::Zero(df);
      const int cell_y0 = static_cast<int>(std::floor((y - support) / support));
      const int cell_y1 = static_cast<int>(std::floor(y / support));
      const int cell_x0 = static_cast<int>(std::floor((x_first - support) / support));
      const int cell_x1 = static_cast<int>(std::floor(x_last / support));
      for (int cy = cell_y0; cy <= cell_y1; ++cy)
        for (int cx = cell_x0; cx <= cell_x1; ++cx)
          for (int k = 0; k < points; ++k) {
            std::uint32_t h = (static_cast<std::uint32_t>(cx) * 0x9E3779B1u) ^
                              (static_cast<std::uint32_t>(cy) * 0x85EBCA77u) ^
                              (static_cast<std::uint32_t>(k) * 0xC2B2AE3Du);
            h ^= h >> 15;
            h *= 0x2C1B3C6Du;
            const float point_x =
                (static_cast<float>(cx) + static_cast<float>(h & 0xffffu) / 65536.0f) * support;
            const float point_y =
                (static_cast<float>(cy) + static_cast<float>(h >> 16) / 65536.0f) * support;
            const float dy = y - point_y;
            if (dy < 0.0f || dy >= support - 1.0f) continue;
            if (x_last < point_x || x_first - point_x >= support - 1.0f) continue;
            const float sign = (h & 1u) != 0u ? 1.0f : -1.0f;
            const VF dx = hn::Sub(px, hn::Set(df, point_x));
            const auto inside =
                hn::And(hn::Ge(dx, hn::Zero(df)), hn::Lt(dx, hn::Set(df, support - 1.0f)));
            const VF w = hn::IfThenElseZero(inside, hn::Set(df, sign));
            for (int l = 0; l < levels; ++l) {
              const int lv = level + l;
              const float texels_per_pixel = 1.0f / static_cast<float>(1 << lv);
              const int side = texton.side[lv];
              const float v = std::max(dy * texels_per_pixel - 0.5f, 0.0f);
              const int v0 = std::min(static_cast<int>(v), side - 2);
              const float fv = v - static_cast<float>(v0);
              const float* planes = texton.texels.data() + texton.first[lv];
              const std::size_t channel_plane = static_cast<std::size_t>(side) * side;
              const VF u = hn::Max(hn::MulSub(dx, hn::Set(df, texels_per_pixel), hn::Set(df, 0.5f)),
                                   hn::Zero(df));
              const VI u0 = hn::Min(hn::ConvertTo(di, u), hn::Set(di, side - 2));
              const VF fu = hn::Sub(u, hn::ConvertTo(df, u0));
              // Lanes one or two texels apart read contiguous texels: vector loads (the second
              // case de-interleaved) replace the gathers.
              const float step = scale * texels_per_pixel;
              const int first = hn::GetLane(u0);
              for (int c = 0; c < 3; ++c) {
                const float* r0 = planes + c * channel_plane + static_cast<std::size_t>(v0) * side;
                const float* r1 = r0 + side;
                VF a, b, e, f;
                if (step == 1.0f) {
                  a = hn::LoadU(df, r0 + first);
                  b = hn::LoadU(df, r0 + first + 1);
                  e = hn::LoadU(df, r1 + first);
                  f = hn::LoadU(df, r1 + first + 1);
                }
#if HWY_TARGET != HWY_SCALAR  // one lane: a step is always 1
                else if (step == 2.0f) {
                  const std::size_t n = hn::Lanes(df);
                  const auto even = [&](const float* at) HWY_ATTR {
                    return hn::ConcatEven(df, hn::LoadU(df, at + n), hn::LoadU(df, at));
                  };
                  a = even(r0 + first);
                  b = even(r0 + first + 1);
                  e = even(r1 + first);
                  f = even(r1 + first + 1);
                }
#endif
                else {
                  const VI next = hn::Add(u0, hn::Set(di, 1));
                  a = hn::GatherIndex(df, r0, u0);
                  b = hn::GatherIndex(df, r0, next);
                  e = hn::GatherIndex(df, r1, u0);
                  f = hn::GatherIndex(df, r1, next);
                }
                const VF top = lerp(a, b, fu);
                const VF bottom = lerp(e, f, fu);
                acc[l][c] = hn::MulAdd(w, lerp(top, bottom, hn::Set(df, fv)), acc[l][c]);
              }
            }
          }
      const std::size_t at = static_cast<std::size_t>(row) * kSide + column;
      const VF normalise = hn::Set(df, 1.0f / std::sqrt(kMni));
      for (int c = 0; c < 3; ++c) {
        const VF v = levels == 2 ? lerp(acc[0][c], acc[1][c], hn::Set(df, blend)) : acc[0][c];
        hn::StoreU(hn::MulAdd(v, normalise, hn::Set(df, 0.5f)), df, out + c * plane + at);
      }
    }
  }
}

}  // namespace stochtex::bench_floor::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <benchmark/benchmark.h>

#include <ctime>
#include <exception>
#include <string>

#include "bench_support.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::bench_floor {
namespace {

HWY_EXPORT(TilingFloor);
HWY_EXPORT(TextonFloor);

using namespace stochtex::bench;

// The evaluators the floor measures: the model's method and parameters, and the floor's kernel.
struct Row {
  const char* name;
  const char* method;
  ParamValues params;
  bool texton;
  Inverse inverse;
};

const Row kRows[] = {
    {"tiling_sliced", "tiling", {{"transport", 0}}, false, Inverse::sliced},
    {"tiling_pca", "tiling", {{"transport", 1}}, false, Inverse::pca},
    {"tiling_variance", "tiling", {{"blend", 1}}, false, Inverse::none},
    {"texton", "texton", {}, true, Inverse::none},
};

// This thread's CPU time in nanoseconds: the evaluator (one thread: `render` works on the
// calling thread) and the floor are timed alike, and the time the machine gives other processes
// does not count (wall-clock ratios on the shared 2-core machine varied by a third).
double thread_ns() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) * 1e9 + static_cast<double>(now.tv_nsec);
}

// Nanoseconds of CPU time per sample of body() over at least 0.2 s.
template <typename Body>
double ns_per_sample(Body&& body) {
  const double start = thread_ns();
  std::int64_t runs = 0;
  double elapsed = 0.0;
  do {
    body();
    benchmark::ClobberMemory();
    ++runs;
    elapsed = thread_ns() - start;
  } while (elapsed < 2e8);
  return elapsed / static_cast<double>(runs * kSide * kSide);
}

// One row: the evaluator (`render`, one thread) and its floor alternate within each iteration,
// so a change in the machine's load weighs on both; counters evaluator_ns, floor_ns, ratio.
void floor_benchmark(benchmark::State& state, const Row& row) {
  const auto zoom = static_cast<float>(state.range(0));
  Model model;
  try {
    model =
        analyze(row.method, crop_top_left(colour_exemplar(), kExemplarSide).view(), row.params, 0);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  state.SetLabel(std::string(cpu_target_name(cpu_target())));
  static const TilingData tiling;
  static const Pyramid texton = make_pyramid(3);
  RenderOptions options;
  options.threads = 1;
  options.filter = zoom > 1.0f;
  const Grid grid{{0.0, 0.0}, zoom, kSide, kSide};
  ImageF image(kSide, kSide, model.channels());
  std::vector<float> floor_out(std::size_t{3} * kSide * kSide);
  double evaluator = 0.0;
  double floor = 0.0;
  for (auto _ : state) {
    evaluator += ns_per_sample([&] { render(model, grid, 7, image.view(), options); });
    floor += ns_per_sample([&] {
      if (row.texton)
        HWY_DYNAMIC_DISPATCH(TextonFloor)(texton, zoom, floor_out.data());
      else
        HWY_DYNAMIC_DISPATCH(TilingFloor)(tiling, row.inverse, zoom, floor_out.data());
    });
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["evaluator_ns"] = evaluator / n;
  state.counters["floor_ns"] = floor / n;
  state.counters["ratio"] = evaluator / floor;
}

[[maybe_unused]] const bool registered = [] {
  for (const Row& row : kRows)
    benchmark::RegisterBenchmark((std::string("BM_Floor/") + row.name).c_str(),
                                 [&row](benchmark::State& state) { floor_benchmark(state, row); })
        ->ArgNames({"zoom"})
        ->Arg(1)
        ->Arg(8)
        ->Iterations(3)
        ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
}  // namespace stochtex::bench_floor
#endif  // HWY_ONCE
