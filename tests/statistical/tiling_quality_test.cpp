// Histogram-preserving tiling and blending against its paper's claims (docs/design.md §8): the
// exemplar's colour histogram is kept (section 3.3), the lattice is invisible (no variance change
// over a tile, figure 4), Gaussian inputs need no transform (section 6.1), and minified renders
// match a supersampled reference (section 5.4). Baselines measured in the same tests: linear
// blending (eq. 3), variance-preserving blending of the raw exemplar (eq. 8) and ADSN.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

#include "io/image_io.hpp"
#include "methods/tiling/evaluate.hpp"
#include "methods/tiling/model.hpp"
#include "metrics/metrics.hpp"
#include "model/model_data.hpp"
#include "shared.hpp"
#include "spectral/adsn.hpp"
#include "statistics.hpp"
#include "stochtex/material.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::tiling_quality_test {
namespace {

using tiling::LatticePoint;
using tiling::MipLevel;

const std::string kTextureDir = STOCHTEX_TEXTURE_DIR;

using test_support::histogram_distance;
using test_support::Sample;
using test_support::summarise;

ImageF render_model(const Model& model, const Grid& grid, std::uint32_t seed, int supersample = 1,
                    bool filter = true) {
  ImageF out(grid.width, grid.height, model.channels());
  RenderOptions options;
  options.supersample = supersample;
  options.filter = filter;
  render(model, grid, seed, out.view(), options);
  return out;
}

// Linear blending (eq. 3) of the same three patches the tiling model reads: the baseline whose
// contrast drops between vertices (figure 4a).
ImageF render_linear(const ImageF& exemplar, double edge, const Grid& grid, std::uint32_t seed) {
  const int channels = exemplar.channels();
  const MipLevel level{exemplar.width(), exemplar.height(), 1.0f, 1.0f, exemplar.pixels().data()};
  ImageF out(grid.width, grid.height, channels);
  for (int j = 0; j < grid.height; ++j)
    for (int i = 0; i < grid.width; ++i) {
      const Vec2d p{grid.origin.x + grid.scale * (i + 0.5), grid.origin.y + grid.scale * (j + 0.5)};
      const LatticePoint lattice = tiling::triangle_lattice(p, edge);
      const tiling::Point2f wrapped = tiling::wrap_position(p, exemplar.width(), exemplar.height());
      float acc[4] = {0, 0, 0, 0};
      for (int v = 0; v < 3; ++v) {
        const tiling::Point2f offset = tiling::vertex_offset(
            lattice.vertex_x[v], lattice.vertex_y[v], seed, exemplar.width(), exemplar.height());
        tiling::fetch_bilinear(level, channels, wrapped.x + offset.x, wrapped.y + offset.y,
                               lattice.weight[v], acc);
      }
      for (int c = 0; c < channels; ++c) out.at(i, j, c) = acc[c];
    }
  return out;
}

ImageF half(const ImageF& image, bool bottom) {
  const int rows = image.height() / 2;
  ImageF out(image.width(), rows, image.channels());
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < image.channels(); ++c)
        out.at(x, y, c) = image.at(x, y + (bottom ? rows : 0), c);
  return out;
}

double edge_of(const Model& model) {
  return std::get<tiling::TilingModel>(model.data().model).lattice_edge();
}

// `stochastic` and `structured` corpus images (SOURCES.md), grey and colour.
const std::vector<std::string> kHistogramExemplars = {
    "moss_ground_512.png",       "sand_height_grey_512.png", "metal_grey_256.png",
    "bricks_stone_wall_512.png", "nuts_grey_256.png",        "water_caustics_256.png"};
constexpr int kDirections = 6;

// a - b with the pooled standard deviation of one measurement of each.
Sample pooled_gap(const Sample& a, const Sample& b) {
  return {a.mean - b.mean,
          std::sqrt(0.5 * (a.deviation * a.deviation + b.deviation * b.deviation))};
}

class TilingHistogram : public testing::TestWithParam<std::string> {};

