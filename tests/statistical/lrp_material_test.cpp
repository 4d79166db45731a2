// Local random-phase noise on whole materials (issue 18): the maps of a shipped material set side
// by side, analysed jointly by one PCA over all N channels, one noise per principal component
// (Gilet et al. 2014, "Local random-phase noise for procedural texturing", ACM TOG 33(6),
// DOI 10.1145/2661229.2661249, section 6: colour in a decorrelated space), mixed back by the
// N x N basis. The zero-lag covariance between maps is kept in expectation; what the independent
// components lose, the lagged cross-correlation between maps, is measured and printed for
// docs/methods/lrp.md.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "statistics.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::lrp_material_test {
namespace {

using test_support::material_exemplar;
using test_support::Sample;
using test_support::summarise;

constexpr int kSize = 256;
constexpr int kSeeds = 8;

// Pearson correlation of channels i and j of `image`, channel j read `lag` pixels to the right
// (over the columns where both exist).
double correlation(const ImageF& image, int i, int j, int lag = 0) {
  double mean_i = 0.0, mean_j = 0.0;
  const int width = image.width() - lag;
  const double count = static_cast<double>(width) * image.height();
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < width; ++x) {
      mean_i += image.at(x, y, i);
      mean_j += image.at(x + lag, y, j);
    }
  mean_i /= count;
  mean_j /= count;
  double cross = 0.0, square_i = 0.0, square_j = 0.0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < width; ++x) {
      const double a = image.at(x, y, i) - mean_i;
      const double b = image.at(x + lag, y, j) - mean_j;
      cross += a * b;
      square_i += a * a;
      square_j += b * b;
    }
  return cross / std::sqrt(square_i * square_j);
}

struct Material {
  const char* set;
  std::vector<std::string> maps;
  // Cross-map correlations of the exemplar to keep (COMMON notes of issue 18): channel pairs and
  // the measured exemplar value, to +-0.02.
  std::vector<std::array<int, 2>> pairs;
  std::vector<double> expected;
};

TEST(LrpMaterial, RenderedCorrelationMatrixMatchesTheExemplars) {
  // rock_sandstone: albedo RGB 0-2, normal RGB 3-5, roughness 6, height 7, ao 8 (9 channels);
  // sand_pebbles: albedo 0-2, normal 3-5, roughness 6, metallic 7 (8 channels).
  const std::vector<Material> materials = {
      {"rock_sandstone",
       {"albedo", "normal", "roughness", "height", "ao"},
       {{1, 4}, {7, 8}},
       {0.88, 0.65}},
      {"sand_pebbles", {"albedo", "normal", "roughness", "metallic"}, {{6, 7}}, {-0.87}},
  };
  for (const Material& material : materials) {
    const ImageF exemplar = material_exemplar(material.set, material.maps);
    const int n = exemplar.channels();
    const Model model = analyze("lrp", exemplar.view(), {}, 0);
    ASSERT_EQ(model.channels(), n);
    // Per pair (i < j): the correlation in each of kSeeds renders.
    std::vector<std::vector<double>> rendered(static_cast<std::size_t>(n * n));
    // The limit of the method: corr(x_i(p), x_j(p + 2 px right)) minus the same with i and j
    // swapped. Independent components have even cross-covariances, so a render's asymmetry is 0
    // in expectation; the exemplar's (height against the normal's x slope) is not.
    const int lag = 2;
    std::vector<double> rendered_asymmetry;
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
      ImageF out(kSize, kSize, n);
      render(model, Grid{{0.0, 0.0}, 1.0, kSize, kSize}, seed, out.view());
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
          rendered[static_cast<std::size_t>(i * n + j)].push_back(correlation(out, i, j));
      if (std::string(material.set) == "rock_sandstone")
        rendered_asymmetry.push_back(correlation(out, 7, 3, lag) - correlation(out, 3, 7, lag));
    }
    double worst_z = 0.0;
    double worst_error = 0.0;
    double error_sum = 0.0;
    double spread_sum = 0.0;
    int pairs = 0;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        const double target = correlation(exemplar, i, j);
        const Sample sample = summarise(rendered[static_cast<std::size_t>(i * n + j)]);
        const double error = std::abs(sample.mean - target);
        // The mean of kSeeds renders has the standard error deviation / sqrt(kSeeds); the floor
        // covers a pair whose renders barely vary (a nearly constant map).
        const double standard_error = std::max(sample.deviation / std::sqrt(double(kSeeds)), 1e-3);
        worst_z = std::max(worst_z, error / standard_error);
        worst_error = std::max(worst_error, error);
        error_sum += error;
        spread_sum += sample.deviation;
        ++pairs;
        // The zero-lag covariance is kept in expectation (one PCA over all channels, each
        // component's noise with the component's exact variance): the mean over seeds is off by
        // its own standard error only. Measured over these 8 seeds: largest |z| 2.4 (rock, 36
        // pairs) and 2.1 (sand, 28 pairs), one render's sd 0.005-0.06 per pair; 5 standard
        // errors leaves room for the 64 comparisons. A colour/rest block-diagonal PCA fails it:
        // albedo against normal.y (0.88) would render near 0, hundreds of standard errors away.
        EXPECT_LT(error, 5.0 * standard_error)
            << material.set << " channels " << i << ", " << j << ": exemplar " << target
            << ", renders " << sample.mean << " +- " << sample.deviation;
      }
    std::cout << std::setprecision(3) << material.set << " (" << n << " channels, " << pairs
              << " pairs): correlation error mean " << error_sum / pairs << ", largest "
              << worst_error << ", largest z " << worst_z << "; one render's spread (mean sd) "
              << spread_sum / pairs << "\n";
    for (std::size_t p = 0; p < material.pairs.size(); ++p) {
      const auto [i, j] = material.pairs[p];
      const double target = correlation(exemplar, i, j);
      const Sample sample = summarise(rendered[static_cast<std::size_t>(i * n + j)]);
      std::cout << "  channels " << i << ", " << j << ": exemplar " << target << ", renders "
                << sample.mean << " +- " << sample.deviation << "\n";
      // The values quoted in the issue, measured on the exemplar to two digits.
      EXPECT_NEAR(target, material.expected[p], 0.02) << material.set;
      // Kept by the renders to the bound above and, in sign and size, to 0.1.
      EXPECT_NEAR(sample.mean, material.expected[p], 0.1) << material.set;
    }
    if (!rendered_asymmetry.empty()) {
      const double exemplar_asymmetry =
          correlation(exemplar, 7, 3, lag) - correlation(exemplar, 3, 7, lag);
      const Sample sample = summarise(rendered_asymmetry);
      std::cout << "  lagged cross-correlation (height, normal x) at +" << lag << " px minus -"
                << lag << " px: exemplar " << exemplar_asymmetry << ", renders " << sample.mean
                << " +- " << sample.deviation << "\n";
      // Not kept: the renders' asymmetry is 0 to its noise (measured -0.002 +- 0.013 over the 8
      // renders, z = 0.5) while the exemplar's is 0.16. This fails if the method starts keeping
      // lagged cross-spectra (then update docs/methods/lrp.md, "Materials").
      EXPECT_LT(std::abs(sample.mean), 4.0 * sample.deviation / std::sqrt(double(kSeeds)) + 0.01);
      EXPECT_GT(std::abs(exemplar_asymmetry), 0.1);
    }
  }
}

}  // namespace
}  // namespace stochtex::lrp_material_test
