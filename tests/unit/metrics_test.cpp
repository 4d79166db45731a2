#include "metrics/metrics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "spectral/adsn.hpp"

namespace stochtex::metrics_test {
namespace {

// Uniform white noise in [-amplitude, amplitude] (variance amplitude^2 / 3) from raw mt19937 words:
// std::uniform_real_distribution is not specified exactly, so it differs between standard
// libraries, while mt19937 itself is.
ImageF uniform_noise(int width, int height, int channels, double amplitude, std::uint32_t seed) {
  std::mt19937 rng(seed);
  ImageF image(width, height, channels);
  for (float& value : image.pixels()) {
    const double unit = (static_cast<double>(rng()) + 0.5) / 4294967296.0;
    value = static_cast<float>(amplitude * (2.0 * unit - 1.0));
  }
  return image;
}

// A separable 3-tap box blur (wrapping): a low-pass spectrum, unlike white noise.
ImageF blurred(const ImageF& image) {
  ImageF result(image.width(), image.height(), image.channels());
  const int w = image.width();
  const int h = image.height();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < image.channels(); ++c) {
        float sum = 0.0f;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) sum += image.at((x + dx + w) % w, (y + dy + h) % h, c);
        result.at(x, y, c) = sum / 9.0f;
      }
  return result;
}

double spectrum_at(const std::vector<double>& spectrum, int crop, int kx, int ky) {
  return spectrum[static_cast<std::size_t>(ky) * crop + kx];
}

// Periodic Hann window of side n, 1-D: W(0) = n / 2, W(+-1) = -n / 4, zero elsewhere, and
// sum w^2 = 3n / 8. Removing the crop mean m before windowing gives, for white noise of variance
// s^2, E|X(k)|^2 = s^2 (sum w^2 - |W(k)|^2 / n^2) in 2-D (one degree of freedom lost), so after the
// division by sum w^2 = (3n / 8)^2 the expected spectrum is s^2 (1 - loss(k)) with loss(0, 0) =
// (n^2 / 4)^2 / (n^2 (3n / 8)^2) = 4/9, loss(+-1, 0) = 1/9 and loss(+-1, +-1) = 1/36.
double mean_removal_loss(int kx, int ky, int n) {
  // The 1-D factor |W(k)|^2 / (n sum w^2): 2/3 at 0, 1/6 at +-1 (they sum to 1, by Parseval).
  auto axis = [n](int k) {
    if (k == 0) return 2.0 / 3.0;
    if (k == 1 || k == n - 1) return 1.0 / 6.0;
    return 0.0;
  };
  return axis(kx) * axis(ky);
}

TEST(WelchPowerSpectrum, WhiteNoiseIsFlatAtChannelsTimesVariance) {
  constexpr int size = 384;
  constexpr int crop = 32;
  constexpr int channels = 3;
  constexpr double amplitude = 0.5;
  const double variance = amplitude * amplitude / 3.0;
  const ImageF noise = uniform_noise(size, size, channels, amplitude, 20240601u);
  const std::vector<double> spectrum = welch_power_spectrum(noise.view(), crop);
  ASSERT_EQ(spectrum.size(), static_cast<std::size_t>(crop * crop));

  // Crops per axis: (384 - 32) / 16 + 1 = 23, so K = 529. The periodogram of one crop at one
  // frequency is close to exponential (chi^2 with 2 dof) per channel, so the sum over 3 channels
  // has relative variance 1/3, or 2/3 at the real frequencies (kx, ky in {0, n/2}: chi^2 with 1
  // dof). Half-overlapping Hann crops are correlated by (1/6)^2 per shared axis, which inflates
  // the variance of the mean of K periodograms by 1 + 4/36 + 4/36^2 < 1.2.
  const double crops = 23.0 * 23.0;
  const double level = channels * variance;
  for (int ky = 0; ky < crop; ++ky) {
    for (int kx = 0; kx < crop; ++kx) {
      const bool real = (kx % (crop / 2) == 0) && (ky % (crop / 2) == 0);
      const double relative_variance = (real ? 2.0 : 1.0) / channels;
      const double sigma = std::sqrt(1.2 * relative_variance / crops);
      const double expected = level * (1.0 - mean_removal_loss(kx, ky, crop));
      EXPECT_NEAR(spectrum_at(spectrum, crop, kx, ky), expected, 5.0 * sigma * expected)
          << "at (" << kx << ", " << ky << ")";
    }
  }

  // By Parseval the mean over all frequencies is the window-weighted variance of each crop, whose
  // expectation is level * (1 - 1/n^2). For uniform noise Var(x^2) = 4/5 s^4 and
  // sum w^4 / (sum w^2)^2 = (35/18)^2 / n^2, so one channel of one crop has relative standard
  // deviation sqrt(4/5) * 35/18 / n = 0.054; over 3 channels and 529 crops (correlation 3/70 per
  // shared axis, inflation < 1.2) that is 0.054 * sqrt(1.2 / (3 * 529)) = 0.0015.
  double mean = 0.0;
  for (const double value : spectrum) mean += value;
  mean /= static_cast<double>(spectrum.size());
  EXPECT_NEAR(mean, level * (1.0 - 1.0 / (crop * crop)), 5.0 * 0.0015 * level);
}

