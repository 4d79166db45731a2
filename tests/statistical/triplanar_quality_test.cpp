// Triplanar histogram-preserving blending (figure 16 of "High-Performance By-Example Noise using
// a Histogram-Preserving Blending Operator", Heitz and Neyret, HPG 2018) against linear triplanar
// mapping: where the projections overlap, linear blending of independent planes lowers the
// variance by sum w_k^2 and moves the colour histogram towards the mean; the Gaussianised blend
// and one T^-1 look-up keep both as where one projection dominates.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "io/image_io.hpp"
#include "metrics/metrics.hpp"
#include "statistics.hpp"
#include "stochtex/stochtex.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::triplanar_quality_test {
namespace {

const std::string kTextureDir = STOCHTEX_TEXTURE_DIR;

using test_support::Sample;
using test_support::summarise;

Vec3d normalised(Vec3d v) {
  const double length = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return {v.x / length, v.y / length, v.z / length};
}

Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// `count` points of the plane through the origin with this normal, uniform over a square of
// `extent` pixels (many exemplar periods), point samples (zero footprint: the statistics are
// those of the unfiltered noise). Random rather than on a grid: with a grid one pixel apart, a
// 45-degree plane's projections fell on whole pixels along one axis and fractions along the
// other, and their bilinear reads had 13% less variance than an axis plane's (grass, linear and
// histogram-preserving alike): an artefact of the grid, not of the blending.
std::vector<SurfacePoint> plane_points(Vec3d normal, int count, double extent) {
  const Vec3d n = normalised(normal);
  const Vec3d u =
      normalised(cross(std::abs(n.x) < 0.9 ? Vec3d{1.0, 0.0, 0.0} : Vec3d{0.0, 1.0, 0.0}, n));
  const Vec3d v = cross(n, u);
  std::mt19937 engine(3);
  std::uniform_real_distribution<double> uniform(0.0, extent);
  std::vector<SurfacePoint> points;
  for (int k = 0; k < count; ++k) {
    const double a = uniform(engine);
    const double b = uniform(engine);
    points.push_back({{a * u.x + b * v.x, a * u.y + b * v.y, a * u.z + b * v.z}, n, u, {}, {}});
  }
  return points;
}

double total_variance(const ImageF& image) {
  const ColourStatistics statistics = colour_statistics(image.view());
  double sum = 0.0;
  const auto channels = static_cast<std::size_t>(image.channels());
  for (std::size_t c = 0; c < channels; ++c) sum += statistics.covariance[c * channels + c];
  return sum;
}

struct PlaneCase {
  const char* name;
  Vec3d normal;
};

// sum_k w_k^2 for the weights |n_k|^4 / sum (SurfaceOptions' default sharpness): the variance
// factor of linear blending of independent planes.
double weight_squares(Vec3d normal) {
  const Vec3d n = normalised(normal);
  const std::array<double, 3> w = {std::pow(n.x, 4.0), std::pow(n.y, 4.0), std::pow(n.z, 4.0)};
  const double total = w[0] + w[1] + w[2];
  return (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) / (total * total);
}

// Measured over 8 seeds (per-seed standard deviations, grass_lawn_256 / metal_grey_256): variance
// ratio 0.002-0.011, SW2 0.00006-0.0027. Every bound below is 4 standard deviations of the
// difference of two 8-seed means, 4 sqrt(2 / 8) times the pooled per-seed deviation, from the
// deviations this run measures. Measured means (variance / exemplar's; SW2):
//   grass: triplanar 0.613 / 0.614 / 0.614, 0.0099 / 0.0099 / 0.0099;
//          linear 0.611 / 0.307 / 0.205, 0.0100 / 0.0200 / 0.0245 (dominant / two / three);
//   metal: triplanar 0.905 / 0.895 / 0.898, 0.019 / 0.021 / 0.020;
//          linear 0.894 / 0.451 / 0.301, 0.021 / 0.096 / 0.126.
TEST(TilingTriplanarQuality, OverlapKeepsVarianceAndHistogramWhereLinearLosesThem) {
  // Dominant: the (x, y) plane's weight is 0.998 at sharpness 4. Two: w = (1/2, 1/2, 0). Three:
  // w = 1/3 each.
  const std::array<PlaneCase, 3> planes = {
      {{"dominant", {0.2, 0.1, 1.0}}, {"two", {1.0, 1.0, 0.0}}, {"three", {1.0, 1.0, 1.0}}}};
  constexpr int kSeeds = 8;
  constexpr int kSide = 384;
  const auto tolerance = [&](const Sample& a, const Sample& b) {
    return 4.0 * std::sqrt(2.0 / kSeeds) * test_support::pooled(a, b);
  };
  for (const char* name : {"grass_lawn_256.png", "metal_grey_256.png"}) {
    const ImageF exemplar = read_image(kTextureDir + "/" + name);
    // The radius these numbers were measured at (the default chooses 1/4 for both exemplars).
    const Model model = analyze("tiling", exemplar.view(), {{"tile_radius", 0.5}}, 0);
    const double exemplar_variance = total_variance(exemplar);
    // [mapping][plane]: variance / the exemplar's, and sliced Wasserstein-2 to the exemplar.
    std::array<std::array<Sample, 3>, 2> variance;
    std::array<std::array<Sample, 3>, 2> histogram;
    for (int mapping = 0; mapping < 2; ++mapping)
      for (std::size_t p = 0; p < planes.size(); ++p) {
        const std::vector<SurfacePoint> points =
            plane_points(planes[p].normal, kSide * kSide, 2000.0);
        SurfaceOptions options;
        options.mapping =
            mapping == 0 ? SurfaceMapping::triplanar : SurfaceMapping::triplanar_linear;
        std::vector<double> ratios;
        std::vector<double> distances;
        for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
          ImageF out(kSide, kSide, model.channels());
          evaluate_surface(model, points, options, seed, out.view());
          ratios.push_back(total_variance(out) / exemplar_variance);
          distances.push_back(sliced_wasserstein(out.view(), exemplar.view(), 16));
        }
        variance[mapping][p] = summarise(ratios);
        histogram[mapping][p] = summarise(distances);
        std::cout << name << " " << (mapping == 0 ? "triplanar" : "linear") << " " << planes[p].name
                  << ": variance / exemplar " << variance[mapping][p].mean << " (sd "
                  << variance[mapping][p].deviation << "), SW2 " << histogram[mapping][p].mean
                  << " (sd " << histogram[mapping][p].deviation << ")\n";
      }
    for (std::size_t p = 1; p < planes.size(); ++p) {
      // Histogram-preserving: the overlap is the dominant plane's noise in variance and histogram.
      EXPECT_NEAR(variance[0][p].mean, variance[0][0].mean,
                  tolerance(variance[0][p], variance[0][0]))
          << name << " " << planes[p].name;
      EXPECT_NEAR(histogram[0][p].mean, histogram[0][0].mean,
                  tolerance(histogram[0][p], histogram[0][0]))
          << name << " " << planes[p].name;
      // Linear: the variance drops by sum w^2 (relative to the dominant plane's, itself 0.997),
      // and the histogram moves away from the exemplar's far beyond the noise.
      const double expected = weight_squares(planes[p].normal) / weight_squares(planes[0].normal);
      const double ratio = variance[1][p].mean / variance[1][0].mean;
      const double ratio_tolerance = 4.0 * std::sqrt(1.0 / kSeeds) * ratio *
                                     std::hypot(variance[1][p].deviation / variance[1][p].mean,
                                                variance[1][0].deviation / variance[1][0].mean);
      std::cout << name << " linear " << planes[p].name << ": variance ratio " << ratio
                << " (sum w^2 " << expected << ", tolerance " << ratio_tolerance << ")\n";
      EXPECT_NEAR(ratio, expected, ratio_tolerance) << name << " " << planes[p].name;
      EXPECT_GT(histogram[1][p].mean,
                histogram[0][p].mean + 10.0 * tolerance(histogram[1][p], histogram[0][p]))
          << name << " " << planes[p].name;
    }
  }
}

}  // namespace
}  // namespace stochtex::triplanar_quality_test
