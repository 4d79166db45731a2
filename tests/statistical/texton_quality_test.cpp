// Texton noise against its paper's claims, on the shipped `gaussian` exemplars (docs/design.md
// §8). Every bound is derived from the estimator's own noise, measured over fixed seeds: a
// texton noise sample must be as close to the exemplar as an ADSN sample (the exact Gaussian
// texture) up to a few standard errors of that difference.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

#include "io/image_io.hpp"
#include "metrics/metrics.hpp"
#include "shared.hpp"
#include "spectral/adsn.hpp"
#include "statistics.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::texton_quality_test {
namespace {

using test_support::mean_spectrum;
using test_support::pooled;
using test_support::Sample;
using test_support::summarise;

const std::string kTextureDir = STOCHTEX_TEXTURE_DIR;
// The corpus images SOURCES.md classes as `gaussian` (micro-textures a Gaussian field models).
const std::vector<std::string> kGaussianExemplars = {
    "concrete_cement_512.png", "grass_lawn_256.png", "brushed_aluminium_grey_256.png",
    "grass_lawn_128.png"};
constexpr int kSeeds = 6;

ImageF render_texton(const Model& model, int width, int height, std::uint32_t seed,
                     double scale = 1.0, int supersample = 1) {
  ImageF out(width, height, model.channels());
  RenderOptions options;
  options.supersample = supersample;
  render(model, Grid{{0.0, 0.0}, scale, width, height}, seed, out.view(), options);
  return out;
}

TEST(TextonQuality, SpectrumMeanAndCovarianceReachTheAdsnLevel) {
  for (const auto& name : kGaussianExemplars) {
    const ImageF exemplar = read_image(kTextureDir + "/" + name);
    const Model model = test_support::default_model("texton", name, exemplar);
    const int width = exemplar.width();
    const int height = exemplar.height();
    const int crop = welch_crop_size(exemplar.view(), exemplar.view());
    const ColourStatistics target = colour_statistics(exemplar.view());
    std::vector<double> texton_spectral, adsn_spectral, texton_cov, adsn_cov, texton_mean,
        adsn_mean;
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
      const ImageF noise = render_texton(model, width, height, seed);
      const ImageF gaussian = adsn(exemplar.view(), width, height, seed);
      texton_spectral.push_back(spectral_error(noise.view(), exemplar.view(), crop));
      adsn_spectral.push_back(spectral_error(gaussian.view(), exemplar.view(), crop));
      const ColourStatistics noise_stats = colour_statistics(noise.view());
      const ColourStatistics gaussian_stats = colour_statistics(gaussian.view());
      texton_cov.push_back(covariance_error(noise_stats, target));
      adsn_cov.push_back(covariance_error(gaussian_stats, target));
      texton_mean.push_back(mean_error(noise_stats, target));
      adsn_mean.push_back(mean_error(gaussian_stats, target));
    }
    const Sample ts = summarise(texton_spectral), as = summarise(adsn_spectral);
    const Sample tc = summarise(texton_cov), ac = summarise(adsn_cov);
    const Sample tm = summarise(texton_mean), am = summarise(adsn_mean);
    std::cout << name << ": spectral error texton " << ts.mean << " (sd " << ts.deviation
              << "), ADSN " << as.mean << " (sd " << as.deviation << "); covariance error texton "
              << tc.mean << " (sd " << tc.deviation << "), ADSN " << ac.mean << " (sd "
              << ac.deviation << "); mean error texton " << tm.mean << ", ADSN " << am.mean << "\n";
    // "Reaches the ADSN level": the mean gap over the seeds is within 4 pooled standard
    // deviations of a single sample's measurement, i.e. one texton noise sample cannot be told
    // from an ADSN sample by this measure beyond the measure's own sample-to-sample noise. The test
    // can fail: with support 16 all seven exemplars fail it (gaps 0.075-0.28 against bounds
    // 0.013-0.086, measured).
    EXPECT_LE(ts.mean - as.mean, 4.0 * pooled(ts, as)) << name << " spectral error";
    EXPECT_LE(tc.mean - ac.mean, 4.0 * pooled(tc, ac)) << name << " covariance error";
    EXPECT_LE(tm.mean - am.mean, 4.0 * pooled(tm, am)) << name << " mean error";
  }
}

