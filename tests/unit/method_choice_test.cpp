#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>

#include "metrics/metrics.hpp"
#include "metrics/structure.hpp"
#include "stochtex/io.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::method_choice_test {
namespace {

ImageF shipped(const char* name) {
  return read_image(std::filesystem::path(STOCHTEX_TEXTURE_DIR) / name);
}

ImageF gaussian_white_noise(int side, std::uint32_t seed) {
  ImageF image(side, side, 1);
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.5f, 0.1f);
  for (float& value : image.pixels()) value = normal(rng);
  return image;
}

TEST(StructureMeasures, BandsReachASixtyFourthOfTheSmallerSide) {
  EXPECT_EQ(kurtosis_bands(16, 16), 1);
  EXPECT_EQ(kurtosis_bands(128, 128), 2);
  EXPECT_EQ(kurtosis_bands(512, 256), 3);
  EXPECT_EQ(kurtosis_bands(512, 512), 4);
}

// Any linear filter of Gaussian noise is Gaussian: kurtosis 3 in every band, no spectral peak.
TEST(StructureMeasures, GaussianNoiseMeasuresGaussian) {
  const ImageF noise = gaussian_white_noise(256, 3);
  for (const double kurtosis : band_kurtosis(noise.view(), kurtosis_bands(256, 256)))
    EXPECT_NEAR(kurtosis, 3.0, 0.15);
  EXPECT_LT(spectral_peak_fraction(noise.view()), 0.01);
}

// Sparse bright dots: each band's energy sits on a few pixels. A grating: its power in one peak.
TEST(StructureMeasures, DotsAreFarFromGaussianAndAGratingIsPeaked) {
  ImageF dots(128, 128, 1);
  std::mt19937 rng(5);
  for (int k = 0; k < 60; ++k)
    dots.at(static_cast<int>(rng() % 128), static_cast<int>(rng() % 128), 0) = 1.0f;
  EXPECT_GT(band_kurtosis(dots.view(), 1)[0], 20.0);
  ImageF grating = gaussian_white_noise(128, 7);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x)
      grating.at(x, y, 0) += 0.3f * static_cast<float>(std::sin(2.0 * std::numbers::pi * x / 8.0));
  EXPECT_GT(spectral_peak_fraction(grating.view()), 0.5);
}

// The choices docs/comparison.md's table records, which its pictures support: tiling keeps the
// bricks' courses and the plaid's checks that the Gaussian methods turn into blur; the grass and
// the brushed metal are Gaussian textures, which texton reproduces.
TEST(MethodChoice, ShippedExemplarsGetTheMethodTheirPicturesSupport) {
  const MethodChoice bricks = choose_method(shipped("bricks_stone_wall_512.png").view());
  EXPECT_EQ(bricks.method, "tiling");
  EXPECT_GT(bricks.band_kurtosis, 4.4);
  EXPECT_TRUE(
      bricks.reason.starts_with("tiling: far from Gaussian (band-pass kurtosis 4.6 at 1 px"))
      << bricks.reason;
  EXPECT_NEAR(bricks.wrap_step, 2.71, 0.01);

  const MethodChoice plaid = choose_method(shipped("plaid_fabric_256.png").view());
  EXPECT_EQ(plaid.method, "tiling");
  EXPECT_LT(plaid.band_kurtosis, 3.5);
  EXPECT_GT(plaid.peak_fraction, 0.5);
  EXPECT_TRUE(plaid.reason.starts_with("tiling: periodic (")) << plaid.reason;

  const MethodChoice grass = choose_method(shipped("grass_lawn_128.png").view());
  EXPECT_EQ(grass.method, "texton");
  EXPECT_NEAR(grass.band_kurtosis, 3.0, 0.2);
  EXPECT_TRUE(grass.reason.starts_with("texton: close to Gaussian (")) << grass.reason;

  const MethodChoice metal = choose_method(shipped("brushed_aluminium_grey_256.png").view());
  EXPECT_EQ(metal.method, "texton");
  EXPECT_GT(metal.wrap_step, kTileableWrapStep);
  EXPECT_EQ(metal.reason.find('\n'), std::string::npos);
}

TEST(MethodChoice, IsDeterministic) {
  const ImageF grass = shipped("grass_lawn_128.png");
  const MethodChoice a = choose_method(grass.view());
  const MethodChoice b = choose_method(grass.view());
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(a.band_kurtosis, b.band_kurtosis);
  EXPECT_EQ(a.peak_fraction, b.peak_fraction);
}

}  // namespace
}  // namespace stochtex::method_choice_test
