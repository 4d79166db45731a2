#include "methods/tiling/pyramid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "core/colour_statistics.hpp"
#include "core/srgb.hpp"
#include "methods/tiling/evaluate.hpp"
#include "methods/tiling/simd.hpp"
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

// A sparse matrix by rows (SparseRows, simd.hpp).
struct Kernel {
  std::vector<std::size_t> first{0};
  std::vector<std::int32_t> cells;
  std::vector<float> weights;
  SparseRows rows() const { return {first.data(), cells.data(), weights.data(), first.size() - 1}; }
};

// The prefiltered inverse of a pyramid level (our reading of Deliot & Heitz 2019, section
// "prefiltering the look-up table"): a level-l texel is the mean g of the G values under it, and
// the filtered output wanted is the mean of T^-1 over those values, not T^-1(g). For a Gaussian
// field the level-0 values under a texel of mean g spread as N(g, r^2) with r^2 = var(G_0) -
// var(G_l), so T^-1_l(g) = E[T^-1(z)], z ~ N(g, r^2). At the top level (one texel, r = sigma)
// a constant fetch returns the exemplar's mean colour, not T^-1(1/2), its median. The expectation
// is a midpoint rule over `kPrefilterStrata` equal-probability strata of N(g, r^2), each read from
// the table like the evaluator does (linear interpolation in the erf parameterisation, eq. 22, in
// lanes: table_coordinates); row i is the table cell at g_i = 1/2 + sigma Phi^-1((i + 1/2) /
// size). A row touches at most 2 kPrefilterStrata cells however wide it spreads: only those are
// kept, as the float weights the sums multiply by. A zero weight adds nothing to a sum of the
// finite values a table holds.
Kernel prefilter_kernel(int size, double residual_deviation) {
  Kernel kernel;
  kernel.first.reserve(static_cast<std::size_t>(size) + 1);
  std::array<double, kPrefilterStrata> strata{};
  for (int q = 0; q < kPrefilterStrata; ++q)
    strata[q] = normal_quantile((q + 0.5) / kPrefilterStrata);
  std::array<float, kPrefilterStrata> g{};
  std::array<std::int32_t, kPrefilterStrata> cells{};
  std::array<float, kPrefilterStrata> fractions{};
  std::array<std::int32_t, 2 * kPrefilterStrata> touched{};
  std::array<std::int32_t, 2 * kPrefilterStrata> row_cells{};
  std::array<float, 2 * kPrefilterStrata> row_weights{};
  std::vector<double> dense(static_cast<std::size_t>(size), 0.0);
  for (int i = 0; i < size; ++i) {
    const double centre = kGaussianMean + kGaussianDeviation * normal_quantile((i + 0.5) / size);
    for (int q = 0; q < kPrefilterStrata; ++q)
      g[q] = static_cast<float>(centre + residual_deviation * strata[q]);
    table_coordinates(g.data(), g.size(), size, cells.data(), fractions.data());
    bool ascending = true;
    for (int q = 0; q < kPrefilterStrata; ++q) {
      const float t = fractions[q];
      dense[cells[q]] += (1.0 - t) / kPrefilterStrata;
      dense[cells[q] + 1] += static_cast<double>(t) / kPrefilterStrata;
      ascending = ascending && (q == 0 || cells[q] >= cells[q - 1]);
    }
    // The cells touched, in ascending order: the strata ascend, and so do their cells unless
    // rounding turns one back (then they are sorted).
    std::size_t count = 0;
    for (int q = 0; q < kPrefilterStrata; ++q)
      for (const std::int32_t cell : {cells[q], cells[q] + 1})
        if (!ascending || count == 0 || cell > touched[count - 1]) touched[count++] = cell;
    auto end = touched.begin() + static_cast<std::ptrdiff_t>(count);
    if (!ascending) {
      std::sort(touched.begin(), end);
      end = std::unique(touched.begin(), end);
    }
    std::size_t kept = 0;
    for (auto cell = touched.begin(); cell != end; ++cell) {
      const auto weight = static_cast<float>(dense[*cell]);
      if (weight != 0.0f) {
        row_cells[kept] = *cell;
        row_weights[kept++] = weight;
      }
      dense[*cell] = 0.0;
    }
    kernel.cells.insert(kernel.cells.end(), row_cells.begin(), row_cells.begin() + kept);
    kernel.weights.insert(kernel.weights.end(), row_weights.begin(), row_weights.begin() + kept);
    kernel.first.push_back(kernel.cells.size());
  }
  return kernel;
}