TEST_P(TilingHistogram, IsPreservedUnlikeLinearBlendingOrAdsn) {
  {
    const std::string name = GetParam();
    const ImageF exemplar = read_image(kTextureDir + "/" + name);
    const Model model = test_support::default_model("tiling", name, exemplar);
    const Model variance_only = analyze("tiling", exemplar.view(), {{"blend", 1}}, 0, name);
    const int side = exemplar.width();
    const Grid grid{{0.0, 0.0}, 1.0, side, side};
    // Grey images cost one sort per measurement: more seeds make their noise as small as colour's.
    const int seeds = exemplar.channels() == 1 ? 16 : 4;
    std::vector<double> ours, linear, variance, gaussian;
    for (std::uint32_t seed = 1; seed <= static_cast<std::uint32_t>(seeds); ++seed) {
      ours.push_back(
          sliced_wasserstein(render_model(model, grid, seed).view(), exemplar.view(), kDirections));
      linear.push_back(
          sliced_wasserstein(render_linear(exemplar, edge_of(model), grid, seed).view(),
                             exemplar.view(), kDirections));
      variance.push_back(sliced_wasserstein(render_model(variance_only, grid, seed).view(),
                                            exemplar.view(), kDirections));
      gaussian.push_back(sliced_wasserstein(adsn(exemplar.view(), side, side, seed).view(),
                                            exemplar.view(), kDirections));
    }
    const double floor =
        sliced_wasserstein(half(exemplar, false).view(), half(exemplar, true).view(), kDirections);
    const Sample o = summarise(ours), l = summarise(linear), v = summarise(variance),
                 g = summarise(gaussian);
    std::cout << name << ": sliced W2 to the exemplar: tiling " << o.mean << " (sd " << o.deviation
              << "), linear " << l.mean << " (sd " << l.deviation << "), variance-only " << v.mean
              << " (sd " << v.deviation << "), ADSN " << g.mean << " (sd " << g.deviation
              << "); exemplar floor (top vs bottom half) " << floor << "\n";
    // Bounds from the estimator's noise: `sd` is the seed-to-seed standard deviation of one
    // measurement, and a difference is judged against the pooled deviation of its two terms.
    // "Close to the floor": a render is no further from the exemplar than one half of the exemplar
    // is from the other (the exemplar's own non-stationarity), up to 3 deviations. Measured 0.14
    // to 0.76 of the floor, 1.09 on sand (within its noise).
    EXPECT_LE(o.mean, floor + 3.0 * o.deviation) << name;
    // "Far below" linear blending and ADSN: above ours by more than 4 pooled deviations and, for
    // linear blending, by a factor 2 (measured 3.2 to 11). The test can fail: with T^-1 skipped
    // (the output left in Gaussian space) every exemplar fails all of these bounds (checked).
    const Sample to_linear = pooled_gap(l, o);
    const Sample to_adsn = pooled_gap(g, o);
    EXPECT_GT(to_linear.mean, 4.0 * to_linear.deviation) << name;
    EXPECT_GT(l.mean, 2.0 * o.mean) << name;
    // docs/design.md §8: tiling must beat ADSN on non-Gaussian inputs, i.e. where ADSN's own
    // error exceeds the floor by more than 4 of its deviations (metal, nuts, water); on the others
    // (moss, sand, bricks: Gaussian-like histograms) it must not be worse.
    if (g.mean - floor > 4.0 * g.deviation)
      EXPECT_GT(to_adsn.mean, 4.0 * to_adsn.deviation) << name;
    else
      EXPECT_GT(to_adsn.mean, -3.0 * to_adsn.deviation) << name;
    // Variance-only blending (eq. 8) keeps the global histogram of near-Gaussian exemplars and
    // fails on non-Gaussian ones; it is never better than ours beyond the noise. Its pixel-level
    // failure is tested below, at the triangle centres.
    const Sample to_variance = pooled_gap(v, o);
    EXPECT_GT(to_variance.mean, -3.0 * to_variance.deviation) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(StochasticAndStructured, TilingHistogram,
                         testing::ValuesIn(kHistogramExemplars),
                         [](const testing::TestParamInfo<std::string>& param) {
                           return param.param.substr(0, param.param.find('_'));
                         });

// Per-pixel statistics across seeds over a region of the lattice, with each pixel's lattice
// weight norm W^2 = sum w^2 (1 on a vertex, 1/3 at a triangle centre).
struct SeedStatistics {
  std::vector<double> weight_norm;            // per pixel
  std::vector<std::vector<double>> variance;  // per group of seeds, per pixel (channel sum)
  std::vector<float> centre_values;           // channel-0 values at pixels with W^2 < 0.4
};

template <typename Render>
SeedStatistics seed_statistics(const Grid& grid, double edge, int groups, int seeds_per_group,
                               Render&& render_seed) {
  SeedStatistics stats;
  const std::size_t pixels = static_cast<std::size_t>(grid.width) * grid.height;
  for (int j = 0; j < grid.height; ++j)
    for (int i = 0; i < grid.width; ++i) {
      const LatticePoint lattice = tiling::triangle_lattice(
          {grid.origin.x + grid.scale * (i + 0.5), grid.origin.y + grid.scale * (j + 0.5)}, edge);
      double norm = 0.0;
      for (const float w : lattice.weight) norm += static_cast<double>(w) * w;
      stats.weight_norm.push_back(norm);
    }
  for (int group = 0; group < groups; ++group) {
    std::vector<double> sum(pixels, 0.0), square(pixels, 0.0);
    for (int k = 0; k < seeds_per_group; ++k) {
      const ImageF image = render_seed(static_cast<std::uint32_t>(group * seeds_per_group + k + 1));
      const int channels = image.channels();
      for (std::size_t p = 0; p < pixels; ++p) {
        for (int c = 0; c < channels; ++c) {
          const double value = image.pixels()[p * channels + c];
          sum[p] += value;
          square[p] += value * value;
        }
        if (stats.weight_norm[p] < 0.4) stats.centre_values.push_back(image.pixels()[p * channels]);
      }
    }
    std::vector<double> variance(pixels);
    for (std::size_t p = 0; p < pixels; ++p)
      variance[p] = (square[p] - sum[p] * sum[p] / seeds_per_group) / (seeds_per_group - 1);
    stats.variance.push_back(std::move(variance));
  }
  return stats;
}

// Mean per-pixel variance of the pixels near triangle centres (W^2 < 0.4) over that of the
// pixels near vertices (W^2 > 0.8), per group of seeds: 1 when the lattice is invisible. Returns
// the mean over groups and its standard error.
Sample centre_to_vertex_variance(const SeedStatistics& stats) {
  std::vector<double> ratios;
  for (const auto& variance : stats.variance) {
    double centre = 0.0, vertex = 0.0;
    int centre_count = 0, vertex_count = 0;
    for (std::size_t p = 0; p < variance.size(); ++p) {
      if (stats.weight_norm[p] < 0.4) {
        centre += variance[p];
        ++centre_count;
      } else if (stats.weight_norm[p] > 0.8) {
        vertex += variance[p];
        ++vertex_count;
      }
    }
    ratios.push_back((centre / centre_count) / (vertex / vertex_count));
  }
  Sample ratio = summarise(ratios);
  ratio.deviation /= std::sqrt(static_cast<double>(ratios.size()));
  return ratio;
}

TEST(TilingQuality, LatticeIsInvisibleInThePerPixelVarianceAcrossSeeds) {
  // Figure 4: linear blending lowers the contrast between vertices (variance x W^2), revealing
  // the grid; histogram-preserving blending keeps every pixel's distribution, so the per-pixel
  // variance across seeds is flat over a tile. nuts_grey_256 is bimodal (the hardest case for
  // blending). The region spans 256 x 256 exemplar pixels (tiles of edge 128) at 64 x 64 point
  // samples (the blending operator, not the filter, is under test).
  const ImageF exemplar = read_image(kTextureDir + "/nuts_grey_256.png");
  const Model model = analyze("tiling", exemplar.view(), {}, 0);
  const Model variance_only = analyze("tiling", exemplar.view(), {{"blend", 1}}, 0);
  const double edge = edge_of(model);
  const Grid grid{{17.5, 29.5}, 4.0, 64, 64};
  constexpr int kGroups = 8;
  constexpr int kSeedsPerGroup = 32;
  const auto statistics = [&](auto&& render_seed) {
    return seed_statistics(grid, edge, kGroups, kSeedsPerGroup, render_seed);
  };
  const SeedStatistics ours =
      statistics([&](std::uint32_t seed) { return render_model(model, grid, seed, 1, false); });
  const SeedStatistics linear =
      statistics([&](std::uint32_t seed) { return render_linear(exemplar, edge, grid, seed); });
  const SeedStatistics variance = statistics(
      [&](std::uint32_t seed) { return render_model(variance_only, grid, seed, 1, false); });
  const Sample r_ours = centre_to_vertex_variance(ours);
  const Sample r_linear = centre_to_vertex_variance(linear);
  const Sample r_variance = centre_to_vertex_variance(variance);
  // The pixel-level histogram at the triangle centres (where three patches mix most) against the
  // exemplar's: what section 3.3 promises and eq. (8) does not keep for a bimodal histogram.
  const auto centre_distance = [&](const SeedStatistics& stats) {
    const ImageView<const float> values{stats.centre_values.data(),
                                        static_cast<int>(stats.centre_values.size()), 1, 1,
                                        static_cast<std::ptrdiff_t>(stats.centre_values.size())};
    return sliced_wasserstein(values, exemplar.view(), 1);
  };
  const double floor =
      sliced_wasserstein(half(exemplar, false).view(), half(exemplar, true).view(), 1);
  const double d_ours = centre_distance(ours);
  const double d_linear = centre_distance(linear);
  const double d_variance = centre_distance(variance);
  std::cout << "centre/vertex per-pixel variance: tiling " << r_ours.mean << " (se "
            << r_ours.deviation << "), linear " << r_linear.mean << " (se " << r_linear.deviation
            << "), variance-only " << r_variance.mean << " (se " << r_variance.deviation
            << "); W2 of the centre pixels to the exemplar: tiling " << d_ours << ", linear "
            << d_linear << ", variance-only " << d_variance << " (exemplar floor " << floor
            << ")\n";
  // The ratio's standard error comes from the spread of 8 independent groups of 32 seeds; flat
  // means within 4 of them of 1. Measured: 0.993 (se 0.0045) ours, 0.424 (se 0.0025) linear,
  // 1.000 variance-only. The samples sit on texel centres, so the fetch is exact and only the
  // blending is under test: on texel corners (a bilinear average of 4 texels, whose distribution
  // in Gaussian space is a variance mixture, not a Gaussian) ours measured 0.968 (se 0.004).
  // The centre pixels' histogram: W2 0.0044 ours (floor 0.0145), 0.17 linear, 0.12 variance-only.
  // The test can fail: linear blending fails the ratio, and T^-1 skipped (output left in Gaussian
  // space) fails the histogram bounds (W2 0.24, checked).
  EXPECT_LT(std::abs(r_ours.mean - 1.0), 4.0 * r_ours.deviation);
  EXPECT_LT(r_linear.mean, 0.8 - 4.0 * r_linear.deviation);
  EXPECT_LE(d_ours, floor);
  EXPECT_GT(d_variance, 3.0 * d_ours);
  EXPECT_GT(d_linear, 3.0 * d_ours);
}

TEST(TilingControls, KeepTheHistogramAndHideTheLattice) {
  // The artist controls one at a time at their strongest documented setting, against the
  // defaults, on nuts_grey_256 (bimodal: the hardest case for blending) as above: (a) the sliced
  // W2 of a whole render to the exemplar over 16 seeds, (b) the centre/vertex ratio of the
  // per-pixel variance across seeds (8 groups of 32 seeds, point samples).
  const ImageF exemplar = read_image(kTextureDir + "/nuts_grey_256.png");
  const double floor =
      sliced_wasserstein(half(exemplar, false).view(), half(exemplar, true).view(), kDirections);
  const Grid whole{{0.0, 0.0}, 1.0, 256, 256};
  const Grid region{{17.5, 29.5}, 4.0, 64, 64};
  const std::vector<std::pair<std::string, ParamValues>> settings = {
      {"defaults", {}},
      {"rotation 180", {{"rotation", 180}}},
      {"scale_jitter 0.5", {{"scale_jitter", 0.5}}},
      {"sharpness 4", {{"sharpness", 4}}}};
  Sample defaults;
  for (const auto& [label, params] : settings) {
    const Model model = analyze("tiling", exemplar.view(), params, 0);
    std::vector<double> distances;
    for (std::uint32_t seed = 1; seed <= 16; ++seed)
      distances.push_back(sliced_wasserstein(render_model(model, whole, seed).view(),
                                             exemplar.view(), kDirections));
    const Sample w2 = summarise(distances);
    const Sample ratio = centre_to_vertex_variance(seed_statistics(
        region, edge_of(model), 8, 32,
        [&](std::uint32_t seed) { return render_model(model, region, seed, 1, false); }));
    std::cout << label << ": sliced W2 to the exemplar " << w2.mean << " (sd " << w2.deviation
              << ", floor " << floor << "); centre/vertex per-pixel variance " << ratio.mean
              << " (se " << ratio.deviation << ")\n";
    if (label == "defaults") defaults = w2;
    // (a) At the level of the defaults: within 4 pooled deviations of theirs, and as close to
    // the exemplar as the defaults' bound above (floor + 3 deviations). Measured W2 (sd over
    // seeds, floor 0.0145): 0.0110 (0.006) defaults, 0.0123 (0.009) rotation 180, 0.0119
    // (0.007) scale_jitter 0.5, 0.0105 (0.006) sharpness 4.
    const Sample gap = pooled_gap(w2, defaults);
    EXPECT_LT(gap.mean, 4.0 * gap.deviation) << label;
    EXPECT_LE(w2.mean, floor + 3.0 * w2.deviation) << label;
    // (b) Flat: within 4 standard errors of 1, as the defaults' bound above. A rotated or scaled
    // patch is read between texels (a bilinear average, whose variance is lower) except at its
    // vertex: up to the 0.968 the defaults measured on texel corners (above) is that, not a
    // visible lattice (linear blending: 0.42). Measured 0.977 (se 0.006) rotation 180, 0.979
    // (se 0.006) scale_jitter 0.5, 0.994 (se 0.005) sharpness 4, 0.993 (se 0.004) defaults.
    const bool between_texels = params.contains("rotation") || params.contains("scale_jitter");
    EXPECT_LT(std::abs(ratio.mean - 1.0), 4.0 * ratio.deviation + (between_texels ? 0.035 : 0.0))
        << label;
  }
}

TEST(TilingControls, HeightBlendLetsTheHigherPatchWinAndKeepsTheMaps) {
  // rock_sandstone's albedo, height and ao (5 channels) with height_blend 0.1 against the plain
  // blend, 8 seeds of 1024² at the same positions: (a) the higher patch wins, so the render's mean
  // height rises (paired over the seeds); (b) every other map's histogram (1-D W1 per channel)
  // stays nearer the exemplar's than the Gaussian version's (ADSN); (c) the per-pixel variance
  // across seeds over a tile, as KeepTheHistogramAndHideTheLattice above.
  const test_support::ShippedMaterial rock =
      test_support::shipped_material("rock_sandstone", {"albedo", "height", "ao"});
  const std::vector<MaterialMap>& maps = rock.maps;
  const ImageF exemplar = material_exemplar(maps).exemplar;
  constexpr int kHeight = 3;
  const int channels = exemplar.channels();
  const auto mean_height = [](const ImageF& image) {
    double sum = 0.0;
    for (int j = 0; j < image.height(); ++j)
      for (int i = 0; i < image.width(); ++i) sum += image.at(i, j, kHeight);
    return sum / (static_cast<double>(image.width()) * image.height());
  };
  const Model plain = analyze_material("tiling", maps);
  const Model blended = analyze_material("tiling", maps, {{"height_blend", 0.1}});
  constexpr int kSide = 1024;
  constexpr int kSeeds = 8;
  std::vector<double> rise;
  std::vector<std::vector<double>> kept(channels), lost(channels);
  for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
    const Grid grid{{1000.0 * seed, -700.0 * seed}, 1.0, kSide, kSide};
    const ImageF render = render_model(blended, grid, seed);
    const ImageF gaussian = adsn(exemplar.view(), kSide, kSide, seed);
    rise.push_back(mean_height(render) - mean_height(render_model(plain, grid, seed)));
    for (int c = 0; c < channels; ++c) {
      kept[c].push_back(histogram_distance(render, exemplar, c));
      lost[c].push_back(histogram_distance(gaussian, exemplar, c));
    }
  }
  // (a) Beyond 4 standard errors of the paired difference. Measured rise (sd over seeds): 0.044
  // (0.003), the height in [0, 1]. Against the exemplar's mean (512², 8 seeds): 0.043 at
  // height_blend 0.02, 0.035 at 0.1, 0.028 at 0.2 (sd 0.01), the plain blend -0.007 (0.014).
  const Sample height = summarise(rise);
  std::cout << "mean height rise " << height.mean << " (sd " << height.deviation << ")\n";
  EXPECT_GT(height.mean, 4.0 * height.deviation / std::sqrt(kSeeds));
  // (b) The difference of the means beyond 4 of its standard errors, as
  // TilingMaterial.MapsKeepTheirHistogramsAndCrossCorrelations. The height's own histogram moves
  // up by the rise (its W1 is about the mean rise: the blended height dominates the plain one),
  // which is the control's effect, so it is left out. Measured W1 (tiling, ADSN): albedo
  // 0.0020, 0.0080 / 0.0031, 0.0069 / 0.0027, 0.0059; height 0.045, 0.011; ao 0.025, 0.062.
  for (int c = 0; c < channels; ++c) {
    const Sample k = summarise(kept[c]);
    const Sample l = summarise(lost[c]);
    std::cout << "channel " << c << " histogram W1: tiling " << k.mean << " (sd " << k.deviation
              << "), ADSN " << l.mean << " (sd " << l.deviation << ")\n";
    if (c != kHeight) {
      EXPECT_LT(k.mean + 4.0 * pooled(k, l) * std::sqrt(2.0 / kSeeds), l.mean) << "channel " << c;
    }
  }
  // (c) Not flat: the triangle centres, where the higher patch is chosen among three, vary more
  // across seeds than the vertices (one patch). Measured centre/vertex ratio (se over 8 groups of
  // 32 seeds): 1.120 (0.008) at height_blend 0.02, 1.105 (0.008) at 0.1, 1.084 (0.009) at 0.2;
  // the plain blend 1.001 (0.009), linear blending 0.42. Bound: the measured 1.105 within 4
  // standard errors, so that a change of the operator shows.
  const Grid region{{17.5, 29.5}, 4.0, 64, 64};
  const Sample ratio = centre_to_vertex_variance(seed_statistics(
      region, edge_of(blended), 8, 32,
      [&](std::uint32_t seed) { return render_model(blended, region, seed, 1, false); }));
  std::cout << "centre/vertex per-pixel variance " << ratio.mean << " (se " << ratio.deviation
            << ")\n";
  EXPECT_LT(std::abs(ratio.mean - 1.105), 4.0 * ratio.deviation);
}

// The least-squares correlation of a render's slopes (channels `slopes`, `slopes` + 1: x, up) with
// the central differences of its height (channel `height`) over the interior: 1 when the normal
// map is exactly a multiple of the height's gradient.
double slope_gradient_fit(const ImageF& image, int slopes, int height) {
  double cross = 0.0, slope_squares = 0.0, gradient_squares = 0.0;
  for (int j = 1; j + 1 < image.height(); ++j)
    for (int i = 1; i + 1 < image.width(); ++i) {
      const double gradient[2] = {image.at(i + 1, j, height) - image.at(i - 1, j, height),
                                  image.at(i, j - 1, height) - image.at(i, j + 1, height)};
      for (int a = 0; a < 2; ++a) {
        const double slope = image.at(i, j, slopes + a);
        cross += slope * gradient[a];
        slope_squares += slope * slope;
        gradient_squares += gradient[a] * gradient[a];
      }
    }
  return cross / std::sqrt(slope_squares * gradient_squares);
}

// The slopes' magnitude |s| of channels `slopes`, `slopes` + 1, as a one-channel image.
ImageF slope_magnitude(const ImageF& image, int slopes) {
  ImageF out(image.width(), image.height(), 1);
  for (int j = 0; j < image.height(); ++j)
    for (int i = 0; i < image.width(); ++i)
      out.at(i, j, 0) = std::hypot(image.at(i, j, slopes), image.at(i, j, slopes + 1));
  return out;
}

TEST(TilingControls, TurnedPatchesTurnTheNormalMapsSlopes) {
  // rock_sandstone's albedo, normal map (2 slopes) and height (6 channels), with full rotation,
  // and with rotation and scale jitter, against the same material without them; 4 seeds of 512²:
  // (a) the rendered normal map stays the gradient of the rendered height: the slope-gradient fit
  // stays at the plain render's, where slopes copied unturned from turned patches would not;
  // (b) the slopes' magnitude histogram (and each other map's) stays nearer the exemplar's than
  // the Gaussian version's; (c) the normal's length.
  const test_support::ShippedMaterial rock =
      test_support::shipped_material("rock_sandstone", {"albedo", "normal", "height"});
  const std::vector<MaterialMap>& maps = rock.maps;
  const ImageF exemplar = material_exemplar(maps).exemplar;
  constexpr int kSlopes = 3;
  constexpr int kHeight = 5;
  const int channels = exemplar.channels();
  ASSERT_EQ(channels, 6);
  const ImageF exemplar_magnitude = slope_magnitude(exemplar, kSlopes);
  constexpr int kSide = 1024;
  constexpr int kSeeds = 8;
  const Model plain = analyze_material("tiling", maps);
  std::vector<double> plain_fit, gaussian_magnitude;
  std::vector<std::vector<double>> gaussian_histogram(channels);
  for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
    const Grid grid{{1000.0 * seed, -700.0 * seed}, 1.0, kSide, kSide};
    plain_fit.push_back(slope_gradient_fit(render_model(plain, grid, seed), kSlopes, kHeight));
    const ImageF gaussian = adsn(exemplar.view(), kSide, kSide, seed);
    gaussian_magnitude.push_back(
        histogram_distance(slope_magnitude(gaussian, kSlopes), exemplar_magnitude, 0));
    for (int c = 0; c < channels; ++c)
      gaussian_histogram[c].push_back(histogram_distance(gaussian, exemplar, c));
  }
  const Sample plain_sample = summarise(plain_fit);
  const Sample gaussian_sample = summarise(gaussian_magnitude);
  std::cout << "plain slope-gradient fit " << plain_sample.mean << " (sd " << plain_sample.deviation
            << "); ADSN slope magnitude W1 " << gaussian_sample.mean << "\n";
  const ParamValues controls[2] = {{{"rotation", 180.0}},
                                   {{"rotation", 180.0}, {"scale_jitter", 0.5}}};
  for (const ParamValues& control : controls) {
    const Model turned = analyze_material("tiling", maps, control);
    std::vector<double> fit, magnitude;
    std::vector<std::vector<double>> histogram(channels);
    double length_error = 0.0;
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
      const Grid grid{{1000.0 * seed, -700.0 * seed}, 1.0, kSide, kSide};
      const ImageF render = render_model(turned, grid, seed);
      fit.push_back(slope_gradient_fit(render, kSlopes, kHeight));
      magnitude.push_back(
          histogram_distance(slope_magnitude(render, kSlopes), exemplar_magnitude, 0));
      for (int c = 0; c < channels; ++c)
        histogram[c].push_back(histogram_distance(render, exemplar, c));
      for (const auto& [name, map] : split_maps(turned, render.view()))
        if (name == "normal")
          for (int j = 0; j < kSide; ++j)
            for (int i = 0; i < kSide; ++i) {
              double squares = 0.0;
              for (int c = 0; c < 3; ++c) squares += std::pow(2.0 * map.at(i, j, c) - 1.0, 2);
              length_error = std::max(length_error, std::abs(std::sqrt(squares) - 1.0));
            }
    }
    const std::string label = control.size() == 1 ? "rotation" : "rotation + scale jitter";
    // (a) Within 4 pooled standard deviations of the plain render's fit. Measured (sd over the
    // seeds): plain 0.880 (0.002), rotation 0.889 (0.001), rotation + jitter 0.890 (0.002); the
    // slopes left unturned in the turned patches gave 0.002 (0.10) and -0.001 (0.09).
    const Sample f = summarise(fit);
    std::cout << label << ": slope-gradient fit " << f.mean << " (sd " << f.deviation << ")\n";
    EXPECT_GT(f.mean, plain_sample.mean - 4.0 * pooled(f, plain_sample)) << label;
    // (b) As TilingMaterial.MapsKeepTheirHistogramsAndCrossCorrelations, beyond 4 standard
    // errors of the difference of the means; the height (features larger than a tile) by its
    // mean only. The slopes' magnitude W1 rises with rotation, turned or not (rotated patches are
    // read between texels, and bilinear interpolation smooths the high-frequency slopes): measured
    // 0.0148 (0.004) rotated, 0.0128 (0.007) with the jitter, ADSN 0.041 (about 0.006 unrotated,
    // 512² renders).
    const Sample m = summarise(magnitude);
    std::cout << label << ": slope magnitude W1 " << m.mean << " (sd " << m.deviation << ")\n";
    EXPECT_LT(m.mean + 4.0 * pooled(m, gaussian_sample) * std::sqrt(2.0 / kSeeds),
              gaussian_sample.mean)
        << label;
    for (int c = 0; c < channels; ++c) {
      // A turned patch mixes s_x and s_y: the magnitude's histogram is kept, not theirs.
      if (c == kSlopes || c == kSlopes + 1) continue;
      const Sample k = summarise(histogram[c]);
      const Sample l = summarise(gaussian_histogram[c]);
      std::cout << label << ": channel " << c << " histogram W1 " << k.mean << ", ADSN " << l.mean
                << "\n";
      EXPECT_LT(k.mean + (c == kHeight ? 0.0 : 4.0 * pooled(k, l) * std::sqrt(2.0 / kSeeds)),
                l.mean)
          << label << ", channel " << c;
    }
    // (c) normalize(-s_x, -s_y, 1), decoded from 0.5 + 0.5 n in float.
    EXPECT_LT(length_error, 1e-5) << label;
  }
  // (d) Zoomed out 8 times, the slopes' variance against the supersampled reference (16 x 16
  // point samples per pixel, same seeds): the radial table prefiltered per level keeps it, as
  // the 1-D tables do. Measured ratio (sd over 4 seeds): 0.979 (0.002), the plain material's
  // 0.992 (0.015); the level-0 table at every level gave 0.929 (0.002). Bound: 0.955, halfway,
  // more than 10 standard deviations from either.
  const Model turned = analyze_material("tiling", maps, controls[0]);
  const Grid minified{{40.0, -90.0}, 8.0, 64, 64};
  const auto slope_variance = [](const ImageF& image) {
    double total = 0.0;
    for (int c = kSlopes; c < kSlopes + 2; ++c) {
      double sum = 0.0, squares = 0.0;
      for (int j = 0; j < image.height(); ++j)
        for (int i = 0; i < image.width(); ++i) {
          sum += image.at(i, j, c);
          squares += image.at(i, j, c) * image.at(i, j, c);
        }
      const double n = static_cast<double>(image.width()) * image.height();
      total += squares / n - (sum / n) * (sum / n);
    }
    return total;
  };
  std::vector<double> ratio;
  for (std::uint32_t seed = 1; seed <= 4; ++seed)
    ratio.push_back(slope_variance(render_model(turned, minified, seed)) /
                    slope_variance(render_model(turned, minified, seed, 16)));
  const Sample minified_ratio = summarise(ratio);
  std::cout << "minified slope variance / supersampled " << minified_ratio.mean << " (sd "
            << minified_ratio.deviation << ")\n";
  EXPECT_GT(minified_ratio.mean, 0.955);
}

