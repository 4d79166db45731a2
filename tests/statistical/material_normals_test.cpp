// A material's normal map derived from its synthesised height (docs/materials.md): the
// Gaussian-model methods render normals that follow their own height, with the slope scale
// calibrated so that the rendered slopes have the exemplar's mean squared slope
// (with_calibrated_slopes in src/material.cpp).

#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "statistics.hpp"
#include "stochtex/io.hpp"
#include "stochtex/material.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::material_normals_test {
namespace {

using test_support::Sample;
using test_support::summarise;

constexpr int kSide = 256;
constexpr int kSeeds = 4;

// The root mean square slope |s| of a normal map encoded 0.5 + 0.5 n.
double rms_slope(const ImageF& normal) {
  double sum = 0.0;
  for (int y = 0; y < normal.height(); ++y)
    for (int x = 0; x < normal.width(); ++x) {
      const double nx = 2.0 * normal.at(x, y, 0) - 1.0;
      const double ny = 2.0 * normal.at(x, y, 1) - 1.0;
      const double nz = 2.0 * normal.at(x, y, 2) - 1.0;
      sum += (nx * nx + ny * ny) / (nz * nz);
    }
  return std::sqrt(sum / (static_cast<double>(normal.width()) * normal.height()));
}

TEST(MaterialNormals, DerivedSlopesHaveTheExemplarsMeanSquare) {
  const std::string folder = std::string(STOCHTEX_MATERIAL_DIR) + "/rock_sandstone/";
  const ImageF normal = read_image(folder + "normal.png");
  const ImageF height = read_image(folder + "height.png");
  const std::vector<MaterialMap> maps{{"normal", {}, normal.view(), "normal.png"},
                                      {"height", {}, height.view(), "height.png"}};
  const double target = rms_slope(normal);
  for (const std::string method : {"texton", "lrp", "gabor"}) {
    const Model model = analyze_material(method, maps);
    ASSERT_EQ(model.maps()[0].derived_from, "height") << method;
    std::vector<double> ratios;
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
      const Grid grid{{1000.0 * seed, 300.0 * seed}, 1.0, kSide, kSide};
      const auto parts = render_maps(model, grid, [&](const Grid& part, ImageView<float> out) {
        render(model, part, seed, out);
      });
      ratios.push_back(rms_slope(parts[0].image) / target);
    }
    // The calibration measured the model's height on one 256² render of seed 0, which scatters
    // like each of these renders (other seeds and places): the mean ratio lies within 4 standard
    // deviations of that combined noise of 1, sqrt(sd^2 / seeds + sd^2), sd the spread of one
    // 256² render's ratio over the seeds. Measured (rock): texton 1.01 +- 0.01, lrp 0.96 +- 0.05,
    // gabor 1.02 +- 0.03; the least-squares scale alone gave lrp 2.8 and gabor 0.7 (mean |s|
    // 1.47 and 0.37 against the exemplar's 0.52).
    const Sample ratio = summarise(ratios);
    std::cout << std::setprecision(3) << method << ": rms slope / exemplar's " << ratio.mean
              << " +- " << ratio.deviation << "\n";
    EXPECT_LE(std::abs(ratio.mean - 1.0), 4.0 * ratio.deviation * std::sqrt(1.0 + 1.0 / kSeeds))
        << method;
  }
}

}  // namespace
}  // namespace stochtex::material_normals_test
