// Local random-phase noise against its paper's claims (Gilet et al. 2014), on `gaussian` exemplars
// of the corpus and on a continuous ring target (docs/design.md §8). Bounds come from the
// estimators' own noise, measured over fixed seeds; each test says how it can fail.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

#include "io/image_io.hpp"
#include "methods/lrp/analysis.hpp"
#include "metrics/metrics.hpp"
#include "model/model_data.hpp"
#include "shared.hpp"
#include "spectral/adsn.hpp"
#include "statistics.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::lrp_quality_test {
namespace {

const std::string kTextureDir = STOCHTEX_TEXTURE_DIR;

using test_support::mean_spectrum;

ImageF render_model(const Model& model, int size, std::uint32_t seed) {
  ImageF out(size, size, model.channels());
  render(model, Grid{{0.0, 0.0}, 1.0, size, size}, seed, out.view());
  return out;
}

TEST(LrpQuality, SpectrumAndCovarianceAgainstAdsnAsCosinesGrow) {
  // Two `gaussian` exemplars (grey and colour), J = 10, 25, 50, 100. The expected spectrum is
  // estimated by averaging 4 renders; the reference is the exemplar's Welch spectrum. ADSN (the
  // exact Gaussian texture) and a white noise of the exemplar's covariance bracket the scale.
  constexpr int kSize = 192;
  constexpr int kCrop = 64;
  constexpr int kSeeds = 4;
  for (const std::string name : {"brushed_aluminium_grey_256.png", "concrete_cement_512.png"}) {
    const ImageF exemplar = read_image(kTextureDir + "/" + name);
    const std::vector<double> target = welch_power_spectrum(exemplar.view(), kCrop);
    const double adsn_error = relative_l1_distance(
        mean_spectrum([&](std::uint32_t s) { return adsn(exemplar.view(), kSize, kSize, s); },
                      kSeeds, kCrop),
        target);
    // White noise: a flat spectrum at the exemplar's total variance (Welch spectra average to
    // the variance, metrics.hpp).
    const double variance =
        std::accumulate(target.begin(), target.end(), 0.0) / static_cast<double>(target.size());
    const double white_error =
        relative_l1_distance(std::vector<double>(target.size(), variance), target);
    const ColourStatistics exemplar_stats = colour_statistics(exemplar.view());
    std::cout << name << ": averaged-spectrum error ADSN " << adsn_error << ", white noise "
              << white_error << "\n";
    // Measured over 6 sets of 4 renders: one averaged-spectrum error fluctuates by sigma = 0.012
    // (J = 10 and 100 alike); ADSN's by 0.005-0.008.
    constexpr double kSigma = 0.0125;
    std::vector<double> errors;
    for (const double cosines : {10.0, 25.0, 50.0, 100.0}) {
      const Model model = analyze("lrp", exemplar.view(), {{"cosines", cosines}}, 0, name);
      double covariance = 0.0;
      const double error = relative_l1_distance(
          mean_spectrum(
              [&](std::uint32_t s) {
                ImageF image = render_model(model, kSize, s);
                covariance +=
                    covariance_error(colour_statistics(image.view()), exemplar_stats) / kSeeds;
                return image;
              },
              kSeeds, kCrop),
          target);
      errors.push_back(error);
      std::cout << "  J " << cosines << ": averaged-spectrum error " << error
                << ", covariance error " << covariance << "\n";
      // PCA channels with the exact variance each keep the colour covariance (measured
      // 0.010-0.045 averaged over 4 renders; one 192^2 render's covariance fluctuates by ~0.02;
      // with a wrong A_S the error was 0.2-0.45).
      EXPECT_LT(covariance, 0.08) << name << " J " << cosines;
    }
    // The error falls as J grows (measured 0.31 -> 0.18 and 0.29 -> 0.12): J = 100 lies below
    // J = 10 by more than 3 standard deviations of a difference (3 sqrt(2) sigma). With one
    // amplitude per stratum as published (`amplitudes=0`) the curve is flat (0.43-0.72).
    EXPECT_LT(errors.back(), errors.front() - 3.0 * std::sqrt(2.0) * kSigma) << name;
    // ... and approaches the ADSN level: within 1.6 times it (measured 1.58 and 1.25 times; 1.8
    // and 2.5 before the spacing floor, the closed support and DC of issue 20) plus 4 sigma. The
    // published constant amplitudes land at 4-5 times the ADSN level and fail this.
    EXPECT_LT(errors.back(), 1.6 * adsn_error + 4.0 * kSigma) << name;
    EXPECT_LT(errors.back(), 0.85 * white_error) << name;
  }
}

TEST(LrpQuality, RingTargetIsReproduced) {
  // Figure 10: a single stratum of a continuous ring spectrum (radius 0.2 cycle per pixel).
  const Model model = lrp::spectrum_model(lrp::ring_spectrum(128, 0.2, 0.01, 1.0),
                                          {{"strata", 1}, {"cosines", 5}}, 0);
  constexpr int kCrop = 64;
  const std::vector<double> spectrum =
      mean_spectrum([&](std::uint32_t s) { return render_model(model, 256, s); }, 4, kCrop);
  std::vector<double> radial(kCrop, 0.0);
  double total = 0.0, near_ring = 0.0, variance = 0.0;
  for (int y = 0; y < kCrop; ++y)
    for (int x = 0; x < kCrop; ++x) {
      const double fx = (x > kCrop / 2 ? x - kCrop : x) / double(kCrop);
      const double fy = (y > kCrop / 2 ? y - kCrop : y) / double(kCrop);
      const double value = spectrum[static_cast<std::size_t>(y) * kCrop + x];
      const double radius = std::hypot(fx, fy);
      radial[static_cast<std::size_t>(radius * kCrop)] += value;
      total += value;
      variance += value / (kCrop * kCrop);
      if (std::abs(radius - 0.2) < 0.1) near_ring += value;
    }
  // Per-radius mean power (divide by the ring's circumference), peak location.
  std::size_t peak = 1;
  for (std::size_t r = 1; r < radial.size(); ++r)
    if (radial[r] / double(r) > radial[peak] / double(peak)) peak = r;
  const double peak_radius = (static_cast<double>(peak) + 0.5) / kCrop;
  std::cout << "ring: peak at " << peak_radius << " cycle/pixel, " << near_ring / total
            << " of the energy within 0.1 of the ring, variance " << variance << "\n";
  // With J = 5 the windows are ~5.5 pixels wide, so the ring is blurred by ~1/5.5 cycle (section
  // 3.5); the peak stays on the ring (one radial bin is 1/64) and the energy around it. The test
  // fails if the frequency scale is wrong (peak elsewhere) or the window leaks (energy spread).
  EXPECT_NEAR(peak_radius, 0.2, 1.5 / kCrop);
  EXPECT_GT(near_ring / total, 0.9);
  EXPECT_NEAR(variance, 1.0, 0.15);  // the target's variance (4 renders: ~5% noise)
}

// Relative variation (max - min) / mean of the per-position variance over a lattice cell.
double envelope_variation(double envelope) {
  // One stratum on a lattice of spacing Delta; positions folded into an 8 x 8 grid of phases in
  // the cell, each phase bin gathering 16 x 16 cells x 64 seeds.
  const Model model =
      lrp::spectrum_model(lrp::ring_spectrum(64, 0.15, 0.02, 1.0),
                          {{"strata", 1}, {"cosines", 4}, {"envelope", envelope}}, 0);
  const double spacing = std::get<lrp::LrpModel>(model.data().model).data().strata_table[0].spacing;
  constexpr int kPhases = 8;
  constexpr int kCells = 16;
  constexpr int kSeeds = 64;
  std::vector<Vec2d> positions;
  for (int cy = 0; cy < kCells; ++cy)
    for (int cx = 0; cx < kCells; ++cx)
      for (int py = 0; py < kPhases; ++py)
        for (int px = 0; px < kPhases; ++px)
          positions.push_back(
              {(cx + (px + 0.5) / kPhases) * spacing, (cy + (py + 0.5) / kPhases) * spacing});
  std::vector<double> sum(kPhases * kPhases, 0.0), square(kPhases * kPhases, 0.0);
  ImageF out(1, static_cast<int>(positions.size()), 1);
  for (std::uint32_t seed = 0; seed < kSeeds; ++seed) {
    evaluate(model, positions, {}, seed, out.view());
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const double value = out.at(0, static_cast<int>(i), 0);
      sum[i % (kPhases * kPhases)] += value;
      square[i % (kPhases * kPhases)] += value * value;
    }
  }
  const double n = double(kCells * kCells * kSeeds);
  double low = 1e300, high = 0.0, mean = 0.0;
  for (std::size_t b = 0; b < sum.size(); ++b) {
    const double variance = square[b] / n - (sum[b] / n) * (sum[b] / n);
    low = std::min(low, variance);
    high = std::max(high, variance);
    mean += variance / double(sum.size());
  }
  return (high - low) / mean;
}