TEST(TilingFiltering, MinifiedRenderMatchesTheSupersampledReference) {
  // render --scale 8 against --supersample 16 (16 x 16 point samples per pixel), same seeds, on a
  // strongly non-Gaussian exemplar (sparse bright caustics: its mean and median differ). Three
  // filters: ours (mip level of G from the footprint taken before the offsets, section 5.4, and
  // T^-1 prefiltered per level), the same mip fetch with the unfiltered T^-1 (the paper's shader:
  // a minified fetch then maps towards the median), and point samples (aliasing).
  // Both transports: the 3-D table of the sliced transport and the 1-D tables of the per-channel
  // one (the default), each prefiltered per level.
  const ImageF exemplar = read_image(kTextureDir + "/water_caustics_256.png");
  for (const double transport : {0.0, 1.0}) {
    // The exemplar as is (make_tileable off), as measured below: the filters are this test's
    // subject. Made tileable, the margin of the last bound is thinner (ours 0.146 against 0.284
    // unfiltered).
    const Model model =
        analyze("tiling", exemplar.view(), {{"make_tileable", 0}, {"transport", transport}}, 0);
    const tiling::TilingModel& tiling = std::get<tiling::TilingModel>(model.data().model);
    constexpr int kSize = 64;
    constexpr double kScale = 8.0;
    constexpr int kRepeats = 3;
    const Grid grid{{0.0, 0.0}, kScale, kSize, kSize};
    const auto total_variance = [](const ImageF& image) {
      const ColourStatistics stats = colour_statistics(image.view());
      return stats.covariance[0] + stats.covariance[4] + stats.covariance[8];
    };
    double variance[4] = {}, mean_gap[3] = {}, spectral[3] = {}, mean_noise = 0.0;
    for (std::uint32_t seed = 1; seed <= kRepeats; ++seed) {
      const ImageF reference = render_model(model, grid, seed, 16);
      ImageF naive(kSize, kSize, 3);
      const Footprint footprint{{kScale, 0.0}, {0.0, kScale}};
      for (int j = 0; j < kSize; ++j)
        for (int i = 0; i < kSize; ++i) {
          float g[3];
          tiling.blended_gaussian({kScale * (i + 0.5), kScale * (j + 0.5)},
                                  tiling::TilingModel::footprint_width(&footprint), seed, g);
          tiling.inverse_transform(g, {}, &naive.at(i, j, 0));
        }
      const ImageF images[3] = {render_model(model, grid, seed), naive,
                                render_model(model, grid, seed, 1, false)};
      const ColourStatistics r = colour_statistics(reference.view());
      for (int k = 0; k < 3; ++k) {
        variance[k] += total_variance(images[k]) / kRepeats;
        mean_gap[k] += mean_error(colour_statistics(images[k].view()), r) / kRepeats;
        spectral[k] += spectral_error(images[k].view(), reference.view(), 16) / kRepeats;
      }
      variance[3] += total_variance(reference) / kRepeats;
      // Standard error of a 64 x 64 image mean of the reference, pixels taken as independent (the
      // filtered field decorrelates within about one output pixel).
      mean_noise += std::sqrt(total_variance(reference) / (kSize * kSize)) / kRepeats;
    }
    std::cout << "transport " << transport << ", scale 8 against supersampled: variance ours "
              << variance[0] << ", unfiltered T^-1 " << variance[1] << ", point samples "
              << variance[2] << ", reference " << variance[3] << "; mean gap " << mean_gap[0]
              << ", " << mean_gap[1] << ", " << mean_gap[2] << " (noise " << mean_noise
              << "); spectral error " << spectral[0] << ", " << spectral[1] << ", " << spectral[2]
              << "\n";
    // Measured (3 seeds), sliced transport: mean gap 0.0013 ours, 0.029 with the unfiltered T^-1
    // (noise 0.0021); variance ratio to the reference 0.88 ours, 1.67 point samples; spectral
    // error 0.14 ours, 0.28 unfiltered T^-1, 0.74 point samples. Per-channel transport: mean gap
    // 0.0062 ours, 0.013 unfiltered (noise 0.0025); variance ratio 0.96 ours, 1.42 point samples;
    // spectral error 0.058 ours, 0.096 unfiltered, 0.44 point samples: its 1-D tables are
    // smooth, so the unfiltered T^-1 errs less in the spectrum than the 3-D table's (0.28) and the
    // prefiltered one gains less than half of it.
    EXPECT_LT(mean_gap[0], 4.0 * mean_noise) << "transport " << transport;
    // The median, not the mean: what prefiltering fixes.
    EXPECT_GT(mean_gap[1], 4.0 * mean_noise) << "transport " << transport;
    EXPECT_NEAR(variance[0] / variance[3], 1.0, 0.2) << "transport " << transport;
    EXPECT_GT(variance[2] / variance[3], transport == 0.0 ? 1.5 : 1.3) << "transport " << transport;
    EXPECT_LT(spectral[0], 0.25) << "transport " << transport;
    if (transport == 0.0) {
      EXPECT_LT(spectral[0], 0.5 * spectral[1]);
    }
  }
}

