#pragma once
// The pieces of the tiling-and-blending evaluator (Algorithm 1 of the paper), written in the
// restricted subset of docs/design.md §4 (uint32/float, flat arrays, no allocation) so that they
// can be mirrored in GLSL. Lattice and fetch functions are public so tests and baselines (linear
// blending) use exactly the evaluator's geometry.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>

#include "core/hash.hpp"
#include "core/periodic.hpp"
#include "stochtex/model.hpp"

namespace stochtex::tiling {

// The Gaussian of eq. (20): mean 1/2 and standard deviation 1/6 per channel, so that the values fit
// in [0, 1] (section 4.2).
inline constexpr float kGaussianMean = 0.5f;
inline constexpr float kGaussianDeviation = 1.0f / 6.0f;
// Eq. (22)'s factor 1 / (sigma sqrt(2)) of the erf: Phi(g) = (1 + erf((g - mu) kErfScale)) / 2.
inline constexpr float kErfScale = 1.0f / (kGaussianDeviation * 1.41421356237f);
// The coefficients of erf_rational (below).
inline constexpr double kErfNumerator[] = {
    -2.72614225801306e-10, 2.77068142495902e-08,  -2.10102402082508e-06, -5.69250639462346e-05,
    -7.34990630326855e-04, -2.95459980854025e-03, -1.60960333262415e-02};
inline constexpr double kErfDenominator[] = {-1.45660718464996e-05, -2.13374055278905e-04,
                                             -1.68282697438203e-03, -7.37332916720468e-03,
                                             -1.42647390514189e-02};
inline constexpr double kErfClamp = 4.0;

// 1 / sqrt(3), of the triangle lattice's geometry (triangle_lattice below).
inline constexpr double kInverseSqrt3 = 0.57735026918962576;

// The arithmetic that the scalar reference and the vectorised evaluator (simd.cpp) share, source
// for source: the lattice and the wrap, the blend weights, the bilinear fetch, erf and the look-up
// tables.
#include "methods/tiling/kernel.inc"

// kernel.inc's operations on single values: the scalar reference.
struct ScalarOps {
  using F = float;
  using I = int;
  using D = double;
  static float f(float c) noexcept { return c; }
  static int i(int c) noexcept { return c; }
  static double d(double c) noexcept { return c; }
  static float floor(float v) noexcept { return std::floor(v); }
  static double floor(double v) noexcept { return std::floor(v); }
  static int to_int(float v) noexcept { return static_cast<int>(v); }
  static float to_float(int v) noexcept { return static_cast<float>(v); }
  template <typename T>
  static T select(bool condition, T a, T b) noexcept {
    return condition ? a : b;
  }
  static int add_where(bool condition, int x, int y) noexcept {
    if (condition) x += y;
    return x;
  }
  static int subtract_unless(bool condition, int x, int y) noexcept {
    if (!condition) x -= y;
    return x;
  }
  static float sqrt(float v) noexcept { return std::sqrt(v); }
  static float erf(float x) noexcept {
    return static_cast<float>(erf_ratio(ScalarOps{}, static_cast<double>(x)));
  }
  static float gather(const float* base, int index) noexcept { return base[index]; }
};

// The three vertices of the equilateral-triangle (simplex) lattice around a point and their
// blending weights (section 5.1, after Perlin 2001). Vertex (i, j) of the skewed lattice sits at
// edge * (i + j / 2, j * sqrt(3) / 2) in model space; its hexagonal tile is the six triangles
// around it and its weight is the barycentric coordinate, 1 on the vertex and 0 on the tile border.
struct LatticePoint {
  std::int64_t vertex_x[3];  // skewed lattice coordinates of the vertices (64-bit: p = 1e7 is fine)
  std::int64_t vertex_y[3];
  float weight[3];  // >= 0, sum to 1
  // The point minus vertex v in skewed lattice units (the tile's local position, for the patch
  // transform of the artist controls).
  float from_vertex_x[3];
  float from_vertex_y[3];
};

// p in skewed lattice units: vertex (i, j) at (i, j).
inline Vec2d skewed_position(Vec2d p, double edge) noexcept {
  Vec2d skewed;
  skew(ScalarOps{}, p.x, p.y, edge, skewed.x, skewed.y);
  return skewed;
}

inline LatticePoint triangle_lattice(Vec2d p, double edge) noexcept {
  // Skewed coordinates are formed in double and split into a 64-bit cell and a float fraction, so
  // the fraction (hence the weights) is as precise at p = 1e7 as at p = 0 (docs/design.md §4).
  const Vec2d skewed = skewed_position(p, edge);
  const double skewed_x = skewed.x;
  const double skewed_y = skewed.y;
  const double cell_x = std::floor(skewed_x);
  const double cell_y = std::floor(skewed_y);
  const auto base_x = static_cast<std::int64_t>(cell_x);
  const auto base_y = static_cast<std::int64_t>(cell_y);
  const auto fx = static_cast<float>(skewed_x - cell_x);
  const auto fy = static_cast<float>(skewed_y - cell_y);
  LatticePoint out;
  // Lower triangle (0,0) (1,0) (0,1) or upper triangle (1,1) (0,1) (1,0) of the skewed cell.
  const bool lower = triangle_weights(ScalarOps{}, fx, fy, out.weight);
  const int dx[3] = {lower ? 0 : 1, lower ? 1 : 0, lower ? 0 : 1};
  const int dy[3] = {lower ? 0 : 1, lower ? 0 : 1, lower ? 1 : 0};
  for (int v = 0; v < 3; ++v) {
    out.vertex_x[v] = base_x + dx[v];
    out.vertex_y[v] = base_y + dy[v];
    out.from_vertex_x[v] = fx - static_cast<float>(dx[v]);
    out.from_vertex_y[v] = fy - static_cast<float>(dy[v]);
  }
  return out;
}

struct Point2f {
  float x;
  float y;
};

// Burley 2019 ("On Histogram-Preserving Blending for Randomized Texture Tiling", JCGT 8(4)): the
// weights raised to `sharpness` and renormalised to sum 1; sharpness 1 leaves them as they are.
inline void sharpen_weights(float* weight, float sharpness) noexcept {
  if (sharpness == 1.0f) return;
  float sum = 0.0f;
  for (int v = 0; v < 3; ++v) {
    weight[v] = std::pow(weight[v], sharpness);
    sum += weight[v];
  }
  for (int v = 0; v < 3; ++v) weight[v] /= sum;
}

// The height-aware blend: the height blend of game engines (A. Mishkinis, "Advanced Terrain
// Texture Splatting", Gamasutra 2013), w_i' = max(h_i + w_i - max_j(h_j + w_j) + depth, 0)
// renormalised, with h_i the patch's height, in a smooth form: w_i' = w_i exp((h_i + w_i -
// max_j(h_j + w_j)) / depth) / sum_j (...), the max over the patches of weight > 0. The engine
// form gives a vertex of barycentric weight 0 a weight of its own when its patch is higher than
// the others by more than their weight - depth, so the blend would jump across the lattice's
// triangle edges (where that vertex changes); the factor w_i keeps w_i = 0 at 0, so the blend is
// continuous and a vertex shows its patch alone. As in the engine form, the patch of the highest
// h + w wins, over a transition about `depth` wide in h + w; a large depth tends to the
// barycentric weights. `depth` > 0.
inline void height_blend_weights(float* weight, const float* height, float depth) noexcept {
  float top = -std::numeric_limits<float>::infinity();
  for (int v = 0; v < 3; ++v)
    if (weight[v] > 0.0f) top = std::max(top, height[v] + weight[v]);
  float sum = 0.0f;
  for (int v = 0; v < 3; ++v) {
    // below <= 0 where the weight is > 0; the top patch's factor is 1 even for a tiny depth.
    const float below = height[v] + weight[v] - top;
    weight[v] =
        weight[v] > 0.0f ? weight[v] * (below < 0.0f ? std::exp(below / depth) : 1.0f) : 0.0f;
    sum += weight[v];
  }
  for (int v = 0; v < 3; ++v) weight[v] /= sum;
}

// The artist controls' transform of a vertex's patch: the point's position relative to the
// vertex (model space) is rotated by a random angle uniform in [-max_angle, +max_angle] radians
// and scaled by 2^(u jitter), u uniform in [-1, 1], both drawn from the vertex's own key in the
// stream `transforms` (so the offsets' draws do not change). The patch is read at
// offset + wrap(vertex) + M (p - vertex), M = scale * rotation: a rotation about the tile's
// centre; a footprint (dpdx, dpdy) becomes (M dpdx, M dpdy).
struct PatchTransform {
  float xx, xy, yx, yy;  // M, row-major
  float scale;
};

inline PatchTransform patch_transform(std::int64_t vertex_x, std::int64_t vertex_y,
                                      std::uint32_t seed, float max_angle, float jitter) noexcept {
  CounterRng rng(cell_key(vertex_x, vertex_y, seed, Stream::transforms));
  const float angle_draw = rng.uniform();
  const float scale_draw = rng.uniform();
  const float angle = max_angle * (2.0f * angle_draw - 1.0f);
  const float scale = std::exp2(jitter * (2.0f * scale_draw - 1.0f));
  const float c = scale * std::cos(angle);
  const float s = scale * std::sin(angle);
  return {c, -s, s, c, scale};
}

// The shift M (p - vertex) - (p - vertex) that moves a patch's fetch from its untransformed
// position to the transformed one, `local` = p - vertex in model space. Zero for the identity.
inline Point2f transform_shift(const PatchTransform& m, Point2f local) noexcept {
  return {(m.xx - 1.0f) * local.x + m.xy * local.y, m.yx * local.x + (m.yy - 1.0f) * local.y};
}

// transform_shift with p - vertex in skewed lattice units, `from_x`, `from_y` (LatticePoint),
// `edge` the lattice edge: the shift from wrap(p) + offset.
inline Point2f patch_shift(const PatchTransform& m, float from_x, float from_y,
                           float edge) noexcept {
  return transform_shift(m, {edge * (from_x + 0.5f * from_y),
                             edge * from_y * (1.5f * static_cast<float>(kInverseSqrt3))});
}

// The triangle lattice of a periodic field (core/periodic.hpp) of model-space period P: the
// lattice is periodic with (n edge, 0) and (0, m sqrt(3) edge) (vertex (i, j + 2m) is vertex
// (i - m, j) moved up by that period), so positions are stretched per axis by s = (n edge / P_x,
// m sqrt(3) edge / P_y), n and m rounded (a stretch within half a lattice period over the output),
// and each vertex is reduced into the period, (i mod n, j mod 2m) with i shifted by m per wrap of
// j: its random draws come from the reduced vertex. A patch is read at its offset plus p minus the
// vertex's position (rounded to whole pixels, as the offsets are, to keep the exemplar's texel
// grid), where the default evaluator reads wrap(p) + offset: the same patch up to a translation,
// and periodic in P where wrap(p) is periodic in the exemplar's size only.
class PeriodicLattice {
 public:
  // A vertex of lattice(): its reduced indices (the key of its draws), the translation of its
  // patch (p minus the vertex's position, whole pixels) and p minus its exact position (the patch
  // transform's centre).
  struct Vertex {
    std::int64_t key_x;
    std::int64_t key_y;
    Point2f translation;
    Point2f local;
  };

