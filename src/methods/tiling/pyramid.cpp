#include "methods/tiling/pyramid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "core/colour_statistics.hpp"
#include "methods/tiling/evaluate.hpp"
#include "stochtex/image.hpp"

namespace stochtex::tiling {
namespace {

// Strata of the quadrature that prefilters T^-1 (see prefilter_kernel).
constexpr int kPrefilterStrata = 64;

// The variance of each channel of a pyramid level's texels (width x height x channels).
std::vector<double> level_variances(const std::vector<float>& texels, int width, int height,
                                    int channels) {
  const ImageView<const float> level{texels.data(), width, height, channels,
                                     static_cast<std::ptrdiff_t>(width) * channels};
  return channel_variances(level, channel_means(level));
}

// One row of a banded matrix: entries first .. first + weights.size() - 1.
struct KernelRow {
  int first = 0;
  std::vector<float> weights;
};

// The prefiltered inverse of a pyramid level (our reading of Deliot & Heitz 2019, section
// "prefiltering the look-up table"): a level-l texel is the mean g of the G values under it, and
// the filtered output wanted is the mean of T^-1 over those values, not T^-1(g). For a Gaussian
// field the level-0 values under a texel of mean g spread as N(g, r^2) with r^2 = var(G_0) -
// var(G_l), so T^-1_l(g) = E[T^-1(z)], z ~ N(g, r^2). At the top level (one texel, r = sigma)
// a constant fetch returns the exemplar's mean colour, not T^-1(1/2), its median. The expectation
// is a midpoint rule over `kPrefilterStrata` equal-probability strata of N(g, r^2), each read from
// the table like the evaluator does (linear interpolation in the erf parameterisation, eq. 22);
// row i is the table cell at g_i = 1/2 + sigma Phi^-1((i + 1/2) / size).
std::vector<KernelRow> prefilter_kernel(int size, double residual_deviation) {
  std::vector<KernelRow> rows(static_cast<std::size_t>(size));
  std::vector<double> strata(kPrefilterStrata);
  for (int q = 0; q < kPrefilterStrata; ++q)
    strata[q] = normal_quantile((q + 0.5) / kPrefilterStrata);
  std::vector<double> dense(static_cast<std::size_t>(size));
  for (int i = 0; i < size; ++i) {
    std::fill(dense.begin(), dense.end(), 0.0);
    const double centre = kGaussianMean + kGaussianDeviation * normal_quantile((i + 0.5) / size);
    int first = size;
    int last = -1;
    for (int q = 0; q < kPrefilterStrata; ++q) {
      const auto g = static_cast<float>(centre + residual_deviation * strata[q]);
      int cell = 0;
      const float t = table_coordinate(gaussian_to_uniform(g), size, cell);
      dense[cell] += (1.0 - t) / kPrefilterStrata;
      dense[cell + 1] += static_cast<double>(t) / kPrefilterStrata;
      first = std::min(first, cell);
      last = std::max(last, cell + 1);
    }
    rows[i].first = first;
    rows[i].weights.assign(dense.begin() + first, dense.begin() + last + 1);
  }
  return rows;
}

// out[i] = sum_a K[i][a] in[a] along one axis of a table with `stride` floats between cells and
// `count` independent lines, each line's origin given by line_origin(line). Each sum adds its
// terms in the order of a; the sums of a block of lines and components run side by side (a
// model load is bound by this loop: one sum at a time waits on every addition).
template <typename Origin>
void apply_kernel(const std::vector<KernelRow>& rows, const std::vector<float>& in,
                  std::vector<float>& out, std::size_t stride, std::size_t lines, int components,
                  Origin line_origin) {
  constexpr std::size_t kBlock = 8;
  std::array<std::size_t, kBlock * 3> origins{};
  std::array<double, kBlock * 3> sums{};
  for (std::size_t line = 0; line < lines; line += kBlock) {
    std::size_t chains = 0;
    for (std::size_t l = line; l < std::min(line + kBlock, lines); ++l)
      for (int c = 0; c < components; ++c) origins[chains++] = line_origin(l) + c;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      std::fill_n(sums.begin(), chains, 0.0);
      const float* from = in.data() + static_cast<std::size_t>(rows[i].first) * stride;
      for (std::size_t k = 0; k < rows[i].weights.size(); ++k) {
        const float weight = rows[i].weights[k];  // a float product, added in double
        for (std::size_t j = 0; j < chains; ++j) sums[j] += weight * from[origins[j] + k * stride];
      }
      for (std::size_t j = 0; j < chains; ++j)
        out[origins[j] + i * stride] = static_cast<float>(sums[j]);
    }
  }
}

// prefilter_kernel for a radial table (GroupTransform::radial): the level's texel is the mean g of
// slopes in Gaussian space spread as N(g, r^2 I) in 2-D, and the filtered slope wanted is the mean
// of T^-1 over them, E[|s|(|z|) z / |z|], z ~ N(g, r^2 I) (centred). By symmetry it points along g
// with a magnitude that depends on |g| alone: row i holds it at the cell's radius. The expectation
// is a midpoint rule over kRadialStrata^2 equal-probability strata of the 2-D Gaussian.
constexpr int kRadialStrata = 16;

void prefilter_radial(const std::vector<float>& base, int table, int size, double spread,
                      std::vector<float>& out) {
  std::vector<double> strata(kRadialStrata);
  for (int q = 0; q < kRadialStrata; ++q)
    strata[q] = spread * normal_quantile((q + 0.5) / kRadialStrata);
  const float* slopes = base.data() + static_cast<std::ptrdiff_t>(table) * size;
  for (int i = 0; i < size; ++i) {
    const double rho = uniform_to_radius((i + 0.5) / size);
    double sum = 0.0;
    for (const double a : strata)
      for (const double b : strata) {
        const double x = rho + a;
        const double length = std::hypot(x, b);
        if (length > 0.0)
          sum += radial_lookup(slopes, size, static_cast<float>(length)) * (x / length);
      }
    out[static_cast<std::size_t>(table) * size + i] =
        static_cast<float>(sum / (kRadialStrata * kRadialStrata));
  }
}

}  // namespace

