// Texton noise mixing (Galerne, Leclaire, Moisan, "Texton Noise", CGF 2017, DOI 10.1111/cgf.13073,
// section 7, figure 5) against the claims, on two shipped colour exemplars: centre crops
// 256 x 256 of moss_ground_512 (A) and rock_sandstone_512 (B), the method's default parameters
// (R = 21, support 128), a horizontal ramp. Every bound comes from the measurements' own noise
// over fixed seeds; the numbers quoted are the ones measured when the bounds were set.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "io/image_io.hpp"
#include "metrics/metrics.hpp"
#include "statistics.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::texton_mix_quality_test {
namespace {

using test_support::mean_spectrum;
using test_support::pooled;
using test_support::Sample;
using test_support::summarise;

const std::string kTextureDir = STOCHTEX_TEXTURE_DIR;
constexpr int kCrop = 256;
constexpr int kSteps = 21;
// The ramp: rho goes from 0 at x = 0 to 1 at x = kRampEnd, so each of the 21 regions (rho rounded
// to k / 20) is 256 pixels wide; region borders lie at x = 256 k + 128.
constexpr double kRampEnd = 256.0 * (kSteps - 1);
constexpr int kHalfSupport = 64;  // texton noise's default support is 128
constexpr int kSeeds = 6;

struct Setup {
  ImageF a;
  ImageF b;
  Model mixed;
  Model texton_a;
  Model texton_b;
};

ImageF centre_crop(const std::string& name) {
  const ImageF image = read_image(kTextureDir + "/" + name);
  const ImageView<const float> crop =
      image.view().sub((image.width() - kCrop) / 2, (image.height() - kCrop) / 2, kCrop, kCrop);
  ImageF out(kCrop, kCrop, image.channels());
  for (int y = 0; y < kCrop; ++y)
    for (int x = 0; x < kCrop; ++x)
      for (int c = 0; c < image.channels(); ++c) out.view().at(x, y, c) = crop.at(x, y, c);
  return out;
}

const Setup& setup() {
  static const Setup made = [] {
    Setup s{centre_crop("moss_ground_512.png"), centre_crop("rock_sandstone_512.png"), {}, {}, {}};
    MixInputs inputs;
    inputs.a = s.a.view();
    inputs.b = s.b.view();
    s.mixed = mix(inputs, {{"ramp_start", 0.0}, {"ramp_end", kRampEnd}}, 0);
    s.texton_a = analyze("texton", s.a.view(), {}, 0);
    s.texton_b = analyze("texton", s.b.view(), {}, 0);
    return s;
  }();
  return made;
}

ImageF render_at(const Model& model, double x0, int width, int height, std::uint32_t seed) {
  ImageF out(width, height, model.channels());
  render(model, Grid{{x0, 0.0}, 1.0, width, height}, seed, out.view());
  return out;
}

// Far left of the ramp (every impulse reaching the window has rho = 0) and far right (rho = 1).
constexpr double kLeft = -kCrop - kHalfSupport;
constexpr double kRight = kRampEnd + kHalfSupport;
// The region of rho = 0.5 (k = 10), 256 pixels wide.
constexpr double kMiddle = 0.5 * kRampEnd - 128.0;

struct Errors {
  std::vector<double> spectral, covariance, mean;
};

void add_errors(Errors& errors, const ImageF& image, const ImageF& exemplar) {
  const int crop = welch_crop_size(exemplar.view(), exemplar.view());
  errors.spectral.push_back(spectral_error(image.view(), exemplar.view(), crop));
  const ColourStatistics target = colour_statistics(exemplar.view());
  const ColourStatistics stats = colour_statistics(image.view());
  errors.covariance.push_back(covariance_error(stats, target));
  errors.mean.push_back(mean_error(stats, target));
}

void expect_at_texton_level(const Model& texton, double x0, const ImageF& exemplar,
                            const char* side) {
  Errors mixed, plain;
  for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
    add_errors(mixed, render_at(setup().mixed, x0, kCrop, kCrop, seed), exemplar);
    add_errors(plain, render_at(texton, 0.0, kCrop, kCrop, seed), exemplar);
  }
  const auto check = [&](const std::vector<double>& m, const std::vector<double>& p,
                         const char* what) {
    const Sample ms = summarise(m), ps = summarise(p);
    std::cout << side << " " << what << " error: mixing " << ms.mean << " (sd " << ms.deviation
              << "), texton noise " << ps.mean << " (sd " << ps.deviation << "), gap/pooled "
              << (ms.mean - ps.mean) / pooled(ms, ps) << "\n";
    EXPECT_LE(ms.mean - ps.mean, 4.0 * pooled(ms, ps)) << side << " " << what;
  };
  check(mixed.spectral, plain.spectral, "spectral");
  check(mixed.covariance, plain.covariance, "covariance");
  check(mixed.mean, plain.mean, "mean");
}

