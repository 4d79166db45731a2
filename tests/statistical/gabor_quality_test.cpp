// Gabor noise by example against its paper's claims, on `gaussian` exemplars of the corpus
// (docs/design.md §8). Bounds are derived from the estimator's own noise, measured over fixed
// seeds: the procedural noise must be as close to the exemplar as an ADSN sample (the exact
// Gaussian texture, the paper's ground truth of section 3.1) up to a few standard deviations of
// one sample's measurement.

#include <gtest/gtest.h>

#include <cmath>
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
#include "test_support.hpp"

namespace stochtex::gabor_quality_test {
namespace {

const std::string kTextureDir = STOCHTEX_TEXTURE_DIR;

using test_support::pooled;
using test_support::Sample;
using test_support::summarise;

ImageF render_noise(const Model& model, int width, int height, std::uint32_t seed,
                    double scale = 1.0, int supersample = 1, bool filter = true) {
  ImageF out(width, height, model.channels());
  RenderOptions options;
  options.supersample = supersample;
  options.filter = filter;
  render(model, Grid{{0.0, 0.0}, scale, width, height}, seed, out.view(), options);
  return out;
}

struct Errors {
  Sample noise_spectral, adsn_spectral, noise_covariance, adsn_covariance;
};

// Spectral and covariance errors against the exemplar of `seeds` renders of side `size` and of
// as many ADSN samples of the same size (docs/design.md §8).
Errors measure(const Model& model, const ImageF& exemplar, int size, int seeds) {
  const int crop = size / 2;
  const ColourStatistics target = colour_statistics(exemplar.view());
  std::vector<double> noise_spectral, adsn_spectral, noise_cov, adsn_cov;
  for (std::uint32_t seed = 1; seed <= static_cast<std::uint32_t>(seeds); ++seed) {
    const ImageF noise = render_noise(model, size, size, seed);
    const ImageF gaussian = adsn(exemplar.view(), size, size, seed);
    noise_spectral.push_back(spectral_error(noise.view(), exemplar.view(), crop));
    adsn_spectral.push_back(spectral_error(gaussian.view(), exemplar.view(), crop));
    noise_cov.push_back(covariance_error(colour_statistics(noise.view()), target));
    adsn_cov.push_back(covariance_error(colour_statistics(gaussian.view()), target));
  }
  return {summarise(noise_spectral), summarise(adsn_spectral), summarise(noise_cov),
          summarise(adsn_cov)};
}

void print(const std::string& what, const Errors& e) {
  std::cout << what << ": spectral error gabor " << e.noise_spectral.mean << " (sd "
            << e.noise_spectral.deviation << "), ADSN " << e.adsn_spectral.mean << " (sd "
            << e.adsn_spectral.deviation << "); covariance error gabor " << e.noise_covariance.mean
            << " (sd " << e.noise_covariance.deviation << "), ADSN " << e.adsn_covariance.mean
            << " (sd " << e.adsn_covariance.deviation << ")\n";
}

// The bound of "at the ADSN level": the mean gap over the seeds within 4 pooled standard
// deviations of one sample's measurement (the estimator's own noise) plus `bias` of the ADSN
// error.
double spectral_bound(const Errors& e, double bias) {
  return 4.0 * pooled(e.noise_spectral, e.adsn_spectral) + bias * e.adsn_spectral.mean;
}
double covariance_bound(const Errors& e) {
  return 4.0 * pooled(e.noise_covariance, e.adsn_covariance);
}

TEST(GaborQuality, DefaultsStayNearTheAdsnLevel) {
  // Renders of 128^2 (Welch crops of 64) keep the suite fast; the docs list full-size numbers.
  // At the default budget N = 1024 the shot noise is not yet Gaussian: each 64^2 crop sees a
  // finite set of kernels, each a narrow-band wave, so its periodogram is spikier than a Gaussian
  // field's and the spectral error sits from 2% to 30% above ADSN's (measured at the defaults of
  // issue 20; 7% below to 49% above before; the gap closes with N, see the next test). The bound
  // allows that bias (50%) plus 4 pooled sd. The test can fail: with kappa = 1/2 (a handful of
  // Gaussians) the fit loses half the variance and the covariance gap is 0.4 against bounds below
  // 0.3, and the spectral gap 0.29-0.30 reaches its bound (measured on grass). Concrete, the fourth
  // shipped `gaussian` exemplar, is left out to keep the suite near a minute on two cores.
  for (const std::string name :
       {"brushed_aluminium_grey_256.png", "grass_lawn_256.png", "grass_lawn_128.png"}) {
    const ImageF exemplar = read_image(kTextureDir + "/" + name);
    const Model model = test_support::default_model("gabor", name, exemplar);
    const Errors e = measure(model, exemplar, 128, 3);
    print(name, e);
    EXPECT_LE(e.noise_spectral.mean - e.adsn_spectral.mean, spectral_bound(e, 0.5)) << name;
    EXPECT_LE(e.noise_covariance.mean - e.adsn_covariance.mean, covariance_bound(e) + 0.05) << name;
  }
}

TEST(GaborQuality, SpectrumReachesTheAdsnLevelAsTheImpulseBudgetGrows) {
  // Section 9.1: N trades quality for speed. At N = 4096 the noise is Gaussian enough that its
  // spectral error is at the ADSN level (4 pooled sd plus 10% for the fit's own bias; the gap
  // measured -0.003 at the defaults of issue 20, 0.037 before), and more impulses never make it
  // worse beyond the estimator's noise.
  const ImageF exemplar = read_image(kTextureDir + "/grass_lawn_128.png");
  std::vector<Errors> errors;
  for (const double impulses : {256.0, 1024.0, 4096.0}) {
    const Model model = analyze("gabor", exemplar.view(), {{"impulses", impulses}}, 0);
    errors.push_back(measure(model, exemplar, 128, 4));
    print("grass_lawn_128, N = " + std::to_string(static_cast<int>(impulses)), errors.back());
  }
  EXPECT_LE(errors[2].noise_spectral.mean - errors[2].adsn_spectral.mean,
            spectral_bound(errors[2], 0.1));
  for (std::size_t i = 1; i < errors.size(); ++i)
    EXPECT_LT(errors[i].noise_spectral.mean,
              errors[i - 1].noise_spectral.mean +
                  2.0 * pooled(errors[i].noise_spectral, errors[i - 1].noise_spectral))
        << "budget step " << i;
}

TEST(GaborQuality, ColourCovarianceInEachColourSpace) {
  // Section 7: channels are synthesised independently, so the colour space must decorrelate
  // them. The maximally independent and PCA (the default) spaces keep the exemplar's covariance
  // at the ADSN level; RGB loses the cross-channel covariance (the grass's channels are correlated:
  // error 0.75 against 0.03, measured), which shows the test can fail.
  const ImageF exemplar = read_image(kTextureDir + "/grass_lawn_128.png");
  for (const double space : {0.0, 1.0, 2.0}) {
    const Model model = analyze("gabor", exemplar.view(), {{"colour_space", space}}, 0);
    const Errors e = measure(model, exemplar, 128, 3);
    print("grass_lawn_128, colour_space " + std::to_string(static_cast<int>(space)), e);
    const double gap = e.noise_covariance.mean - e.adsn_covariance.mean;
    if (space < 2.0)
      EXPECT_LE(gap, covariance_bound(e) + 0.05) << "colour space " << space;
    else
      EXPECT_GT(gap, covariance_bound(e) + 0.05) << "RGB keeps no cross-covariance";
  }
}

// The correlation matrix (n x n, row-major) of an image's channels.
std::vector<double> correlations(ImageView<const float> image) {
  const std::vector<double> c = colour_statistics(image).covariance;
  const auto n = static_cast<std::size_t>(image.channels);
  std::vector<double> r(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      r[i * n + j] = c[i * n + j] / std::sqrt(c[i * n + i] * c[j * n + j]);
  return r;
}

// The largest difference between two correlation matrices.
double correlation_error(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

TEST(GaborQuality, MaterialsKeepTheirCrossMapCorrelations) {
  // A material's maps analysed jointly (issue 18): rock_sandstone's five maps (9 channels) and
  // sand_pebbles' four (8), 128² crops, default parameters (the PCA colour space since issue 20),
  // 6 seeds of 128² renders against as many ADSN samples. The maps' scales differ (albedo,
  // metallic), so the measure is the correlation matrix: its largest difference to the crop's
  // must be at the ADSN level (4 pooled sd of one sample, as above; measured gaps 0.019 on rock
  // and 0.038 on sand against bounds 0.17 and 0.29), and the cross-map correlations of
  // data/materials must stay within 4 sd (over the seeds) of ADSN's estimate of them (measured,
  // crop / gabor / bound: albedo G vs normal.y 0.89 / 0.90 / 0.13, height vs ao 0.72 / 0.65 /
  // 0.24, roughness vs metallic -0.85 / -0.82 / 0.16). The test can fail: in the RGB colour space,
  // which synthesises each channel alone, the correlations vanish (largest errors 1.12 and 1.06,
  // the three pairs at 0.13, 0.15 and +0.18; measured).
  struct Pair {
    std::size_t i, j;
    const char* name;
  };
  struct Material {
    std::string set;
    std::vector<std::string> maps;
    std::vector<Pair> pairs;
  };
  const Material materials[] = {
      {"rock_sandstone",
       {"albedo", "normal", "roughness", "height", "ao"},
       {{1, 4, "albedo G vs normal.y"}, {7, 8, "height vs ao"}}},
      {"sand_pebbles",
       {"albedo", "normal", "roughness", "metallic"},
       {{6, 7, "roughness vs metallic"}}},
  };
  constexpr int kSeeds = 6;
  constexpr int kSide = 128;
  for (const Material& material : materials) {
    const ImageF full = test_support::material_exemplar(material.set, material.maps);
    const ImageView<const float> exemplar = full.view().sub(0, 0, kSide, kSide);
    const std::vector<double> target = correlations(exemplar);
    const auto n = static_cast<std::size_t>(exemplar.channels);
    const Model model = analyze("gabor", exemplar, {}, 0, material.set);
    std::vector<double> noise_error, adsn_error;
    std::vector<std::vector<double>> noise_pair(material.pairs.size()),
        adsn_pair(material.pairs.size());
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
      const std::vector<double> noise =
          correlations(render_noise(model, kSide, kSide, seed).view());
      const std::vector<double> gaussian = correlations(adsn(exemplar, kSide, kSide, seed).view());
      noise_error.push_back(correlation_error(noise, target));
      adsn_error.push_back(correlation_error(gaussian, target));
      for (std::size_t p = 0; p < material.pairs.size(); ++p) {
        const std::size_t k = material.pairs[p].i * n + material.pairs[p].j;
        noise_pair[p].push_back(noise[k]);
        adsn_pair[p].push_back(gaussian[k]);
      }
    }
    const Sample noise = summarise(noise_error), gaussian = summarise(adsn_error);
    std::cout << material.set << " (" << n << " channels): largest correlation error gabor "
              << noise.mean << " (sd " << noise.deviation << "), ADSN " << gaussian.mean << " (sd "
              << gaussian.deviation << ")\n";
    EXPECT_LE(noise.mean - gaussian.mean, 4.0 * pooled(noise, gaussian)) << material.set;
    for (std::size_t p = 0; p < material.pairs.size(); ++p) {
      const Pair& pair = material.pairs[p];
      const Sample r = summarise(noise_pair[p]), spread = summarise(adsn_pair[p]);
      const double exemplar_r = target[pair.i * n + pair.j];
      std::cout << "  " << pair.name << ": exemplar " << exemplar_r << ", gabor " << r.mean
                << " (sd " << r.deviation << "), ADSN " << spread.mean << " (sd "
                << spread.deviation << ")\n";
      EXPECT_NEAR(r.mean, exemplar_r, 4.0 * spread.deviation) << material.set << " " << pair.name;
    }
  }
}

TEST(GaborFiltering, MinifiedRendersMatchTheSupersampledReference) {
  // Filtering (Lagae et al. 2009, inherited by the paper, section 9.1): a render at scale s with
  // analytic filtering (each kernel convolved with the footprint's Gaussian) against the same
  // model supersampled s x s (the box filter of s x s exemplar pixels), scale 4 and 8, over
  // kSeeds seeds. Measured per seed: the variance ratio filtered / reference, and the spectral
  // error of the filtered render against the reference. The reference is a different draw of the
  // same field (the filter thins the process, section "Filtering" of docs/methods/gabor.md), so
  // the spectral error has a floor: the error between the references of two seeds, measured
  // alongside. Point sampling (no filter) shows that the measures can fail: it aliases.
  // Impulse budget 64 keeps the supersampled renders affordable (evaluation cost is linear in N).
  constexpr int kSeeds = 8;
  const ImageF exemplar = read_image(kTextureDir + "/grass_lawn_128.png");
  const Model model = analyze("gabor", exemplar.view(), {{"impulses", 64}}, 0);
  const auto total_variance = [](const ImageF& image) {
    const ColourStatistics stats = colour_statistics(image.view());
    return stats.covariance[0] + stats.covariance[4] + stats.covariance[8];
  };
  for (const int scale : {4, 8}) {
    const int side = scale == 4 ? 64 : 48;
    const int crop = side / 2;
    std::vector<double> ratio, unfiltered_ratio, spectral, unfiltered_spectral, floor;
    ImageF previous_reference;
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
      const ImageF filtered = render_noise(model, side, side, seed, scale);
      const ImageF unfiltered = render_noise(model, side, side, seed, scale, 1, false);
      ImageF reference = render_noise(model, side, side, seed, scale, scale);
      const double reference_variance = total_variance(reference);
      ratio.push_back(total_variance(filtered) / reference_variance);
      unfiltered_ratio.push_back(total_variance(unfiltered) / reference_variance);
      spectral.push_back(spectral_error(filtered.view(), reference.view(), crop));
      unfiltered_spectral.push_back(spectral_error(unfiltered.view(), reference.view(), crop));
      if (seed > 1)
        floor.push_back(spectral_error(reference.view(), previous_reference.view(), crop));
      previous_reference = std::move(reference);
    }
    const Sample r = summarise(ratio), u = summarise(unfiltered_ratio), e = summarise(spectral),
                 ue = summarise(unfiltered_spectral), f = summarise(floor);
    std::cout << "scale " << scale << ": variance filtered / supersampled " << r.mean << " (sd "
              << r.deviation << "), point-sampled / supersampled " << u.mean << " (sd "
              << u.deviation << "); spectral error vs supersampled: filtered " << e.mean << " (sd "
              << e.deviation << "), point-sampled " << ue.mean << " (sd " << ue.deviation
              << "), reference vs reference " << f.mean << " (sd " << f.deviation << ")\n";
    // Bounds: 3 standard errors of the mean over the seeds, plus the bias measured (the
    // Gaussian filter is not the box of the reference: variance 1.09 and 1.13 times the
    // reference's, spectral error 0.25 and 0.37 above the floor, at scales 4 and 8).
    const double root_seeds = std::sqrt(static_cast<double>(kSeeds));
    const double variance_bound = 0.15 + 3.0 * r.deviation / root_seeds;
    const double spectral_bound = f.mean + 0.45 + 3.0 * pooled(e, f) / root_seeds;
    EXPECT_NEAR(r.mean, 1.0, variance_bound) << "scale " << scale;
    EXPECT_LE(e.mean, spectral_bound) << "scale " << scale;
    EXPECT_GT(u.mean - 1.0, variance_bound) << "point sampling aliases, scale " << scale;
    EXPECT_GT(ue.mean, spectral_bound) << "point sampling aliases, scale " << scale;
  }
}

}  // namespace
}  // namespace stochtex::gabor_quality_test