TEST(WelchPowerSpectrum, CosineEnergyIsAtItsFrequency) {
  constexpr int crop = 32;
  constexpr int fx = 5;
  constexpr int fy = 3;
  constexpr double amplitude = 2.0;
  ImageF image(128, 96, 1);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      image.at(x, y, 0) = static_cast<float>(
          0.7 + amplitude * std::cos(2.0 * std::numbers::pi * (fx * x + fy * y) / crop));
  const std::vector<double> spectrum = welch_power_spectrum(image.view(), crop);

  // Each crop holds whole periods, so its mean is the offset 0.7 and the windowed cosine has the
  // transform (A / 2) W(k - f) + (A / 2) W(k + f): at k = f, (A / 2) (n^2 / 4), whose square over
  // sum w^2 = (3n / 8)^2 is A^2 n^2 / 9; one step away in x it is A^2 n^2 / 36.
  const double peak = amplitude * amplitude * crop * crop / 9.0;
  EXPECT_NEAR(spectrum_at(spectrum, crop, fx, fy), peak, 1e-4 * peak);
  EXPECT_NEAR(spectrum_at(spectrum, crop, crop - fx, crop - fy), peak, 1e-4 * peak);
  EXPECT_NEAR(spectrum_at(spectrum, crop, fx + 1, fy), peak / 4.0, 1e-4 * peak);
  EXPECT_NEAR(spectrum_at(spectrum, crop, crop - fx - 1, crop - fy), peak / 4.0, 1e-4 * peak);

  // Parseval: the frequencies sum to n^2 times the mean of w^2 (A cos)^2 / mean w^2 = A^2 / 2
  // (the window's own frequencies are too low to beat with 2f); nothing leaks beyond +-1 bin.
  double total = 0.0;
  for (const double value : spectrum) total += value;
  EXPECT_NEAR(total, crop * crop * amplitude * amplitude / 2.0, 1e-4 * total);
  for (int ky = 0; ky < crop; ++ky) {
    for (int kx = 0; kx < crop; ++kx) {
      auto near = [](int k, int f) {
        return std::min((k - f + crop) % crop, (f - k + crop) % crop) <= 1;
      };
      const bool at_peak =
          (near(kx, fx) && near(ky, fy)) || (near(kx, crop - fx) && near(ky, crop - fy));
      if (!at_peak) {
        EXPECT_LT(spectrum_at(spectrum, crop, kx, ky), 1e-6 * peak) << kx << ", " << ky;
      }
    }
  }
}