std::vector<std::vector<float>> build_pyramid(const std::vector<float>& base, int width, int height,
                                              int channels, std::vector<int>& widths,
                                              std::vector<int>& heights) {
  std::vector<std::vector<float>> levels{base};
  widths = {width};
  heights = {height};
  while (widths.back() > 1 || heights.back() > 1) {
    const int w = widths.back();
    const int h = heights.back();
    const int next_w = (w + 1) / 2;
    const int next_h = (h + 1) / 2;
    const std::vector<float>& current = levels.back();
    std::vector<float> next(static_cast<std::size_t>(next_w) * next_h * channels, 0.0f);
    for (int y = 0; y < next_h; ++y)
      for (int x = 0; x < next_w; ++x)
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const int sx = (2 * x + dx) % w;
            const int sy = (2 * y + dy) % h;
            for (int c = 0; c < channels; ++c)
              next[(static_cast<std::size_t>(y) * next_w + x) * channels + c] +=
                  0.25f * current[(static_cast<std::size_t>(sy) * w + sx) * channels + c];
          }
    levels.push_back(std::move(next));
    widths.push_back(next_w);
    heights.push_back(next_h);
  }
  return levels;
}

void prefilter_levels(const TilingData& d, const TilingLayout& layout,
                      const std::vector<std::vector<float>>& texels, const std::vector<int>& widths,
                      const std::vector<int>& heights, std::vector<float>& level_luts,
                      std::vector<float>& level_tables) {
  const auto n = static_cast<std::size_t>(d.lut_size);
  const std::vector<double> base_variance =
      level_variances(texels.front(), d.width, d.height, d.channels);
  for (std::size_t l = 0; l < texels.size(); ++l) {
    const std::vector<double> variance =
        level_variances(texels[l], widths[l], heights[l], d.channels);
    const auto residual = [&](int channel) {
      return l == 0 ? 0.0 : std::sqrt(std::max(0.0, base_variance[channel] - variance[channel]));
    };
    std::vector<float> lut = d.lut;
    std::vector<float> tables = d.tables;
    for (const TableGroup& group : layout.groups) {
      if (l == 0) break;
      if (group.transform == GroupTransform::lut) {
        std::vector<float> scratch(lut.size());
        // Axis c of the table is channel first + c of G; the layout is [z][y][x][colour].
        const int f = group.first;
        apply_kernel(prefilter_kernel(d.lut_size, residual(f)), lut, scratch, 3, n * n, 3,
                     [&](std::size_t line) { return line * n * 3; });
        apply_kernel(prefilter_kernel(d.lut_size, residual(f + 1)), scratch, lut, n * 3, n * n, 3,
                     [&](std::size_t line) { return (line / n) * n * n * 3 + (line % n) * 3; });
        apply_kernel(prefilter_kernel(d.lut_size, residual(f + 2)), lut, scratch, n * n * 3, n * n,
                     3, [&](std::size_t line) { return line * 3; });
        lut = std::move(scratch);
        continue;
      }
      if (group.transform == GroupTransform::radial) {
        // Both slopes of G spread alike (T is isotropic): one residual for the pair.
        const double spread = std::hypot(residual(group.first), residual(group.first + 1));
        prefilter_radial(d.tables, group.first_table, d.table_size,
                         spread * std::numbers::sqrt2 / 2.0, tables);
        continue;
      }
      // Table k of a group is read at channel first + k of G.
      const int count = group.transform == GroupTransform::direct ? 1 : group.channels;
      for (int k = 0; k < count; ++k) {
        const int t = group.first_table + k;
        const auto size = static_cast<std::size_t>(d.table_size);
        apply_kernel(prefilter_kernel(d.table_size, residual(group.first + k)), d.tables, tables, 1,
                     1, 1, [&](std::size_t) { return static_cast<std::size_t>(t) * size; });
      }
    }
    level_luts.insert(level_luts.end(), lut.begin(), lut.end());
    level_tables.insert(level_tables.end(), tables.begin(), tables.end());
  }
}

}  // namespace stochtex::tiling