TEST(TilingGaussian, FastPathReproducesARandomPhaseTexture) {
  // Section 6.1 (figures 10-11): a Gaussian (random-phase) input needs no T or T^-1. The input is
  // an ADSN sample of grass; the tiling output must sit at the spectral and histogram level of
  // ADSN samples of the same input, within 4 pooled deviations of one measurement. Measured
  // (6 seeds): spectral error 0.30 (sd 0.05) against ADSN's 0.32 (sd 0.002), sliced W2 0.00049
  // against 0.00092. The test can fail: linear blending (blend=2) of the same input measured 0.51
  // and 0.011 (`stochtex compare`, one seed).
  const ImageF grass = read_image(kTextureDir + "/grass_lawn_256.png");
  const ImageF exemplar = adsn(grass.view(), 256, 256, 1000);
  const Model model = analyze("tiling", exemplar.view(), {{"blend", 1}}, 0);
  const int crop = welch_crop_size(exemplar.view(), exemplar.view());
  std::vector<double> ours_spectral, adsn_spectral, ours_histogram, adsn_histogram;
  for (std::uint32_t seed = 1; seed <= 6; ++seed) {
    const ImageF noise = render_model(model, Grid{{0.0, 0.0}, 1.0, 256, 256}, seed);
    const ImageF gaussian = adsn(exemplar.view(), 256, 256, seed);
    ours_spectral.push_back(spectral_error(noise.view(), exemplar.view(), crop));
    adsn_spectral.push_back(spectral_error(gaussian.view(), exemplar.view(), crop));
    ours_histogram.push_back(sliced_wasserstein(noise.view(), exemplar.view(), kDirections));
    adsn_histogram.push_back(sliced_wasserstein(gaussian.view(), exemplar.view(), kDirections));
  }
  const Sample os = summarise(ours_spectral), as = summarise(adsn_spectral);
  const Sample oh = summarise(ours_histogram), ah = summarise(adsn_histogram);
  std::cout << "Gaussian input: spectral error tiling " << os.mean << " (sd " << os.deviation
            << "), ADSN " << as.mean << " (sd " << as.deviation << "); sliced W2 tiling " << oh.mean
            << " (sd " << oh.deviation << "), ADSN " << ah.mean << " (sd " << ah.deviation << ")\n";
  const Sample spectral_gap = pooled_gap(os, as);
  const Sample histogram_gap = pooled_gap(oh, ah);
  EXPECT_LT(spectral_gap.mean, 4.0 * spectral_gap.deviation);
  EXPECT_LT(histogram_gap.mean, 4.0 * histogram_gap.deviation);
}

}  // namespace
}  // namespace stochtex::tiling_quality_test