TEST(WelchPowerSpectrum, IsSymmetricAndSumsChannels) {
  constexpr int crop = 16;
  const ImageF grey = uniform_noise(70, 50, 1, 1.0, 7u);
  const std::vector<double> spectrum = welch_power_spectrum(grey.view(), crop);
  const double largest = *std::max_element(spectrum.begin(), spectrum.end());
  for (int ky = 0; ky < crop; ++ky)
    for (int kx = 0; kx < crop; ++kx)
      EXPECT_NEAR(spectrum_at(spectrum, crop, kx, ky),
                  spectrum_at(spectrum, crop, (crop - kx) % crop, (crop - ky) % crop),
                  1e-5 * largest);

  // Three copies of the grey channel, in a view whose rows are padded (row_stride > width * 3).
  ImageF padded(80, 50, 3, -5.0f);
  for (int y = 0; y < 50; ++y)
    for (int x = 0; x < 70; ++x)
      for (int c = 0; c < 3; ++c) padded.at(x + 10, y, c) = grey.at(x, y, 0);
  const std::vector<double> colour = welch_power_spectrum(padded.view().sub(10, 0, 70, 50), crop);
  for (std::size_t i = 0; i < spectrum.size(); ++i)
    EXPECT_NEAR(colour[i], 3.0 * spectrum[i], 1e-9 * largest);
}

TEST(WelchPowerSpectrum, RejectsCropsThatDoNotFit) {
  const ImageF image(20, 10, 1);
  EXPECT_THROW(welch_power_spectrum(image.view(), 16), std::invalid_argument);
  EXPECT_THROW(welch_power_spectrum(image.view(), 1), std::invalid_argument);
  EXPECT_NO_THROW(welch_power_spectrum(image.view(), 10));
}

TEST(WelchCropSize, HalfTheSmallerSideAsAPowerOfTwo) {
  auto crop_for = [](int w1, int h1, int w2, int h2) {
    const ImageF a(w1, h1, 1);
    const ImageF b(w2, h2, 1);
    return welch_crop_size(a.view(), b.view());
  };
  EXPECT_EQ(crop_for(512, 512, 256, 256), 128);
  EXPECT_EQ(crop_for(1024, 2048, 1024, 1024), 128);  // capped
  EXPECT_EQ(crop_for(200, 200, 100, 60), 16);        // 30 -> 16
  EXPECT_EQ(crop_for(256, 256, 64, 64), 32);
  EXPECT_EQ(crop_for(12, 12, 64, 64), 8);  // at least 8
  EXPECT_EQ(crop_for(8, 8, 8, 8), 8);
  EXPECT_EQ(crop_for(7, 5, 64, 64), 4);  // below 8: the largest power of two that fits
  EXPECT_EQ(crop_for(2, 3, 3, 2), 2);
  EXPECT_THROW(crop_for(1, 5, 5, 5), std::invalid_argument);
}

TEST(SpectralError, ZeroForTheSameImageAndPositiveForAnotherSpectrum) {
  const ImageF noise = uniform_noise(128, 128, 3, 0.5, 11u);
  EXPECT_EQ(spectral_error(noise.view(), noise.view(), 32), 0.0);
  // The blurred spectrum is |H|^2 times the white one, and the mean of |H|^2 over frequencies is
  // sum h^2 = 9 / 81: the error is 1 - 1/9.
  const ImageF smooth = blurred(noise);
  EXPECT_NEAR(spectral_error(smooth.view(), noise.view(), 32), 8.0 / 9.0, 0.03);
  // Another draw of the same white noise: only the estimator's noise remains. With 7 x 7 crops
  // each spectrum has a relative standard deviation of about sqrt(1.2 / (3 * 49)) = 0.09 per
  // frequency (see the white-noise test), so E|Sa - Sb| / Sb = sqrt(2) * 0.09 * sqrt(2 / pi) =
  // 0.10.
  const ImageF other = uniform_noise(128, 128, 3, 0.5, 12u);
  EXPECT_LT(spectral_error(other.view(), noise.view(), 32), 0.2);
  const ImageF grey(128, 128, 1);
  EXPECT_THROW(spectral_error(grey.view(), noise.view(), 32), std::invalid_argument);
}

