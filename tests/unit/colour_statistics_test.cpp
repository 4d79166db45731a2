#include "core/colour_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "spectral/principal_components.hpp"

namespace stochtex::colour_statistics_test {
namespace {

ImageF random_image(int width, int height, int channels, std::uint32_t seed) {
  std::mt19937 rng(seed);
  ImageF image(width, height, channels);
  for (float& value : image.pixels()) value = static_cast<float>(rng() % 1000) / 37.0f;
  return image;
}

TEST(ChannelStatistics, AFloatMeanCentresAboutItself) {
  // Channel values {0, 1, 1}: the mean 2/3 is not a float, so the model's float mean m and the
  // double mean give different covariances; the float one is that of the values minus m.
  ImageF image(3, 1, 1);
  image.at(1, 0, 0) = 1.0f;
  image.at(2, 0, 0) = 1.0f;
  const std::vector<double> mean = channel_means(image.view());
  const std::vector<float> float_mean = {static_cast<float>(mean[0])};
  const double m = float_mean[0];
  const double expected = (m * m + (1.0 - m) * (1.0 - m) + (1.0 - m) * (1.0 - m)) / 3.0;
  EXPECT_EQ(channel_covariance(image.view(), float_mean)[0], expected);
  EXPECT_DOUBLE_EQ(channel_covariance(image.view(), mean)[0], 2.0 / 9.0);
  EXPECT_NE(channel_covariance(image.view(), mean)[0], expected);
}

TEST(ChannelStatistics, VariancesAreTheCovarianceDiagonal) {
  const ImageF image = random_image(7, 5, 3, 11);
  const std::vector<double> mean = channel_means(image.view());
  const std::vector<double> covariance = channel_covariance(image.view(), mean);
  const std::vector<double> variances = channel_variances(image.view(), mean);
  ASSERT_EQ(variances.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(variances[i], covariance[i * 3 + i]);
    EXPECT_GT(variances[i], 0.0);
    for (std::size_t j = 0; j < 3; ++j) EXPECT_EQ(covariance[i * 3 + j], covariance[j * 3 + i]);
  }
}

TEST(PrincipalComponents, IncreasingVariancesAndUnitAxesAsColumns) {
  const PrincipalComponents pair = principal_components(std::vector<double>{2.0, 1.0, 1.0, 2.0}, 2);
  ASSERT_EQ(pair.variances.size(), 2u);
  EXPECT_NEAR(pair.variances[0], 1.0, 1e-12);
  EXPECT_NEAR(pair.variances[1], 3.0, 1e-12);
  // Column 1 (the larger variance) is +-(1, 1) / sqrt(2).
  EXPECT_NEAR(std::abs(pair.axes[0 * 2 + 1]), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(pair.axes[0 * 2 + 1], pair.axes[1 * 2 + 1], 1e-12);

  // A colour covariance: every column k is a unit eigenvector of variances[k], in increasing order.
  const ImageF image = random_image(9, 6, 3, 5);
  const std::vector<double> covariance =
      channel_covariance(image.view(), channel_means(image.view()));
  const PrincipalComponents components = principal_components(covariance, 3);
  for (std::size_t k = 0; k < 3; ++k) {
    if (k > 0) {
      EXPECT_LT(components.variances[k - 1], components.variances[k]);
    }
    double norm = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      double product = 0.0;
      for (std::size_t j = 0; j < 3; ++j)
        product += covariance[c * 3 + j] * components.axes[j * 3 + k];
      EXPECT_NEAR(product, components.variances[k] * components.axes[c * 3 + k], 1e-9);
      norm += components.axes[c * 3 + k] * components.axes[c * 3 + k];
    }
    EXPECT_NEAR(norm, 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace stochtex::colour_statistics_test