TEST(LrpQuality, VarianceEnvelopeIsFlatOverALatticeCell) {
  // Section 3.4 claims the envelope varies by less than 5%. Each of the 64 phase bins estimates a
  // variance from n = 16 * 16 * 64 = 16384 samples (relative sd sqrt(2/n) = 1.1% for a Gaussian
  // field; samples one lattice spacing apart are nearly independent); the max - min of 64 such
  // estimates is ~4.5 sd = 5% for a flat envelope. So the bound is 5% + that estimator spread.
  const double normalised = envelope_variation(1.0);
  const double published = envelope_variation(0.0);
  std::cout << "variance envelope over a lattice cell: (max - min) / mean = " << normalised
            << " with envelope normalisation, " << published << " for equation (1) as published\n";
  EXPECT_LT(normalised, 0.05 + 0.05);
  // The published model fails the paper's own claim: sum_i w_i^2 goes from ~1.03 at a node to
  // ~0.47 at a cell centre (window of radius 1.5 on a unit lattice). This is also the check that
  // the measurement can fail.
  EXPECT_GT(published, 0.5);
}

TEST(LrpFiltering, MinifiedRenderAgainstTheSupersampledReference) {
  // Section 6.4's frequency clamping at scales 4 and 8 against a box-filtered reference
  // (--supersample 2 x scale, the same seeds), on a grey `gaussian` exemplar with J = 20 to keep
  // the reference affordable. Clamping is an anti-aliasing rule, not a box filter: a cosine at
  // half a cycle per output pixel keeps weight 1 where the box attenuates it to sinc(1/2)^2 = 0.41,
  // so the filtered variance is expected above the reference, the unfiltered (aliased) one far
  // above.
  const ImageF exemplar = read_image(kTextureDir + "/brushed_aluminium_grey_256.png");
  const Model model = analyze("lrp", exemplar.view(), {{"cosines", 20}}, 0);
  constexpr int kSize = 48;
  constexpr int kRepeats = 3;
  for (const int scale : {4, 8}) {
    // The exemplar's own variance over that of its scale x scale box averages: what the
    // unfiltered render (all the variance) keeps over the supersampled one for a faithful model.
    ImageF boxed(exemplar.width() / scale, exemplar.height() / scale, 1);
    for (int y = 0; y < boxed.height(); ++y)
      for (int x = 0; x < boxed.width(); ++x) {
        double sum = 0.0;
        for (int dy = 0; dy < scale; ++dy)
          for (int dx = 0; dx < scale; ++dx) sum += exemplar.at(x * scale + dx, y * scale + dy, 0);
        boxed.at(x, y, 0) = static_cast<float>(sum / (scale * scale));
      }
    const double box_ratio = colour_statistics(exemplar.view()).covariance[0] /
                             colour_statistics(boxed.view()).covariance[0];
    double variance[3] = {};  // filtered, unfiltered, reference
    double spectral[2] = {};  // filtered, unfiltered, against the reference
    for (std::uint32_t seed = 1; seed <= kRepeats; ++seed) {
      const Grid grid{{0.0, 0.0}, double(scale), kSize, kSize};
      ImageF images[3] = {ImageF(kSize, kSize, 1), ImageF(kSize, kSize, 1),
                          ImageF(kSize, kSize, 1)};
      RenderOptions options;
      render(model, grid, seed, images[0].view(), options);
      options.filter = false;
      render(model, grid, seed, images[1].view(), options);
      options.supersample = 2 * scale;
      render(model, grid, seed, images[2].view(), options);
      for (int i = 0; i < 3; ++i)
        variance[i] += colour_statistics(images[i].view()).covariance[0] / kRepeats;
      for (int i = 0; i < 2; ++i)
        spectral[i] += spectral_error(images[i].view(), images[2].view(), 16) / kRepeats;
    }
    std::cout << "scale " << scale << ": variance filtered " << variance[0] << ", unfiltered "
              << variance[1] << ", supersampled " << variance[2] << " (exemplar, all over box "
              << box_ratio << "); spectral error vs supersampled: filtered " << spectral[0]
              << ", unfiltered " << spectral[1] << "\n";
    // Measured (3 seeds): filtered variance 1.44 and 1.48 times the reference at scales 4 and
    // 8, unfiltered 3.95 and 7.9 (the exemplar's box ratios: 4.16 and 9.03); spectral error 0.44
    // and 0.53 against 2.9 and 6.8. The clamped render must stay far closer to the reference than
    // the aliased one and keep no more than twice its variance (a clamp that does nothing gives
    // the unfiltered numbers); the supersampled reference must keep what a box keeps of the
    // exemplar, within 25% (a reference that does not filter gives a ratio of 1).
    EXPECT_LT(variance[0], 2.0 * variance[2]) << "scale " << scale;
    EXPECT_GT(variance[0], variance[2]) << "scale " << scale;
    EXPECT_NEAR(variance[1] / variance[2], box_ratio, 0.25 * box_ratio) << "scale " << scale;
    EXPECT_LT(spectral[0], 0.25 * spectral[1]) << "scale " << scale;
  }
}