TEST(SlicedWasserstein, ZeroForTheSameImageAndSymmetric) {
  const ImageF a = uniform_noise(40, 30, 3, 1.0, 3u);
  const ImageF b = blurred(uniform_noise(25, 33, 3, 1.0, 4u));
  EXPECT_EQ(sliced_wasserstein(a.view(), a.view()), 0.0);
  const double ab = sliced_wasserstein(a.view(), b.view());
  EXPECT_GT(ab, 0.1);
  EXPECT_EQ(ab, sliced_wasserstein(b.view(), a.view()));
  EXPECT_EQ(ab, sliced_wasserstein(a.view(), b.view()));  // fixed directions: deterministic
  const ImageF grey(4, 4, 1);
  EXPECT_THROW(sliced_wasserstein(grey.view(), a.view()), std::invalid_argument);
  EXPECT_THROW(sliced_wasserstein(a.view(), a.view(), 0), std::invalid_argument);
}

TEST(SlicedWasserstein, ConstantShiftOfOneChannelIsTheShift) {
  constexpr float shift = 0.375f;
  const ImageF a = uniform_noise(64, 48, 1, 1.0, 5u);
  ImageF shifted = a;
  for (float& value : shifted.pixels()) value += shift;
  EXPECT_NEAR(sliced_wasserstein(a.view(), shifted.view()), shift, 1e-6);

  // The same shifted distribution with every pixel four times (a 2x2 tiling): at the 64 * 48
  // quantile levels (2i + 1) / (2 * 3072) the larger image's quantile is its sorted value 4i + 2,
  // one of the four copies of a's value i, so the distance is still exactly the shift.
  ImageF tiled(128, 96, 1);
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 128; ++x) tiled.at(x, y, 0) = shifted.at(x % 64, y % 48, 0);
  EXPECT_NEAR(sliced_wasserstein(a.view(), tiled.view()), shift, 1e-6);
  EXPECT_NEAR(sliced_wasserstein(tiled.view(), a.view()), shift, 1e-6);
}

TEST(SlicedWasserstein, ColourShiftAveragesOverTheSphere) {
  // A shift d projects to <theta, d> on direction theta; over directions uniform on S^2 the mean
  // of <theta, d>^2 is |d|^2 / 3, with relative standard deviation sqrt(4/45) / (1/3) / sqrt(64)
  // = 0.11 for 64 random directions. Directions bunched on one axis would miss this.
  const double d[3] = {0.3, -0.2, 0.1};
  const ImageF a = uniform_noise(32, 32, 3, 1.0, 6u);
  ImageF shifted = a;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) shifted.at(x, y, c) += static_cast<float>(d[c]);
  const double squared = std::pow(sliced_wasserstein(a.view(), shifted.view()), 2);
  const double expected = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / 3.0;
  EXPECT_NEAR(squared, expected, 4.0 * 0.11 * expected);
}

TEST(SlicedWassersteinReference, EqualsTheDirectDistanceBitForBit) {
  const ImageF reference = uniform_noise(48, 40, 3, 0.5, 11u);
  const ImageF smaller = blurred(uniform_noise(32, 30, 3, 0.7, 12u));
  const ImageF larger = uniform_noise(64, 64, 3, 0.3, 13u);
  const SlicedWassersteinReference for_smaller(reference.view(), 32 * 30);
  EXPECT_EQ(for_smaller.distance(smaller.view()),
            sliced_wasserstein(smaller.view(), reference.view()));
  const SlicedWassersteinReference for_larger(reference.view(), 48 * 40);
  EXPECT_EQ(for_larger.distance(larger.view()),
            sliced_wasserstein(larger.view(), reference.view()));
  // An image whose pixel count does not give the reference's levels is refused.
  EXPECT_THROW(for_smaller.distance(larger.view()), std::invalid_argument);
  EXPECT_THROW(for_smaller.distance(uniform_noise(32, 30, 1, 0.5, 1u).view()),
               std::invalid_argument);
  EXPECT_THROW(SlicedWassersteinReference(reference.view(), 48 * 40 + 1), std::invalid_argument);
}

