#include "report/pictures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "metrics/metrics.hpp"

namespace stochtex::pictures_test {
namespace {

TEST(SpectrumPicture, ACosineLightsItsTwoFrequenciesAroundTheCentre) {
  constexpr int crop = 32;
  constexpr int fx = 5;
  constexpr int fy = 3;
  ImageF image(96, 96, 1);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      image.at(x, y, 0) = static_cast<float>(
          0.5 + 0.25 * std::cos(2.0 * std::numbers::pi * (fx * x + fy * y) / crop));
  const std::vector<double> spectrum = welch_power_spectrum(image.view(), crop);
  // Three decades below the peak: the float FFT's rounding noise elsewhere stays black.
  const double peak = std::log10(*std::max_element(spectrum.begin(), spectrum.end()));
  const ImageF picture = spectrum_picture(spectrum, crop, {peak - 3.0, peak});
  ASSERT_EQ(picture.width(), crop);
  ASSERT_EQ(picture.height(), crop);
  ASSERT_EQ(picture.channels(), 1);
  // The peak (the maximum, white) at +-(fx, fy) from the centre pixel (16, 16).
  EXPECT_FLOAT_EQ(picture.at(crop / 2 + fx, crop / 2 + fy, 0), 1.0f);
  EXPECT_FLOAT_EQ(picture.at(crop / 2 - fx, crop / 2 - fy, 0), 1.0f);
  // Far from the peaks the windowed cosine has no energy at all: black.
  EXPECT_FLOAT_EQ(picture.at(crop / 2 - fx, crop / 2 + fy, 0), 0.0f);
  EXPECT_FLOAT_EQ(picture.at(0, 0, 0), 0.0f);
}

TEST(SpectrumPicture, GreyLevelIsLinearInTheLogarithm) {
  // Powers 1, 10, 100, 1000 on a 2x2 spectrum, range 0..3 decades: levels 0, 1/3, 2/3, 1, with
  // the DC (index 0) moved to the centre pixel (1, 1).
  const std::vector<double> spectrum{1.0, 10.0, 100.0, 1000.0};
  const ImageF picture = spectrum_picture(spectrum, 2, {0.0, 3.0});
  EXPECT_NEAR(picture.at(1, 1, 0), 0.0f, 1e-6f);
  EXPECT_NEAR(picture.at(0, 1, 0), 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(picture.at(1, 0, 0), 2.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(picture.at(0, 0, 0), 1.0f, 1e-6f);
  EXPECT_THROW(spectrum_picture(spectrum, 3, {0.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(spectrum_picture(spectrum, 2, {1.0, 1.0}), std::invalid_argument);
}

TEST(SpectrumRange, FromTheOnePercentQuantileToTheMaximum) {
  std::vector<double> spectrum;
  for (int i = 1; i <= 200; ++i) spectrum.push_back(i);
  spectrum.push_back(0.0);  // zeros (the DC after mean removal) are left out
  const SpectrumRange range = spectrum_range(spectrum);
  EXPECT_DOUBLE_EQ(range.low, std::log10(3.0));  // index 200 / 100 = 2 of 1..200
  EXPECT_DOUBLE_EQ(range.high, std::log10(200.0));
  // A flat spectrum still gets one decade.
  const SpectrumRange flat = spectrum_range(std::vector<double>(16, 5.0));
  EXPECT_DOUBLE_EQ(flat.high - flat.low, 1.0);
  EXPECT_THROW(spectrum_range(std::vector<double>(4, 0.0)), std::invalid_argument);
}

TEST(ColourHistogram, FractionsPerChannelWithOutOfRangeValuesInTheEndBins) {
  ImageF image(4, 1, 2);
  const float values[4][2] = {{0.1f, -1.0f}, {0.1f, 0.6f}, {0.9f, 2.0f}, {0.6f, NAN}};
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 2; ++c) image.at(x, 0, c) = values[x][c];
  const ColourHistogram histogram = colour_histogram(image.view(), 4);
  ASSERT_EQ(histogram.fractions.size(), 8u);
  const std::vector<double> expected{0.5, 0.0, 0.25, 0.25,   // 0.1, 0.1, 0.6, 0.9
                                     0.5, 0.0, 0.25, 0.25};  // -1 and NaN, 0.6, 2
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_DOUBLE_EQ(histogram.fractions[i], expected[i]) << i;
  EXPECT_DOUBLE_EQ(histogram.largest(), 0.5);
  // Over [0.5, 1] in 2 bins: 0.6 in the first, 0.9 in the second, 0.1 clamped into the first.
  const ColourHistogram narrow = colour_histogram(image.view(), 2, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(narrow.fractions[0], 0.75);
  EXPECT_DOUBLE_EQ(narrow.fractions[1], 0.25);
  EXPECT_THROW(colour_histogram(image.view(), 0), std::invalid_argument);
  EXPECT_THROW(colour_histogram(image.view(), 4, 1.0, 1.0), std::invalid_argument);
}

TEST(HistogramRange, WidensTheCentralValuesWithinZeroToOne) {
  ImageF image(100, 10, 1);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 100; ++x) image.at(x, y, 0) = 0.4f + 0.002f * static_cast<float>(x);
  const auto [low, high] = histogram_range(image.view());
  // Values 0.4 .. 0.598: quantiles near those ends, widened by a quarter of the span (~0.05).
  EXPECT_NEAR(low, 0.35, 0.005);
  EXPECT_NEAR(high, 0.648, 0.005);
  ImageF wide(201, 1, 1);
  for (int x = 0; x < 201; ++x) wide.at(x, 0, 0) = static_cast<float>(x) / 200.0f;
  const auto [wide_low, wide_high] = histogram_range(wide.view());
  EXPECT_DOUBLE_EQ(wide_low, 0.0);
  EXPECT_DOUBLE_EQ(wide_high, 1.0);
}

TEST(HistogramPicture, DrawsTheLineAtItsHeightOverThePaleReference) {
  // One grey channel, 2 bins: everything in the first bin.
  ColourHistogram histogram{1, 2, 0.0, 1.0, {1.0, 0.0}};
  const ColourHistogram reference{1, 2, 0.0, 1.0, {0.5, 0.5}};
  const ImageF picture = histogram_picture(histogram, reference, 8, 11, 1.0);
  ASSERT_EQ(picture.width(), 8);
  ASSERT_EQ(picture.height(), 11);
  ASSERT_EQ(picture.channels(), 3);
  // Columns 0-3 show bin 0: the line (black) at the top row, fraction 1 = top.
  EXPECT_FLOAT_EQ(picture.at(1, 0, 0), 0.0f);
  // Columns 4-7 show bin 1: the line on the bottom row; above it, the reference's pale area
  // (fraction 0.5: rows 5 to 10) tinted a quarter of the way to black; above that, white.
  EXPECT_FLOAT_EQ(picture.at(6, 10, 0), 0.0f);
  EXPECT_FLOAT_EQ(picture.at(6, 7, 0), 0.75f);
  EXPECT_FLOAT_EQ(picture.at(6, 2, 0), 1.0f);
  // The step from bin 0 to bin 1 is joined by a vertical run in column 4.
  for (int y = 0; y < 11; ++y) EXPECT_FLOAT_EQ(picture.at(4, y, 0), 0.0f) << y;
  // Fractions above `top` are clipped to the top row.
  const ImageF clipped = histogram_picture(histogram, reference, 8, 11, 0.25);
  EXPECT_FLOAT_EQ(clipped.at(1, 0, 0), 0.0f);
  histogram.bins = 3;
  EXPECT_THROW(histogram_picture(histogram, reference, 8, 11, 1.0), std::invalid_argument);
}

TEST(Downscale, AveragesTheAreaEachOutputPixelCovers) {
  ImageF image(4, 2, 1);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) image.at(x, y, 0) = static_cast<float>(x + 4 * y);
  const ImageF half = downscale(image.view(), 2);
  ASSERT_EQ(half.width(), 2);
  ASSERT_EQ(half.height(), 1);
  EXPECT_FLOAT_EQ(half.at(0, 0, 0), (0 + 1 + 4 + 5) / 4.0f);
  EXPECT_FLOAT_EQ(half.at(1, 0, 0), (2 + 3 + 6 + 7) / 4.0f);
  // A non-integer ratio: 3 pixels into 2, each output covering 1.5 input pixels.
  ImageF row(3, 1, 1);
  row.at(0, 0, 0) = 0.0f;
  row.at(1, 0, 0) = 3.0f;
  row.at(2, 0, 0) = 6.0f;
  const ImageF two = downscale(row.view(), 2);
  ASSERT_EQ(two.width(), 2);
  EXPECT_FLOAT_EQ(two.at(0, 0, 0), (0.0f + 0.5f * 3.0f) / 1.5f);
  EXPECT_FLOAT_EQ(two.at(1, 0, 0), (0.5f * 3.0f + 6.0f) / 1.5f);
  // Small enough already: unchanged.
  const ImageF same = downscale(image.view(), 4);
  ASSERT_EQ(same.width(), 4);
  EXPECT_FLOAT_EQ(same.at(3, 1, 0), 7.0f);
  EXPECT_THROW(downscale(image.view(), 0), std::invalid_argument);
}

}  // namespace
}  // namespace stochtex::pictures_test