// out = K in along one axis of a table of `blocks` blocks, each of K's rows of cells of `width`
// contiguous floats: out[b][i][j] = sum_k K[i][k] in[b][k][j] (apply_rows, in lanes).
void apply_kernel(const Kernel& kernel, const float* in, float* out, std::size_t blocks,
                  std::size_t width) {
  const SparseRows rows = kernel.rows();
  for (std::size_t b = 0; b < blocks; ++b)
    apply_rows(rows, in + b * rows.rows * width, out + b * rows.rows * width, width);
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

bool decodes_in_tables(const TilingData& d, const TableGroup& group, int channel) {
  if (d.colour.empty() || d.colour[static_cast<std::size_t>(channel)] != ColourSpace::srgb ||
      d.blend != Blend::histogram)
    return false;
  switch (group.transform) {
    case GroupTransform::lut:
    case GroupTransform::direct:
      return true;
    case GroupTransform::decorrelated:
      return group.channels == 1 &&
             d.colour_basis[static_cast<std::size_t>(group.first_basis)] != 0.0f;
    case GroupTransform::radial:
      return false;
  }
  return false;
}

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
  // The tables of linear light for srgb channels (docs/design.md §14): prefiltered like the
  // others, each level's then returns the expectation of the decoded colour over the footprint
  // (TilingModel::calibrate_colour corrects what the Gaussian residual gets wrong).
  std::vector<float> base_lut = d.lut;
  std::vector<float> base_tables = d.tables;
  for (const TableGroup& group : layout.groups) {
    if (group.transform == GroupTransform::lut) {
      for (std::size_t i = 0; i < base_lut.size(); ++i)
        if (decodes_in_tables(d, group, group.first + static_cast<int>(i % 3)))
          base_lut[i] = srgb_decode(base_lut[i]);
      continue;
    }
    if (!decodes_in_tables(d, group, group.first)) continue;
    const auto first = static_cast<std::size_t>(group.first_table) * d.table_size;
    float* table = base_tables.data() + first;
    if (group.transform == GroupTransform::direct) {
      for (int i = 0; i < d.table_size; ++i) table[i] = srgb_decode(table[i]);
    } else {
      // One decorrelated channel: out = mean + b t, so the table t' = (decode(mean + b t) -
      // mean) / b makes it decode(out) (a grey image).
      const double mean = d.colour_mean[static_cast<std::size_t>(group.first_mean)];
      const double b = d.colour_basis[static_cast<std::size_t>(group.first_basis)];
      for (int i = 0; i < d.table_size; ++i)
        table[i] = static_cast<float>((srgb_decode(mean + b * table[i]) - mean) / b);
    }
  }
  const std::vector<double> base_variance =
      level_variances(texels.front(), d.width, d.height, d.channels);
  for (std::size_t l = 0; l < texels.size(); ++l) {
    const std::vector<double> variance =
        l == 0 ? base_variance : level_variances(texels[l], widths[l], heights[l], d.channels);
    const auto residual = [&](int channel) {
      return l == 0 ? 0.0 : std::sqrt(std::max(0.0, base_variance[channel] - variance[channel]));
    };
    std::vector<float> lut = base_lut;
    std::vector<float> tables = base_tables;
    for (const TableGroup& group : layout.groups) {
      if (l == 0) break;
      if (group.transform == GroupTransform::lut) {
        std::vector<float> scratch(lut.size());
        // Axis c of the table is channel first + c of G; the layout is [z][y][x][colour].
        const int f = group.first;
        // Along x through the transposed table [x][z][y][colour], whose x cells are contiguous.
        const auto transpose = [n](const std::vector<float>& from, std::vector<float>& to,
                                   bool back) {
          for (std::size_t zy = 0; zy < n * n; ++zy)
            for (std::size_t x = 0; x < n; ++x)
              for (std::size_t c = 0; c < 3; ++c) {
                const std::size_t table = (zy * n + x) * 3 + c;
                const std::size_t transposed = (x * n * n + zy) * 3 + c;
                to[back ? table : transposed] = from[back ? transposed : table];
              }
        };
        transpose(lut, scratch, false);
        apply_kernel(prefilter_kernel(d.lut_size, residual(f)), scratch.data(), lut.data(), 1,
                     n * n * 3);
        transpose(lut, scratch, true);
        apply_kernel(prefilter_kernel(d.lut_size, residual(f + 1)), scratch.data(), lut.data(), n,
                     n * 3);
        apply_kernel(prefilter_kernel(d.lut_size, residual(f + 2)), lut.data(), scratch.data(), 1,
                     n * n * 3);
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
        const std::size_t offset = static_cast<std::size_t>(group.first_table + k) * d.table_size;
        apply_kernel(prefilter_kernel(d.table_size, residual(group.first + k)),
                     base_tables.data() + offset, tables.data() + offset, 1, 1);
      }
    }
    level_luts.insert(level_luts.end(), lut.begin(), lut.end());
    level_tables.insert(level_tables.end(), tables.begin(), tables.end());
  }
}

}  // namespace stochtex::tiling