TEST(ColourStatistics, MeanAndCovarianceOfAKnownImage) {
  // Channel 0 = {1, 2, 3, 4}, channel 1 = {2, 4, 6, 9}, inside a larger image (strided view).
  ImageF image(3, 3, 2, 100.0f);
  const float values[4][2] = {{1, 2}, {2, 4}, {3, 6}, {4, 9}};
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 2; ++c) image.at(1 + i % 2, 1 + i / 2, c) = values[i][c];
  const ColourStatistics statistics = colour_statistics(image.view().sub(1, 1, 2, 2));
  ASSERT_EQ(statistics.mean.size(), 2u);
  ASSERT_EQ(statistics.covariance.size(), 4u);
  EXPECT_DOUBLE_EQ(statistics.mean[0], 2.5);
  EXPECT_DOUBLE_EQ(statistics.mean[1], 5.25);
  // Population covariance (divided by 4): 5/4, 11.5/4 and 26.75/4.
  EXPECT_DOUBLE_EQ(statistics.covariance[0], 1.25);
  EXPECT_DOUBLE_EQ(statistics.covariance[1], 2.875);
  EXPECT_DOUBLE_EQ(statistics.covariance[2], 2.875);
  EXPECT_DOUBLE_EQ(statistics.covariance[3], 6.6875);
}

TEST(ColourStatistics, MeanErrorIsEuclidean) {
  const ColourStatistics a{{0.0, 0.0, 1.0}, std::vector<double>(9, 0.0)};
  const ColourStatistics b{{3.0, 4.0, 1.0}, std::vector<double>(9, 0.0)};
  EXPECT_DOUBLE_EQ(mean_error(a, b), 5.0);
  EXPECT_DOUBLE_EQ(mean_error(b, a), 5.0);
  const ColourStatistics grey{{0.0}, {0.0}};
  EXPECT_THROW(mean_error(a, grey), std::invalid_argument);
}

TEST(ColourStatistics, DoublingTheContrastQuadruplesTheCovariance) {
  const ImageF image = uniform_noise(50, 40, 3, 0.5, 8u);
  const ColourStatistics original = colour_statistics(image.view());
  ImageF contrast = image;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 50; ++x)
      for (int c = 0; c < 3; ++c) {
        const auto mean = static_cast<float>(original.mean[static_cast<std::size_t>(c)]);
        contrast.at(x, y, c) = mean + 2.0f * (image.at(x, y, c) - mean);
      }
  const ColourStatistics doubled = colour_statistics(contrast.view());
  EXPECT_NEAR(covariance_error(doubled, original), 3.0, 1e-5);
  EXPECT_NEAR(covariance_error(original, doubled), 0.75, 1e-5);
  EXPECT_NEAR(mean_error(doubled, original), 0.0, 1e-6);
  EXPECT_EQ(covariance_error(original, original), 0.0);
}

// Renders of uniform noise with amplitude 1 in the left half and `right_amplitude` in the right.
std::vector<ImageF> noise_renders(int count, double right_amplitude) {
  std::vector<ImageF> renders;
  for (int k = 0; k < count; ++k) {
    ImageF render = uniform_noise(64, 64, 2, 1.0, 7000u + static_cast<std::uint32_t>(k));
    for (int y = 0; y < 64; ++y)
      for (int x = 32; x < 64; ++x)
        for (int c = 0; c < 2; ++c)
          render.at(x, y, c) = static_cast<float>(render.at(x, y, c) * right_amplitude);
    renders.push_back(std::move(render));
  }
  return renders;
}

double nonstationarity_of(const std::vector<ImageF>& renders, int block) {
  std::vector<ImageView<const float>> views;
  for (const ImageF& render : renders) views.push_back(render.view());
  return variance_nonstationarity(views, block);
}