TEST(TextonQuality, SpectrumErrorDecreasesAsSupportGrows) {
  // Paper figure 6: the averaged spectrum of the noise approaches the Gaussian model's as the
  // texton support grows. The reference is the ADSN's averaged spectrum; the estimator floor is
  // the distance between two independent ADSN averages.
  const ImageF exemplar = read_image(kTextureDir + "/grass_lawn_256.png");
  constexpr int kSize = 512;
  constexpr int kCrop = 64;
  constexpr int kAveraged = 8;
  const auto gaussian = [&](std::uint32_t offset) {
    return [&exemplar, offset](std::uint32_t seed) {
      return adsn(exemplar.view(), kSize, kSize, seed + offset);
    };
  };
  const std::vector<double> reference = mean_spectrum(gaussian(0), kAveraged, kCrop);
  const double floor =
      relative_l1_distance(mean_spectrum(gaussian(1000), kAveraged, kCrop), reference);
  std::vector<double> errors;
  for (const double support : {16.0, 32.0, 64.0, 128.0}) {
    const Model model = analyze("texton", exemplar.view(), {{"support", support}}, 0);
    errors.push_back(relative_l1_distance(
        mean_spectrum([&](std::uint32_t seed) { return render_texton(model, kSize, kSize, seed); },
                      kAveraged, kCrop),
        reference));
    std::cout << "support " << support << ": averaged-spectrum distance to ADSN " << errors.back()
              << " (estimator floor " << floor << ")\n";
  }
  // Over the whole range the gain is several times the estimator's floor (the distance two
  // equally good estimates show), and no doubling of the support makes the spectrum worse by more
  // than a quarter of that floor. The gain saturates once the support covers the texture's
  // correlation length, as the paper notes (section 9): on grass 64 -> 128 gains half a floor.
  EXPECT_GT(errors.front() - errors.back(), 2.0 * floor);
  for (std::size_t i = 1; i < errors.size(); ++i)
    EXPECT_LT(errors[i], errors[i - 1] + 0.25 * floor) << "support step " << i;
}

TEST(TextonFiltering, MinifiedRenderMatchesTheSupersampledReference) {
  // render --scale 8 against --supersample 16 (16 x 16 point samples per pixel), same seeds.
  const ImageF exemplar = read_image(kTextureDir + "/moss_ground_512.png");
  const Model model = analyze("texton", exemplar.view(), {}, 0);
  constexpr int kSize = 64;
  constexpr double kScale = 8.0;
  double filtered_variance = 0.0, unfiltered_variance = 0.0, reference_variance = 0.0;
  double filtered_spectral = 0.0, unfiltered_spectral = 0.0, mean_gap = 0.0, mean_noise = 0.0;
  constexpr int kRepeats = 3;
  for (std::uint32_t seed = 1; seed <= kRepeats; ++seed) {
    const Grid grid{{0.0, 0.0}, kScale, kSize, kSize};
    ImageF filtered(kSize, kSize, 3), unfiltered(kSize, kSize, 3), reference(kSize, kSize, 3);
    RenderOptions options;
    render(model, grid, seed, filtered.view(), options);
    options.filter = false;
    render(model, grid, seed, unfiltered.view(), options);
    options.supersample = 16;
    render(model, grid, seed, reference.view(), options);
    const auto total_variance = [](const ImageF& image) {
      const ColourStatistics stats = colour_statistics(image.view());
      return stats.covariance[0] + stats.covariance[4] + stats.covariance[8];
    };
    filtered_variance += total_variance(filtered) / kRepeats;
    unfiltered_variance += total_variance(unfiltered) / kRepeats;
    reference_variance += total_variance(reference) / kRepeats;
    filtered_spectral += spectral_error(filtered.view(), reference.view(), 16) / kRepeats;
    unfiltered_spectral += spectral_error(unfiltered.view(), reference.view(), 16) / kRepeats;
    const ColourStatistics f = colour_statistics(filtered.view());
    const ColourStatistics r = colour_statistics(reference.view());
    mean_gap += mean_error(f, r) / kRepeats;
    // Standard error of a 64 x 64 image mean of the reference, treating pixels as independent
    // (the filtered field decorrelates within ~1 output pixel).
    mean_noise += std::sqrt(total_variance(reference) / (kSize * kSize)) / kRepeats;
  }
  std::cout << "scale 8: variance filtered " << filtered_variance << ", unfiltered "
            << unfiltered_variance << ", supersampled " << reference_variance
            << "; spectral error vs supersampled: filtered " << filtered_spectral << ", unfiltered "
            << unfiltered_spectral << "; mean gap " << mean_gap << "\n";
  EXPECT_LT(mean_gap, 4.0 * mean_noise);
  // The prefiltered pyramid approximates the box filter of the reference (docs: variance within
  // a few percent at scale 8); aliasing shows as the unfiltered variance of the unfiltered noise.
  EXPECT_NEAR(filtered_variance / reference_variance, 1.0, 0.15);
  EXPECT_GT(unfiltered_variance / reference_variance, 2.0);
  EXPECT_LT(filtered_spectral, 0.15);
  EXPECT_GT(unfiltered_spectral, 10.0 * filtered_spectral);
}

}  // namespace
}  // namespace stochtex::texton_quality_test