  PeriodicLattice(Vec2d period, double edge) noexcept
      : period_(period),
        edge_(edge),
        columns_(periodic_axis(period.x, edge).cells),
        rows_(periodic_axis(period.y, edge / kInverseSqrt3).cells),
        stretch_x_(static_cast<double>(columns_) * edge / period.x),
        stretch_y_(static_cast<double>(rows_) * edge / kInverseSqrt3 / period.y) {}

  // The lattice around p (reduced into the period) in the stretched space.
  LatticePoint lattice(Vec2d p) const noexcept {
    return triangle_lattice({p.x * stretch_x_, p.y * stretch_y_}, edge_);
  }

  Vertex vertex(Vec2d p, std::int64_t i, std::int64_t j) const noexcept {
    const PeriodicAxis two_rows{2 * rows_, 1.0};
    const std::int64_t key_y = two_rows.wrap(j);
    const std::int64_t wraps_y = (j - key_y) / (2 * rows_);
    const std::int64_t shifted_i = i + rows_ * wraps_y;
    const PeriodicAxis columns{columns_, 1.0};
    const std::int64_t key_x = columns.wrap(shifted_i);
    const std::int64_t wraps_x = (shifted_i - key_x) / columns_;
    // The reduced vertex's position, edge * (i + j / 2, j sqrt(3) / 2), unstretched.
    const double vertex_x =
        edge_ * (static_cast<double>(key_x) + 0.5 * static_cast<double>(key_y)) / stretch_x_;
    const double vertex_y = edge_ * static_cast<double>(key_y) * (0.5 / kInverseSqrt3) / stretch_y_;
    const double x = p.x - static_cast<double>(wraps_x) * period_.x;
    const double y = p.y - static_cast<double>(wraps_y) * period_.y;
    return {key_x,
            key_y,
            {static_cast<float>(x - std::round(vertex_x)),
             static_cast<float>(y - std::round(vertex_y))},
            {static_cast<float>(x - vertex_x), static_cast<float>(y - vertex_y)}};
  }