TEST(VarianceNonstationarity, StationaryNoiseGivesOnlyTheEstimatorNoise) {
  // Per pixel and channel, the variance of 8 draws of uniform noise has relative variance
  // 2/7 + (excess kurtosis -1.2)/8 = 0.136; summing 2 channels halves it and a block averages 64
  // independent pixels: the block variances vary by sqrt(0.136 / 128) = 0.033 relative. The
  // coefficient of variation over 64 blocks is within 1.5x of that with high probability.
  const double stationary = nonstationarity_of(noise_renders(8, 1.0), 8);
  EXPECT_GT(stationary, 0.5 * 0.033);
  EXPECT_LT(stationary, 1.5 * 0.033);
}

TEST(VarianceNonstationarity, AVarianceStepIsItsCoefficientOfVariation) {
  // Block variances 1 and 4 (times 2 channels / 3) in equal numbers: mean 2.5, deviation 1.5, so
  // 0.6, plus the estimator noise above (0.033 relative per block), which changes it by < 0.03.
  EXPECT_NEAR(nonstationarity_of(noise_renders(8, 2.0), 8), 0.6, 0.03);
}

TEST(VarianceNonstationarity, RejectsInconsistentRenders) {
  const std::vector<ImageF> renders = noise_renders(2, 1.0);
  EXPECT_THROW(nonstationarity_of({renders[0]}, 8), std::invalid_argument);
  EXPECT_THROW(nonstationarity_of(renders, 0), std::invalid_argument);
  EXPECT_THROW(nonstationarity_of(renders, 65), std::invalid_argument);
  const ImageF smaller = uniform_noise(32, 64, 2, 1.0, 1u);
  EXPECT_THROW(nonstationarity_of({renders[0], smaller}, 8), std::invalid_argument);
  const ImageF grey = uniform_noise(64, 64, 1, 1.0, 1u);
  EXPECT_THROW(nonstationarity_of({renders[0], grey}, 8), std::invalid_argument);
}

TEST(CompareImages, AnImageAgainstItselfHasOnlyTheReferenceErrors) {
  const ImageF exemplar = blurred(uniform_noise(64, 48, 3, 0.5, 9u));
  const ComparisonReport report = compare_images(exemplar.view(), exemplar.view(), 3u);
  EXPECT_EQ(report.crop, 16);
  EXPECT_EQ(report.image.spectral_error, 0.0);
  EXPECT_EQ(report.image.histogram_error, 0.0);
  EXPECT_EQ(report.image.mean_error, 0.0);
  EXPECT_EQ(report.image.covariance_error, 0.0);
  // An ADSN sample is a different image with the same expected spectrum: with 7 x 5 crops of 16
  // the estimator's noise alone gives an error near sqrt(2) * sqrt(1.2 / (3 * 35)) * sqrt(2 / pi)
  // = 0.12 (see SpectralError). Two halves of one texture differ.
  EXPECT_GT(report.adsn.spectral_error, 0.0);
  EXPECT_LT(report.adsn.spectral_error, 0.3);
  EXPECT_GT(report.adsn.histogram_error, 0.0);
  EXPECT_GT(report.histogram_error_floor, 0.0);

  const ImageF grey(64, 48, 1);
  EXPECT_THROW(compare_images(exemplar.view(), grey.view()), std::invalid_argument);
}