TEST(TextonMixQuality, FarLeftIsATextonNoiseAndFarRightIsB) {
  // Far from the ramp the mixing uses one texton (the aligned tau_0, or t_B) with random signs:
  // its spectral, covariance and mean errors against the exemplar must be those of plain texton
  // noise of that exemplar (same support), within 4 pooled seed-to-seed deviations, as
  // texton_quality_test holds texton noise to ADSN's. Measured (6 seeds, mixing vs texton noise,
  // gap / pooled deviation): A spectral 0.336 vs 0.336 (-0.01), covariance 0.117 vs 0.114 (0.06),
  // mean 0.0051 vs 0.0047 (0.09); B spectral 0.396 vs 0.407 (-0.19), covariance 0.126 vs 0.081
  // (0.59), mean 0.0066 vs 0.0058 (0.22).
  expect_at_texton_level(setup().texton_a, kLeft, setup().a, "A (far left)");
  expect_at_texton_level(setup().texton_b, kRight, setup().b, "B (far right)");
}

TEST(TextonMixQuality, SpectrumAtHalfLiesBetweenAAndB) {
  // Figure 5 shows the texture at rho = 0.5 as an intermediate of the two; section 7's kernel
  // tau_rho = (1 - rho) tau_0 + rho t_B with tau_0 phase-aligned to t_B has, for grey images, the
  // amplitude spectrum (1 - rho) |t_A| + rho |t_B|. So the measure is the expected spectrum
  // (Welch, averaged over 8 renders) of the rho = 0.5 region against those of the far left (A)
  // and far right (B): it must lie closer to each end than the ends lie to each other, and closer
  // still to the amplitude mean ((sqrt S_A + sqrt S_B) / 2)^2. A pointwise "between" on the
  // radially averaged spectrum was not chosen: in colour the channels' cross term makes
  // |tau_0.5|^2 dip below both ends where they cross (measured: ring 3 of 32, A 0.351, B 0.343,
  // middle 0.298). Noise scale: `floor`, the distance between two independent 8-render averages
  // of the middle. Measured: d(A, B) 1.264, d(B, A) 0.741, d(mid, A) 0.462, d(mid, B) 0.498,
  // d(mid, amplitude mean) 0.104, floor 0.070; the margins below are 2 floors.
  constexpr int kAveraged = 8;
  constexpr int kWelch = 64;
  const auto at = [](double x0, std::uint32_t offset) {
    return [x0, offset](std::uint32_t seed) {
      return render_at(setup().mixed, x0, kCrop, kCrop, seed + offset);
    };
  };
  const std::vector<double> a = mean_spectrum(at(kLeft, 0), kAveraged, kWelch);
  const std::vector<double> b = mean_spectrum(at(kRight, 0), kAveraged, kWelch);
  const std::vector<double> middle = mean_spectrum(at(kMiddle, 0), kAveraged, kWelch);
  const double floor =
      relative_l1_distance(mean_spectrum(at(kMiddle, 100), kAveraged, kWelch), middle);
  std::vector<double> amplitude_mean(a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    amplitude_mean[i] = std::pow(0.5 * (std::sqrt(a[i]) + std::sqrt(b[i])), 2.0);
  const double ab = relative_l1_distance(a, b);
  const double ba = relative_l1_distance(b, a);
  const double ma = relative_l1_distance(middle, a);
  const double mb = relative_l1_distance(middle, b);
  const double mp = relative_l1_distance(middle, amplitude_mean);
  std::cout << "averaged spectra: d(A, B) " << ab << ", d(B, A) " << ba << ", d(mid, A) " << ma
            << ", d(mid, B) " << mb << ", d(mid, amplitude mean) " << mp << ", floor " << floor
            << "\n";
  EXPECT_LT(ma + 2.0 * floor, ba);
  EXPECT_LT(mb + 2.0 * floor, ab);
  EXPECT_LT(mp + 2.0 * floor, std::min(ma, mb));
}

TEST(TextonMixQuality, NoStepInMeanOrVarianceAcrossRegionBorders) {
  // Section 7: the texton is chosen per impulse by its region, yet the output has no
  // discontinuity because the kernels blend locally, and the mean is interpolated at the point.
  // A 1024 x 384 strip around rho = 0.5 (four region borders, at band boundaries) is cut into
  // 8-pixel bands; per seed, each band's channel means and total variance, and the step from each
  // band to the next. Each step, averaged over 16 seeds, less the strip's average step (the
  // ramp's trend), is divided by its standard error (the steps' seed-to-seed deviation pooled
  // over the strip, / sqrt(16)). Measured max |z| over the 127 steps: means 2.37, 2.46, 2.73 (R,
  // G, B), variance 3.66 (not at a border). The test can fail: the same renders with the mean
  // quantised to the regions (mean_A + k / 20 (mean_B - mean_A) in region k, as if the mean
  // followed the textons) give max |z| 12.96, 4.63, 6.48, the steps of 0.0166, 0.0060, 0.0089
  // at the borders; the bound 5 catches R and B.
  constexpr int kBand = 8;
  constexpr int kWidth = 1024;
  constexpr int kHeight = 384;
  constexpr int kStripSeeds = 16;
  constexpr double kStart = 0.5 * kRampEnd - 512.0;
  constexpr int kBands = kWidth / kBand;
  const int channels = setup().mixed.channels();
  // means[seed][band][channel], variances[seed][band] (summed over channels)
  std::vector<std::vector<std::vector<double>>> means(kStripSeeds);
  std::vector<std::vector<double>> variances(kStripSeeds);
  for (std::uint32_t seed = 1; seed <= kStripSeeds; ++seed) {
    const ImageF strip = render_at(setup().mixed, kStart, kWidth, kHeight, seed);
    for (int band = 0; band < kBands; ++band) {
      const ColourStatistics stats =
          colour_statistics(strip.view().sub(band * kBand, 0, kBand, kHeight));
      means[seed - 1].push_back(stats.mean);
      double variance = 0.0;
      for (int c = 0; c < channels; ++c) variance += stats.covariance[c * channels + c];
      variances[seed - 1].push_back(variance);
    }
  }
  const auto z_scores = [&](const auto& value) {
    std::vector<Sample> steps;
    for (int band = 0; band + 1 < kBands; ++band) {
      std::vector<double> step;
      for (int s = 0; s < kStripSeeds; ++s) step.push_back(value(s, band + 1) - value(s, band));
      steps.push_back(summarise(step));
    }
    double trend = 0.0, square = 0.0;
    for (const Sample& step : steps) {
      trend += step.mean / (kBands - 1);
      square += step.deviation * step.deviation / (kBands - 1);
    }
    const double standard_error = std::sqrt(square / kStripSeeds);
    std::vector<double> z;
    for (const Sample& step : steps) z.push_back((step.mean - trend) / standard_error);
    return z;
  };
  const auto worst = [](const std::vector<double>& z) {
    double largest = 0.0;
    for (const double value : z) largest = std::max(largest, std::abs(value));
    return largest;
  };
  constexpr double kBound = 5.0;
  for (int c = 0; c < channels; ++c) {
    const double z = worst(z_scores([&](int s, int band) { return means[s][band][c]; }));
    std::cout << "mean, channel " << c << ": max |z| " << z << "\n";
    EXPECT_LT(z, kBound) << "channel " << c;
  }
  const double z = worst(z_scores([&](int s, int band) { return variances[s][band]; }));
  std::cout << "variance: max |z| " << z << "\n";
  EXPECT_LT(z, kBound);
}

}  // namespace
}  // namespace stochtex::texton_mix_quality_test