 private:
  Vec2d period_;
  double edge_;
  std::int64_t columns_;  // n
  std::int64_t rows_;     // m
  double stretch_x_;
  double stretch_y_;
};

// p wrapped into the exemplar's period [0, width) x [0, height), formed in double so that
// p = 1e7 keeps its fraction (docs/design.md §4); offsets are then added in float.
inline Point2f wrap_position(Vec2d p, int width, int height) noexcept {
  const ScalarOps ops;
  return {static_cast<float>(wrap(ops, p.x, static_cast<double>(width))),
          static_cast<float>(wrap(ops, p.y, static_cast<double>(height)))};
}

// The random patch of a lattice vertex (Algorithm 1: uv + hash(v)): a whole-pixel offset, uniform
// over the exemplar's period, from the vertex's own key. Whole pixels keep the exemplar's texel
// grid: at scale 1 every fetch lands on texel centres as in the exemplar itself, where a random
// sub-pixel offset would blur each patch by the bilinear interpolation (measured: spectral error
// 0.30 instead of 0.17 on moss_ground_512, ADSN 0.14).
inline Point2f vertex_offset(std::int64_t vertex_x, std::int64_t vertex_y, std::uint32_t seed,
                             int width, int height) noexcept {
  CounterRng rng(cell_key(vertex_x, vertex_y, seed, Stream::offsets));
  // One draw per statement: the order of the draws must not depend on argument evaluation order.
  const std::uint32_t u = rng.next();
  const std::uint32_t v = rng.next();
  // floor(u * width / 2^32): uniform in [0, width) without an integer division.
  return {static_cast<float>((static_cast<std::uint64_t>(u) * static_cast<std::uint32_t>(width)) >>
                             32u),
          static_cast<float>((static_cast<std::uint64_t>(v) * static_cast<std::uint32_t>(height)) >>
                             32u)};
}

// One periodic mip level of a multi-channel image: texel (i, j) covers the exemplar pixels
// [i, i + 1) / texels_per_pixel, so every level has the exemplar's period exactly.
struct MipLevel {
  int width = 0;
  int height = 0;
  float texels_per_pixel_x = 1.0f;
  float texels_per_pixel_y = 1.0f;
  const float* texels = nullptr;  // width x height x channels, row-major
};

// Adds weight * (bilinear, periodic) level(x, y) to acc; x, y in exemplar pixels, any sign.
inline void fetch_bilinear(const MipLevel& level, int channels, float x, float y, float weight,
                           float* acc) noexcept {
  const BilinearTaps<ScalarOps> taps = bilinear_taps(
      ScalarOps{},
      {level.texels_per_pixel_x, level.texels_per_pixel_y, static_cast<float>(level.width),
       static_cast<float>(level.height), level.width, level.height},
      x, y, weight);
  const float* r0 = level.texels + static_cast<std::ptrdiff_t>(taps.y0) * level.width * channels;
  const float* r1 = level.texels + static_cast<std::ptrdiff_t>(taps.y1) * level.width * channels;
  const int x0 = taps.x0 * channels;
  const int x1 = taps.x1 * channels;
  for (int c = 0; c < channels; ++c)
    acc[c] += bilinear_sum(taps, r0[x0 + c], r0[x1 + c], r1[x0 + c], r1[x1 + c]);
}

// erf(x) to 1e-7 (tested), with IEEE operations only, so that the vectorised evaluator (simd.cpp)
// repeats it bit for bit, which libm's erff has no twin for: the odd rational x P(x^2) / Q(x^2) of
// Eigen's generic_fast_erf_float (also XLA's ErfImpl32), clamped to [-4, 4] where erf is +-1 in
// float, evaluated in double (6.5e-8 from erf there; 4.4e-7 in float).
inline float erf_rational(float x) noexcept {
  return ScalarOps::erf(x);
}

// Eq. (22): the Gaussian value g of eq. (20) mapped to the uniform look-up-table parameter U.
inline float gaussian_to_uniform(float g) noexcept {
  return gaussian_to_uniform(ScalarOps{}, g);
}

// Linear interpolation in a table of `size` >= 2 cells centred on (k + 1/2) / size, clamped at
// the ends (a texture fetch with clamp-to-edge addressing): returns the fraction towards `first`+1.
inline float table_coordinate(float u, int size, int& first) noexcept {
  return table_coordinate(ScalarOps{}, u, size, first);
}

// A normal map's slopes s = (ds/dx, ds/dv) under the artist controls (issue 18) go through T in a
// radial group: T(s) = c + rho(|s|) s / |s|, c = (1/2, 1/2), with rho the exact 1-D transport of
// |s| onto the radius of the 2-D Gaussian of eq. (20), Rayleigh of scale sigma = 1/6. Unlike the
// principal axes, this T commutes with rotations, so a patch's slopes are turned in Gaussian space
// (turn_slopes) and blended like any channel. The table of T^-1 holds the quantiles of |s| at the
// uniform levels U = 1 - exp(-rho^2 / (2 sigma^2)) (the Rayleigh CDF), as eq. (22) does with erf.
inline float radius_to_uniform(float rho) noexcept {
  return -std::expm1(-0.5f * (rho * rho) / (kGaussianDeviation * kGaussianDeviation));
}

// The Rayleigh quantile: the radius rho whose radius_to_uniform is u, for u in [0, 1).
inline double uniform_to_radius(double u) noexcept {
  return kGaussianDeviation * std::sqrt(-2.0 * std::log1p(-u));
}

// |s| = T^-1's radial table at the Gaussian radius rho (linear in U, clamped at the ends).
inline float radial_lookup(const float* table, int size, float rho) noexcept {
  int cell = 0;
  const float t = table_coordinate(radius_to_uniform(rho), size, cell);
  return table[cell] + t * (table[cell + 1] - table[cell]);
}

// The inverse of radial_lookup: the Gaussian radius of the slope magnitude r, by bisection on the
// non-decreasing table (clamped to its first and last cell centres, as the look-up is).
inline float radial_inverse(const float* table, int size, float r) noexcept {
  if (!(r > table[0])) return static_cast<float>(uniform_to_radius(0.5 / size));
  if (!(r < table[size - 1])) return static_cast<float>(uniform_to_radius((size - 0.5) / size));
  int low = 0;  // table[low] < r <= table[high]
  int high = size - 1;
  while (high - low > 1) {
    const int middle = (low + high) / 2;
    (table[middle] < r ? low : high) = middle;
  }
  const float t = (r - table[low]) / (table[high] - table[low]);
  return static_cast<float>(uniform_to_radius((low + 0.5 + static_cast<double>(t)) / size));
}

// A patch's slopes (two channels of G in a radial group) under its transform M = scale * R: the
// patch shows the height h(M p) (p relative to the tile's centre, in pixels with rows down), whose
// gradient is M^T grad h there; in the slopes' (x, up) axes that is s' = M s, a turn by the patch's
// angle and a factor of its scale (a patch shrunk by the jitter has steeper relief: the normal map
// stays the gradient of the rendered height). The turn is exact in Gaussian space (T commutes with
// it); the magnitude goes through the level-0 table: rho' = T(scale T^-1(rho)).
inline void turn_slopes(const PatchTransform& m, const float* table, int size, float* g) noexcept {
  const float dx = g[0] - kGaussianMean;
  const float dy = g[1] - kGaussianMean;
  float factor = 1.0f / m.scale;
  if (m.scale != 1.0f) {
    const float rho = std::sqrt(dx * dx + dy * dy);
    if (rho > 0.0f)
      factor *= radial_inverse(table, size, m.scale * radial_lookup(table, size, rho)) / rho;
  }
  g[0] = kGaussianMean + factor * (m.xx * dx + m.xy * dy);
  g[1] = kGaussianMean + factor * (m.yx * dx + m.yy * dy);
}

// The standard normal quantile Phi^-1(q) for q in (0, 1), to double precision: an initial guess
// refined by Halley steps on erfc (used to place the look-up-table cells of eq. 20).
inline double normal_quantile(double q) noexcept {
  constexpr double kSqrt2 = 1.4142135623730951;
  constexpr double kSqrt2Pi = 2.5066282746310002;
  const double t = q < 0.5 ? q : 1.0 - q;
  // Tail-aware start: a logistic-like approximation, within ~5% everywhere.
  const double s = std::sqrt(-2.0 * std::log(t));
  double x = -(s - (2.30753 + 0.27061 * s) / (1.0 + (0.99229 + 0.04481 * s) * s));
  for (int i = 0; i < 3; ++i) {
    const double error = 0.5 * std::erfc(-x / kSqrt2) - t;
    const double density = std::exp(-0.5 * x * x) / kSqrt2Pi;
    const double newton = error / density;
    x -= newton / (1.0 + 0.5 * x * newton);
  }
  return q < 0.5 ? x : -x;
}

}  // namespace stochtex::tiling