TEST(Comparison, SeveralImagesGiveMeansAndTheAveragedSpectrum) {
  const ImageF exemplar = blurred(uniform_noise(64, 64, 3, 0.5, 9u));
  std::vector<ImageF> renders;
  for (std::uint32_t seed = 1; seed <= 4; ++seed)
    renders.push_back(adsn(exemplar.view(), 64, 64, 40 + seed));
  Comparison comparison(exemplar.view(), 3u);
  EXPECT_THROW((void)comparison.report(), std::logic_error);
  double spectral_sum = 0.0;
  double covariance_sum = 0.0;
  for (std::size_t k = 0; k < renders.size(); ++k) {
    comparison.add(renders[k].view());
    // Image k is set beside the ADSN sample of seed 3 + k, as compare_images sets one image.
    const ComparisonReport single =
        compare_images(exemplar.view(), renders[k].view(), 3u + static_cast<std::uint32_t>(k));
    spectral_sum += single.image.spectral_error;
    covariance_sum += single.image.covariance_error;
    EXPECT_EQ(comparison.images(), static_cast<int>(k) + 1);
    if (k == 0) {
      const ComparisonReport first = comparison.report();
      EXPECT_EQ(first.image.spectral_error, single.image.spectral_error);
      EXPECT_EQ(first.adsn.spectral_error, single.adsn.spectral_error);
      EXPECT_EQ(first.image.averaged_spectral_error, single.image.spectral_error);
    }
  }
  const ComparisonReport report = comparison.report();
  EXPECT_EQ(report.images, 4);
  EXPECT_DOUBLE_EQ(report.image.spectral_error, spectral_sum / 4.0);
  EXPECT_DOUBLE_EQ(report.image.covariance_error, covariance_sum / 4.0);
  // ADSN renders are unbiased: averaging 4 of them removes part of their shot noise, not the
  // exemplar's own estimator noise (measured: 0.63 and 0.71 of the mean single-render error).
  EXPECT_LT(report.image.averaged_spectral_error, 0.9 * report.image.spectral_error);
  EXPECT_LT(report.adsn.averaged_spectral_error, 0.9 * report.adsn.spectral_error);

  const ImageF smaller = adsn(exemplar.view(), 32, 64, 5u);
  EXPECT_THROW(comparison.add(smaller.view()), std::invalid_argument);
  const ImageF grey(64, 64, 1);
  EXPECT_THROW(comparison.add(grey.view()), std::invalid_argument);
}

TEST(Comparison, AveragingKeepsABiasedSpectrum) {
  // White noise of the exemplar's variance lacks its blur: a biased spectrum, whose averaged
  // error stays at its single-render error (measured 1.247 against 1.259; ADSN's 0.23).
  const ImageF exemplar = blurred(uniform_noise(64, 64, 1, 0.5, 9u));
  Comparison comparison(exemplar.view());
  for (std::uint32_t seed = 1; seed <= 4; ++seed) {
    const ImageF white = uniform_noise(64, 64, 1, 0.5 / 3.0, 60u + seed);
    comparison.add(white.view());
  }
  const ComparisonReport report = comparison.report();
  EXPECT_GT(report.image.averaged_spectral_error, 0.9 * report.image.spectral_error);
  EXPECT_GT(report.image.averaged_spectral_error, 2.0 * report.adsn.averaged_spectral_error);
}

TEST(WrapSteps, ATileableImageStepsAtItsWrapAsInside) {
  // Periodic in both axes: white noise blurred circularly, so that the wrap's column and row are
  // as any other (seeded: measured 0.999 and 0.973; a column's 256 steps vary by a few percent).
  constexpr int kSide = 256;
  ImageF noise(kSide, kSide, 2);
  std::mt19937 random(11);
  std::normal_distribution<float> normal;
  for (float& value : noise.pixels()) value = normal(random);
  ImageF periodic(kSide, kSide, 2);
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      for (int c = 0; c < 2; ++c)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            periodic.at(x, y, c) +=
                noise.at((x + dx + kSide) % kSide, (y + dy + kSide) % kSide, c) / 9.0f;
  const WrapSteps tileable = wrap_steps(periodic.view());
  EXPECT_NEAR(tileable.x, 1.0, 0.1);
  EXPECT_NEAR(tileable.y, 1.0, 0.1);
  // A ramp along x steps 1/63 inside and 1 at its wrap: 63 times; constant along y: 1.
  ImageF ramp(64, 8, 1);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 64; ++x) ramp.at(x, y, 0) = static_cast<float>(x) / 63.0f;
  const WrapSteps steps = wrap_steps(ramp.view());
  EXPECT_NEAR(steps.x, 63.0, 1e-3);
  EXPECT_EQ(steps.y, 1.0);
  EXPECT_NEAR(steps.largest(), 63.0, 1e-3);
  EXPECT_GT(steps.largest(), kTileableWrapStep);
  EXPECT_THROW(wrap_steps(ImageF(1, 5, 1).view()), std::invalid_argument);
}

}  // namespace
}  // namespace stochtex::metrics_test