TEST(LrpFiltering, NoIsolatedDotsZoomedOut) {
  // Zoomed out 8 times, frequency clamping leaves only a stratum's few low frequencies per node.
  // When a heavy weight was drawn rarely (concrete's DC at weight 6.0 beside 13 frequencies near
  // 1, one node in 14), those nodes showed as isolated light and dark dots of a node's size: a
  // heavy tail. A Gaussian field puts 6.3e-5 of its samples beyond 4 standard deviations, 16.6 of
  // a 512^2 render. Measured on the first channel, seeds 1 and 2: 79 and 83 such samples with
  // uniform draws of the shaped weights, 7 and 13 with draws in proportion to power (analysis.cpp,
  // draw_in_proportion_to_power); the CLI's srgb model over seeds 1-6: 90-111 against 8-16. The
  // bound is twice the Gaussian count.
  const std::string name = "concrete_cement_512.png";
  const ImageF exemplar = read_image(kTextureDir + "/" + name);
  const Model model = test_support::default_model("lrp", name, exemplar);
  constexpr int kSize = 512;
  constexpr double kGaussianTail = 6.334e-5;  // P(|z| > 4) of a normal variable
  for (const std::uint32_t seed : {1u, 2u}) {
    ImageF image(kSize, kSize, model.channels());
    render(model, Grid{{0.0, 0.0}, 8.0, kSize, kSize}, seed, image.view());
    double sum = 0.0, square = 0.0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        sum += image.at(x, y, 0);
        square += double(image.at(x, y, 0)) * image.at(x, y, 0);
      }
    const double count = double(kSize) * kSize;
    const double mean = sum / count;
    const double deviation = std::sqrt(square / count - mean * mean);
    int beyond = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) beyond += std::abs(image.at(x, y, 0) - mean) > 4 * deviation;
    std::cout << "seed " << seed << ": " << beyond << " samples beyond 4 standard deviations ("
              << kGaussianTail * count << " for a Gaussian field)\n";
    EXPECT_LT(beyond, 2.0 * kGaussianTail * count) << "seed " << seed;
  }
}

}  // namespace
}  // namespace stochtex::lrp_quality_test
