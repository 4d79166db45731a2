// Gabor noise by example (gabor-noise-by-example-2012): the alias tables (section 6.2), the
// spectrum fit by FISTA with its duality gap (section 5), the joint diagonalisation of the colour
// space (section 7), the evaluator's normalisation (eq. 5) and the model file.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <numbers>
#include <numeric>
#include <random>
#include <span>
#include <vector>

#include "core/hash.hpp"
#include "methods/gabor/alias.hpp"
#include "methods/gabor/analysis.hpp"
#include "methods/gabor/colour_space.hpp"
#include "methods/gabor/dictionary.hpp"
#include "methods/gabor/edit_analysis.hpp"
#include "methods/gabor/fit.hpp"
#include "methods/gabor/model.hpp"
#include "methods/gabor/simd.hpp"
#include "model/model_data.hpp"
#include "spectral/periodic.hpp"
#include "stochtex/error.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::gabor::gabor_test {
namespace {

// The probability that the table returns i: its own column's share plus the columns that alias
// to it, each column drawn with probability 1 / n.
std::vector<double> alias_distribution(const std::vector<float>& probability,
                                       const std::vector<std::uint32_t>& alias) {
  const std::size_t n = probability.size();
  std::vector<double> result(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    result[i] += probability[i] / static_cast<double>(n);
    result[alias[i]] += (1.0 - probability[i]) / static_cast<double>(n);
  }
  return result;
}

TEST(GaborAlias, TablesReproduceTheDistributionExactly) {
  std::mt19937 engine(3);
  std::exponential_distribution<double> exponential(1.0);
  std::vector<std::vector<double>> cases = {
      {1.0}, {1.0, 1.0, 1.0}, {5.0, 1.0}, {0.0, 3.0, 0.0, 1.0}, {1e-9, 1.0, 1e9}};
  std::vector<double> skewed(1000);
  for (double& w : skewed) w = std::pow(exponential(engine), 4.0);
  cases.push_back(skewed);
  for (const auto& weights : cases) {
    std::vector<float> probability(weights.size());
    std::vector<std::uint32_t> alias(weights.size());
    build_alias_table(weights, probability, alias);
    double total = 0.0;
    for (const double w : weights) total += w;
    const std::vector<double> distribution = alias_distribution(probability, alias);
    for (std::size_t i = 0; i < weights.size(); ++i) {
      EXPECT_GE(probability[i], 0.0f);
      EXPECT_LE(probability[i], 1.0f);
      EXPECT_LT(alias[i], weights.size());
      // Float storage of the column probabilities: relative error 2^-24 per column.
      EXPECT_NEAR(distribution[i], weights[i] / total, 1e-7) << "entry " << i;
    }
  }
}

TEST(GaborAlias, DrawsFollowTheDistribution) {
  const std::vector<double> weights = {0.1, 0.4, 0.2, 0.3};
  std::vector<float> probability(4);
  std::vector<std::uint32_t> alias(4);
  build_alias_table(weights, probability, alias);
  constexpr int kDraws = 400000;
  std::vector<int> counts(4, 0);
  CounterRng rng(cell_key(1, 2, 3, Stream::kernels));
  for (int i = 0; i < kDraws; ++i) ++counts[draw_alias(probability.data(), alias.data(), 4, rng)];
  // Chi-square with 3 degrees of freedom: 16.3 is the 0.1% quantile.
  double chi_square = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double expected = weights[static_cast<std::size_t>(i)] * kDraws;
    chi_square += (counts[i] - expected) * (counts[i] - expected) / expected;
  }
  EXPECT_LT(chi_square, 16.3);
}

// A synthetic spectrum made of known Gaussians of the dictionary (each with its mirror).
struct KnownAtom {
  int band_index;
  int x;
  int y;
  float coefficient;
};

std::vector<std::vector<float>> place(const GaussianDictionary& dictionary,
                                      const std::vector<KnownAtom>& atoms) {
  const int w = dictionary.width();
  const int h = dictionary.height();
  std::vector<std::vector<float>> alpha(static_cast<std::size_t>(dictionary.band_count()),
                                        std::vector<float>(dictionary.plane_size(), 0.0f));
  for (const KnownAtom& atom : atoms) {
    auto& plane = alpha[static_cast<std::size_t>(atom.band_index)];
    plane[static_cast<std::size_t>((atom.y + h) % h) * w + (atom.x + w) % w] = atom.coefficient;
    plane[static_cast<std::size_t>((-atom.y + h) % h) * w + (-atom.x + w) % w] = atom.coefficient;
  }
  return alpha;
}

// The certificate: the primal value at the stop exceeds the optimum (approached here by a much
// longer run) by no more than the gap reported at the stop.
void expect_gap_certifies(const GaussianDictionary& dictionary, std::span<const float> target,
                          const SpectrumFit& fit, FitOptions options) {
  options.kappa = fit.nu / fit.nu_max;
  options.gap_tolerance = 1e-5;
  options.max_iterations = 6000;
  const SpectrumFit optimum = fit_spectrum(dictionary, target, options);
  EXPECT_GE(fit.primal - optimum.primal, -1e-6 * fit.primal);
  EXPECT_LE(fit.primal - optimum.primal, fit.gap + 1e-6 * fit.primal);
}

// Each known atom's coefficient (a side x side plane) within `tolerance` of its value.
void expect_atoms(const SpectrumFit& fit, const std::vector<KnownAtom>& atoms, int side,
                  double tolerance) {
  for (const KnownAtom& atom : atoms) {
    const float found =
        fit.alpha[static_cast<std::size_t>(atom.band_index)]
                 [static_cast<std::size_t>((atom.y + side) % side) * side + (atom.x + side) % side];
    EXPECT_NEAR(found, atom.coefficient, tolerance * atom.coefficient)
        << "band " << atom.band_index << " at " << atom.x << ", " << atom.y;
  }
}

TEST(GaborFit, RecoversKnownGaussiansAndTheGapCertifiesTheStop) {
  const GaussianDictionary dictionary(64, 64);
  ASSERT_EQ(dictionary.band_count(), 7);  // FWHM 64, 32, ..., 1 bins
  // Bands 2, 4 and 6 (FWHM 16, 4 and 1 bins; sub-grid steps 8, 2 and 1) at positions on their
  // sub-grids, well apart.
  const std::vector<KnownAtom> atoms = {
      {2, 16, 16, 2.0f}, {4, -20, 8, 1.0f}, {6, 5, -12, 0.5f}, {6, 24, -24, 0.25f}};
  for (const KnownAtom& atom : atoms) {
    ASSERT_EQ((atom.x + 64) % 64 % dictionary.step_x(atom.band_index), 0);
    ASSERT_EQ((atom.y + 64) % 64 % dictionary.step_y(atom.band_index), 0);
  }
  std::vector<float> target;
  dictionary.apply(place(dictionary, atoms), target);

  FitOptions options;
  options.kappa = 1.0 / 1024.0;
  options.max_iterations = 3000;
  options.gap_tolerance = 1e-3;
  const SpectrumFit fit = fit_spectrum(dictionary, target, options);
  EXPECT_TRUE(fit.converged);
  EXPECT_EQ(fit.steps, 10);  // kappa = 1/2, ..., 1/1024
  EXPECT_LE(fit.gap, 1e-3 * fit.primal);

  // Positions and bandwidths: each known atom keeps its coefficient up to the l1 shrinkage
  // (nu / 2 per unit-norm column, below 1% here), and what lands elsewhere is a small fraction.
  double elsewhere = 0.0;
  double total = 0.0;
  const std::vector<std::vector<float>> truth = place(dictionary, atoms);
  for (int b = 0; b < dictionary.band_count(); ++b)
    for (std::size_t i = 0; i < dictionary.plane_size(); ++i) {
      const float value = fit.alpha[static_cast<std::size_t>(b)][i];
      total += value;
      if (truth[static_cast<std::size_t>(b)][i] == 0.0f) elsewhere += value;
    }
  EXPECT_LT(elsewhere, 0.02 * total);
  expect_atoms(fit, atoms, 64, 0.03);
  EXPECT_LT(fit.residual_norm, 0.01 * fit.target_norm);

  expect_gap_certifies(dictionary, target, fit, options);
}

double squared_norm(const std::vector<float>& values) {
  double sum = 0.0;
  for (const float v : values) sum += static_cast<double>(v) * v;
  return sum;
}

TEST(GaborFit, WeightsFollowTheSmoothedPeriodogramLevel) {
  constexpr int n = 64;
  std::vector<float> periodogram(static_cast<std::size_t>(n) * n, 1.0f);
  EXPECT_TRUE(spectrum_weights(periodogram, n, n, 0.0).empty());  // the paper's unweighted fit
  for (const float w : spectrum_weights(periodogram, n, n, 0.25)) EXPECT_NEAR(w, 1.0f, 1e-5f);
  // Two levels, 1 and 1/16 (rows 0-31 and 32-63); then a zero quarter, floored at 1e-6 of the
  // peak. Far from the borders (several smoothing widths) the weight is (level / peak)^-gamma.
  for (int y = n / 2; y < n; ++y)
    for (int x = 0; x < n; ++x)
      periodogram[static_cast<std::size_t>(y) * n + x] = x < n / 2 ? 1.0f / 16.0f : 0.0f;
  const std::vector<float> weights = spectrum_weights(periodogram, n, n, 0.25);
  const auto at = [&](int x, int y) { return weights[static_cast<std::size_t>(y) * n + x]; };
  EXPECT_NEAR(at(16, 16), 1.0f, 1e-3f);
  EXPECT_NEAR(at(16, 48), 2.0f, 2e-3f);                  // 16^(1/4)
  EXPECT_NEAR(at(48, 48), std::pow(1e6f, 0.25f), 0.5f);  // the floor
  // In between the weight rises smoothly (a Gaussian of 2 bins): no jump of a factor 2 at once.
  for (int y = 24; y < 40; ++y) {
    EXPECT_GE(at(16, y + 1), at(16, y) * 0.999f);
    EXPECT_LT(at(16, y + 1), at(16, y) * 1.6f);
  }
}

// The automatic coarse fit of an exemplar larger than 256² runs on the decimated periodogram: it
// must keep the variance (the sum), the symmetry m -> -m of a periodogram, and put a bin's power
// on the coarse bins around it with the tent weights.
TEST(GaborFit, DecimatedSpectrumKeepsTheVarianceAndTheSymmetry) {
  constexpr int width = 32;
  constexpr int height = 16;
  std::vector<float> plane(static_cast<std::size_t>(width) * height);
  std::mt19937 random(5);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t index = static_cast<std::size_t>(y) * width + x;
      const std::size_t mirror =
          static_cast<std::size_t>((height - y) % height) * width + (width - x) % width;
      plane[index] = mirror < index ? plane[mirror] : uniform(random);
    }
  for (const int factor : {2, 4}) {
    const int cw = width / factor;
    const int ch = height / factor;
    const std::vector<float> coarse = decimate_spectrum(plane, width, height, factor);
    ASSERT_EQ(coarse.size(), static_cast<std::size_t>(cw) * ch);
    EXPECT_NEAR(std::accumulate(coarse.begin(), coarse.end(), 0.0),
                std::accumulate(plane.begin(), plane.end(), 0.0), 1e-4);
    for (int y = 0; y < ch; ++y)
      for (int x = 0; x < cw; ++x)
        EXPECT_FLOAT_EQ(coarse[static_cast<std::size_t>(y) * cw + x],
                        coarse[static_cast<std::size_t>((ch - y) % ch) * cw + (cw - x) % cw]);
  }
  // One bin at (3, 0): factor 2 puts 1/2 on coarse bins 1 and 2 of row 0, nothing elsewhere.
  std::vector<float> single(plane.size(), 0.0f);
  single[3] = 1.0f;
  const std::vector<float> coarse = decimate_spectrum(single, width, height, 2);
  for (std::size_t i = 0; i < coarse.size(); ++i)
    EXPECT_FLOAT_EQ(coarse[i], i == 1 || i == 2 ? 0.5f : 0.0f) << i;
}

TEST(GaborFit, WeightedFitConvergesWithPerCoefficientSteps) {
  // The known Gaussians of RecoversKnownGaussians..., fitted through data weights. The diagonal
  // preconditioner lets every coefficient move at its own pace: with gamma = 1 (relative errors:
  // weights over three orders of magnitude) the fit reaches the gap tolerance, and the gap
  // certifies it against a longer run; with the default gamma = 1/4 it finds the atoms (the
  // l1 shrinkage of gamma = 1's weights moves them). The reported norms are the unweighted ones.
  const std::vector<KnownAtom> atoms = {
      {2, 16, 16, 2.0f}, {4, -20, 8, 1.0f}, {6, 5, -12, 0.5f}, {6, 24, -24, 0.25f}};
  for (const double gamma : {1.0, 0.25}) {
    GaussianDictionary dictionary(64, 64);
    std::vector<float> spectrum;
    dictionary.apply(place(dictionary, atoms), spectrum);
    std::vector<float> weights = spectrum_weights(spectrum, 64, 64, gamma);
    const float spread = *std::max_element(weights.begin(), weights.end()) /
                         *std::min_element(weights.begin(), weights.end());
    EXPECT_GT(spread, gamma == 1.0 ? 1000.0f : 5.0f);
    std::vector<float> target = spectrum;
    for (std::size_t i = 0; i < target.size(); ++i) target[i] *= weights[i];
    dictionary.set_weights(std::move(weights));

    FitOptions options;
    options.kappa = 1.0 / 1024.0;
    options.max_iterations = 3000;
    options.gap_tolerance = 1e-3;
    const SpectrumFit fit = fit_spectrum(dictionary, target, options);
    EXPECT_NEAR(fit.target_norm, std::sqrt(squared_norm(spectrum)), 1e-5 * fit.target_norm);
    if (gamma == 1.0) {
      EXPECT_TRUE(fit.converged);
      EXPECT_LE(fit.gap, 1e-3 * fit.primal);
      expect_gap_certifies(dictionary, target, fit, options);
      continue;
    }
    EXPECT_LT(fit.residual_norm, 0.02 * fit.target_norm);
    expect_atoms(fit, atoms, 64, 0.05);
  }
}

TEST(GaborFit, DualityGapIsZeroOnlyAtTheOptimum) {
  const GaussianDictionary dictionary(32, 32);
  const std::vector<KnownAtom> atoms = {{3, 4, 4, 1.0f}};
  std::vector<float> target;
  dictionary.apply(place(dictionary, atoms), target);
  const std::vector<std::vector<float>> zero(static_cast<std::size_t>(dictionary.band_count()),
                                             std::vector<float>(dictionary.plane_size(), 0.0f));
  // At alpha = 0 with nu >= nu_max, 0 is optimal: the gap vanishes; with nu below it does not.
  FitOptions options;
  const SpectrumFit fit = fit_spectrum(dictionary, target, options);
  EXPECT_NEAR(duality_gap(dictionary, target, zero, fit.nu_max).gap, 0.0,
              1e-6 * squared_norm(target));
  EXPECT_GT(duality_gap(dictionary, target, zero, 0.5 * fit.nu_max).gap,
            0.1 * squared_norm(target));
}

Matrix multiply(const Matrix& a, const Matrix& b, int n, bool transpose_b = false) {
  Matrix result(static_cast<std::size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        result[static_cast<std::size_t>(i) * n + j] +=
            a[static_cast<std::size_t>(i) * n + k] * (transpose_b
                                                          ? b[static_cast<std::size_t>(j) * n + k]
                                                          : b[static_cast<std::size_t>(k) * n + j]);
  return result;
}

TEST(GaborColour, JointDiagonalisationFindsTheCommonBasis) {
  // C_k = B D_k B^T for a non-orthogonal mixing B and random diagonal D_k (C_0 positive): the
  // matrices share the basis B^-T exactly. T must diagonalise all of them, so T B is a scaled
  // permutation; PCA (which only diagonalises C_0) must not.
  constexpr int n = 3;
  const Matrix mixing = {1.0, 0.6, 0.2, 0.3, 1.0, -0.4, 0.5, 0.1, 1.0};
  std::mt19937 engine(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Matrix> correlations;
  for (int k = 0; k < 12; ++k) {
    Matrix diagonal(n * n, 0.0);
    for (int i = 0; i < n; ++i)
      diagonal[static_cast<std::size_t>(i) * n + i] = k == 0 ? 1.0 + i : normal(engine);
    correlations.push_back(multiply(multiply(mixing, diagonal, n), mixing, n, true));
  }
  const Matrix transform = joint_diagonalizer(correlations, n);
  EXPECT_LT(off_diagonality(transform, correlations, n), 1e-12);
  const Matrix product = multiply(transform, mixing, n);
  for (int i = 0; i < n; ++i) {
    double largest = 0.0;
    double row = 0.0;
    for (int j = 0; j < n; ++j) {
      const double v = product[static_cast<std::size_t>(i) * n + j];
      largest = std::max(largest, v * v);
      row += v * v;
    }
    EXPECT_GT(largest / row, 1.0 - 1e-10) << "row " << i;
  }
  EXPECT_GT(off_diagonality(principal_axes(correlations.front(), n), correlations, n), 1e-3);
}

// A model made of given Gaussians (grey unless `channels` says otherwise).
GaborModel model_of(std::vector<GaussianComponent> gaussians, int channels = 1,
                    double impulses = 256) {
  std::vector<float> mixing(static_cast<std::size_t>(channels) * channels, 0.0f);
  for (int c = 0; c < channels; ++c) mixing[static_cast<std::size_t>(c) * channels + c] = 1.0f;
  return GaborModel(channels, impulses, 0, std::move(gaussians), mixing,
                    std::vector<float>(static_cast<std::size_t>(channels), 0.5f), FitReport{});
}

struct Moments {
  double mean = 0;
  double variance = 0;
};

Moments sample_moments(const GaborModel& model, std::uint32_t seed, double spacing = 37.3,
                       const std::vector<Footprint>& footprints = {}) {
  constexpr int kSamples = 20000;
  std::vector<Vec2d> positions;
  for (int i = 0; i < kSamples; ++i)
    positions.push_back({spacing * (i % 200), spacing * (i / 200)});
  std::vector<Footprint> fps = footprints;
  if (!fps.empty()) fps.assign(positions.size(), footprints.front());
  ImageF out(kSamples, 1, model.channels());
  model.evaluate(positions, fps, seed, out.view());
  double sum = 0.0, square = 0.0;
  for (const float v : out.pixels()) {
    sum += v;
    square += static_cast<double>(v) * v;
  }
  const double count = static_cast<double>(out.pixels().size());
  return {sum / count, square / count - (sum / count) * (sum / count)};
}

// Surface noise skips the kernel draws of an impulse it rejects (GridKernels::kDraws): the draws
// after the skip must be those after a kernel drawn, or every later impulse would change.
TEST(GaborEvaluate, ASkippedKernelPassesOverTheDrawsOfADrawnOne) {
  const float frequency_x[2] = {0.1f, 0.2f};
  const float frequency_y[2] = {-0.1f, 0.05f};
  const float probability[2] = {0.5f, 1.0f};
  const std::uint32_t alias[2] = {1, 1};
  const GridKernels kernels{frequency_x, frequency_y, probability, alias, 2};
  for (std::uint32_t key = 1; key <= 8; ++key) {
    CounterRng drawn(key);
    CounterRng skipped(key);
    float wx, wy, phase;
    kernels.draw(drawn, wx, wy, phase);
    skipped.skip(GridKernels::kDraws);
    EXPECT_EQ(drawn.next(), skipped.next()) << key;
  }
}

TEST(GaborEvaluate, VarianceIsTheSumOfTheGaussiansVariances) {
  // Eq. (5) with p = sigma_g^2 / sigma_b^2: whatever the budget split, the noise variance is the
  // sum of the variances (samples 37 pixels apart are nearly independent: relative standard error
  // of the variance ~ sqrt(2 / 20000) = 1%).
  const GaborModel model = model_of({{0, 3, 0.05f, 0.02f, 0.004f},
                                     {0, 3, -0.1f, 0.2f, 0.002f},
                                     {0, 5, 0.01f, 0.0f, 0.003f},
                                     {0, 1, 0.3f, -0.25f, 0.001f}});
  ASSERT_EQ(model.grids().size(), 3u);
  double variance = 0.0;
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const Moments moments = sample_moments(model, seed);
    EXPECT_NEAR(moments.mean, 0.5, 4.0 * std::sqrt(0.01 / 20000.0));
    variance += moments.variance / 3.0;
  }
  EXPECT_NEAR(variance / 0.01, 1.0, 0.05);
}

TEST(GaborEvaluate, FootprintAttenuatesAsTheGaussianPixelFilter) {
  // One Gaussian at frequency 0.25 of bandwidth a_3: a footprint of scale s (box variance s^2/12
  // beyond the exemplar pixel's 1/12) scales its power by exp(-4 pi^2 (s^2 - 1) / 12 |omega'|^2)
  // in the narrow-band limit; the exact attenuation of eq. (3) filtered is computed here as the
  // integral of the filtered spectrum.
  const GaborModel model = model_of({{0, 3, 0.25f, 0.0f, 0.01f}}, 1, 1024);
  const double scale = 2.0;
  const double filter = 2.0 * std::numbers::pi * std::numbers::pi * (scale * scale - 1.0) / 12.0;
  const double a = bandwidth(3);
  const double precision = std::numbers::pi / (a * a);
  // Power spectrum of the kernel ~ exp(-2 P |xi - omega|^2) (P = pi / a^2); the filter squared
  // is exp(-2 Q |xi|^2): the filtered power is exp(-2 P Q / (P + Q) |omega|^2) (P / (P + Q)).
  const double expected = std::exp(-2.0 * precision * filter / (precision + filter) * 0.0625) *
                          precision / (precision + filter);
  const Moments point = sample_moments(model, 4);
  const Moments filtered = sample_moments(model, 4, 37.3, {Footprint{{scale, 0.0}, {0.0, scale}}});
  EXPECT_NEAR(filtered.variance / point.variance, expected, 0.06 * expected);
}

TEST(GaborEvaluate, HugeFootprintsGiveTheMeanQuickly) {
  // A footprint of 1e12 pixels averages the noise away; the thinned levels end and the grids are
  // skipped instead of visiting ~1e12 cells. A DC Gaussian is the slowest to vanish.
  const GaborModel model = model_of({{0, 8, 0.0f, 0.0f, 0.01f}, {0, 2, 0.2f, 0.1f, 0.01f}});
  const std::vector<Vec2d> positions = {{0.5, 0.5}, {3e6, -2e6}};
  const std::vector<Footprint> footprints(2, Footprint{{1e12, 0.0}, {0.0, 1e12}});
  ImageF out(2, 1, 1);
  model.evaluate(positions, footprints, 1, out.view());
  EXPECT_NEAR(out.at(0, 0, 0), 0.5f, 1e-6f);
  EXPECT_NEAR(out.at(1, 0, 0), 0.5f, 1e-6f);
}

TEST(GaborEvaluate, NoiseIsContinuousAcrossTheKernelsCut) {
  // Samples 1e-5 pixels apart along a 0.45-pixel path, which crosses the support's edge of many
  // kernels. Tapered (kTaperScale), the noise is smooth: every increment is the gradient's, and the
  // largest of 40 000 is measured at 1.77 times their median. Cut hard, each crossing jumps by
  // e^-pi of a kernel's amplitude times its cosine (up to 0.01 of the noise's deviation at 256
  // impulses): measured 283 times the median with kTaperScale = 1e7 (a taper of 1e-7).
  const GaborModel model = model_of({{0, 3, 0.05f, 0.02f, 0.004f}, {0, 1, 0.3f, -0.25f, 0.004f}});
  constexpr int kSamples = 40000;
  std::vector<Vec2d> positions;
  for (int i = 0; i < kSamples; ++i) positions.push_back({3.3 + 1e-5 * i, 5.1 - 0.5e-5 * i});
  ImageF out(kSamples, 1, 1);
  model.evaluate(positions, {}, 2, out.view());
  std::vector<double> increments;
  for (int i = 1; i < kSamples; ++i)
    increments.push_back(std::abs(out.at(i, 0, 0) - out.at(i - 1, 0, 0)));
  const double largest = *std::max_element(increments.begin(), increments.end());
  std::nth_element(increments.begin(), increments.begin() + kSamples / 2, increments.end());
  const double median = increments[kSamples / 2];
  std::cout << "largest increment " << largest / median << " times the median " << median << "\n";
  EXPECT_LT(largest, 10.0 * median);
}

TEST(GaborEvaluate, FarFromTheOriginIsAsPreciseAsAtTheOrigin) {
  // A narrow-band noise sampled 0.05 pixels apart: with positions in float near 1e7 (spacing 1)
  // neighbouring samples would repeat; with 64-bit cells and local offsets they vary as at 0.
  const GaborModel model = model_of({{0, 6, 0.2f, 0.1f, 0.01f}});
  // The ratio of the squared increments to the variance along the path measures the local
  // frequency content, the same at every position for a stationary field: it is ~(2 pi 0.05)^2
  // |omega . direction|^2 here, and collapses to ~0 when the positions lose their precision.
  const auto roughness = [&](double origin) {
    double energy = 0.0;
    double sum = 0.0;
    double square = 0.0;
    for (std::uint32_t seed = 1; seed <= 4; ++seed) {
      std::vector<Vec2d> positions;
      for (int i = 0; i < 4000; ++i) positions.push_back({origin + 0.05 * i, origin - 0.05 * i});
      ImageF out(4000, 1, 1);
      model.evaluate(positions, {}, seed, out.view());
      for (int i = 0; i < 4000; ++i) {
        const double v = out.at(i, 0, 0);
        sum += v;
        square += v * v;
        if (i > 0) {
          const double d = v - out.at(i - 1, 0, 0);
          energy += d * d;
        }
      }
    }
    const double count = 16000.0;
    return energy / (square / count - (sum / count) * (sum / count)) / count;
  };
  const double near = roughness(0.0);
  const double far = roughness(1e7);
  const double expected = std::pow(2.0 * std::numbers::pi * 0.05 * (0.2 - 0.1), 2.0);
  EXPECT_NEAR(near / expected, 1.0, 0.2);
  EXPECT_NEAR(far / expected, 1.0, 0.2);
}

// A gabor model of a 32² exemplar for the file, threading and report checks: 20 FISTA iterations
// per homotopy step (CpuTargets' budget) give it Gaussians in every band the fit reaches; the
// fit's own convergence is GaborFit's.
Model analysed_model(int channels, double colour_space = 0) {
  std::mt19937 engine(4);
  std::normal_distribution<float> normal(0.5f, 0.1f);
  ImageF exemplar(32, 32, channels);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const float shared = normal(engine);
      for (int c = 0; c < channels; ++c)
        exemplar.at(x, y, c) = 0.6f * shared + 0.4f * normal(engine) +
                               0.05f * static_cast<float>(std::sin(0.7 * x + c));
    }
  return analyze("gabor", exemplar.view(),
                 {{"colour_space", colour_space}, {"impulses", 64}, {"iterations", 20}}, 1);
}

TEST(GaborModelFile, RoundTripIsExactAndEvaluatesTheSame) {
  // Up to kMaxChannels: a material's maps analysed and evaluated jointly.
  for (const int channels : {1, 3, 4, 9, kMaxChannels}) {
    const Model model = analysed_model(channels);
    EXPECT_EQ(model.method(), "gabor");
    const std::vector<std::uint8_t> bytes = serialize_model(model);
    const Model loaded = deserialize_model(bytes, "memory");
    EXPECT_EQ(serialize_model(loaded), bytes);
    const std::vector<Vec2d> points = {{0.5, 0.5}, {100.25, -7.0}, {1e7, 3e6}};
    const std::vector<Footprint> footprints(3, Footprint{{3.0, 0.5}, {0.0, 2.0}});
    ImageF a(3, 1, channels), b(3, 1, channels);
    evaluate(model, points, footprints, 5, a.view());
    evaluate(loaded, points, footprints, 5, b.view());
    EXPECT_TRUE(test_support::same_bytes(a, b));
  }
}

TEST(GaborModelFile, RenderIsBitIdenticalWhateverTheThreadsAndTiles) {
  const Model model = analysed_model(3);
  for (const double scale : {1.0, 5.0}) {
    const Grid grid{{-30.5, 12.25}, scale, 41, 37};
    ImageF a(41, 37, 3), b(41, 37, 3);
    RenderOptions one;
    one.threads = 1;
    RenderOptions many;
    many.threads = 3;
    many.tile_size = 7;
    render(model, grid, 3, a.view(), one);
    render(model, grid, 3, b.view(), many);
    EXPECT_TRUE(test_support::same_bytes(a, b));
  }
}

TEST(GaborModelFile, CorruptRecordsAreRejected) {
  const Model model = analysed_model(3);
  const ModelRecord good = std::get<GaborModel>(model.data().model).to_record(model.params());
  ASSERT_NO_THROW(GaborModel::from_record(good, "model.stx"));
  const auto gaussian_value = [](ModelRecord& r, std::size_t column) -> float& {
    for (auto& array : r.arrays)
      if (array.name == "gaussians") return array.values[column];
    throw std::logic_error("no gaussians");
  };
  const std::vector<std::pair<std::string, std::function<void(ModelRecord&)>>> corruptions = {
      {"channel out of range", [&](ModelRecord& r) { gaussian_value(r, 0) = 3.0f; }},
      {"fractional band", [&](ModelRecord& r) { gaussian_value(r, 1) = 1.5f; }},
      {"band too large", [&](ModelRecord& r) { gaussian_value(r, 1) = 16.0f; }},
      {"frequency beyond Nyquist", [&](ModelRecord& r) { gaussian_value(r, 2) = 0.7f; }},
      {"NaN frequency", [&](ModelRecord& r) { gaussian_value(r, 3) = NAN; }},
      {"negative variance", [&](ModelRecord& r) { gaussian_value(r, 4) = -1.0f; }},
      {"infinite variance", [&](ModelRecord& r) { gaussian_value(r, 4) = INFINITY; }},
      {"impulse budget too large", [](ModelRecord& r) { r.scalars["impulses"] = 1e9; }},
      {"impulse budget zero", [](ModelRecord& r) { r.scalars["impulses"] = 0; }},
      {"channels disagreeing with the arrays", [](ModelRecord& r) { r.scalars["channels"] = 5; }},
      {"count mismatch", [](ModelRecord& r) { r.scalars["gaussians"] += 1; }},
      {"too many Gaussians", [](ModelRecord& r) { r.scalars["gaussians"] = 1e12; }},
      {"negative report", [](ModelRecord& r) { r.scalars["fit_error"] = -1; }},
      {"missing colour", [](ModelRecord& r) { r.arrays.erase(r.arrays.begin() + 1); }},
      {"NaN colour", [](ModelRecord& r) { r.arrays[1].values[4] = NAN; }},
      {"NaN mean", [](ModelRecord& r) { r.arrays[2].values[0] = NAN; }},
  };
  for (const auto& [what, corrupt] : corruptions) {
    ModelRecord record = good;
    corrupt(record);
    test_support::expect_record_rejected<GaborModel>(record, what);
  }
}

TEST(GaborModelFile, HostileChannelCountsAreRefusedBeforeTheArraysAreRead) {
  // The count is read and checked first: a file cannot size the colour matrix, the mean or the
  // renderer's buffers. With the arrays gone, only the count's own check can refuse it by name.
  const Model model = analysed_model(9);
  ModelRecord good = std::get<GaborModel>(model.data().model).to_record(model.params());
  ASSERT_NO_THROW(GaborModel::from_record(good, "model.stx"));
  good.arrays.clear();
  for (const double channels : {0.0, -1.0, 2.5, double{kMaxChannels} + 1.0, 1e9, 1e300,
                                static_cast<double>(NAN), static_cast<double>(INFINITY)}) {
    ModelRecord record = good;
    record.scalars["channels"] = channels;
    try {
      GaborModel::from_record(record, "bad.stx");
      ADD_FAILURE() << channels << " channels: accepted";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("channels"), std::string::npos)
          << channels << ": " << error.what();
    }
  }
}

TEST(GaborAnalysis, ReportsSparsenessFitErrorAndOffDiagonality) {
  const Model model = analysed_model(3);
  const GaborModel& gabor = std::get<GaborModel>(model.data().model);
  const FitReport& report = gabor.report();
  EXPECT_GT(report.sparseness, 0.0);
  EXPECT_LT(report.sparseness, 1.0);
  EXPECT_GT(report.fit_error, 0.0);
  EXPECT_LT(report.fit_error, 1.0);
  // The channels share most of their signal: RGB is far from diagonal, the two decorrelating
  // spaces are not, and the joint diagonaliser is at least as good as PCA on its own criterion.
  EXPECT_GT(report.offdiagonality_rgb, 0.3);
  EXPECT_LT(report.offdiagonality_pca, report.offdiagonality_rgb);
  EXPECT_LE(report.offdiagonality_independent, report.offdiagonality_pca * 1.0001);
}

int finest_band(const Model& model) {
  int finest = 0;
  for (const GaussianComponent& g : std::get<GaborModel>(model.data().model).gaussians())
    finest = std::max(finest, g.band);
  return finest;
}

TEST(GaborAnalysis, NarrowestBandIsChosenFromTheSpectrum) {
  // 64² grey exemplars: white noise (a diffuse spectrum) and the same noise under a strong wave
  // on a frequency bin (a one-bin peak). Band b spans 64 / 2^b bins: 4 bins is band 4, 1 bin
  // band 6.
  std::mt19937 engine(11);
  std::normal_distribution<float> normal(0.5f, 0.1f);
  ImageF diffuse(64, 64, 1);
  ImageF peaked(64, 64, 1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      diffuse.at(x, y, 0) = normal(engine);
      peaked.at(x, y, 0) = diffuse.at(x, y, 0) +
                           0.3f * static_cast<float>(std::cos(2.0 * std::numbers::pi * 5 * x / 64));
    }
  const auto finest = [&](const ImageF& exemplar, double narrowest) {
    return finest_band(analyze("gabor", exemplar.view(), {{"narrowest", narrowest}}, 1));
  };
  // Automatic (the default): the diffuse spectrum keeps the 4-bin dictionary; the peak's 4-bin
  // fit inflates the variance, so it is fitted down to one bin.
  EXPECT_LE(finest(diffuse, 0), 4);
  EXPECT_EQ(finest(peaked, 0), 6);
  // Fixed: 1 is the paper's dictionary, whose one-bin Gaussians fit the periodogram's noise.
  EXPECT_EQ(finest(diffuse, 1), 6);
  EXPECT_LE(finest(peaked, 4), 4);
  EXPECT_LE(finest(diffuse, 16), 2);
}

TEST(GaborAnalysis, RenormalisedNoiseHasThePeriodogramsVariance) {
  // A diffuse 64² grey exemplar at a coarse kappa: the l1 shrinkage lowers the fitted variance;
  // renormalise (the default) restores the periodic component's variance, as ADSN has it.
  std::mt19937 engine(12);
  std::normal_distribution<float> normal(0.5f, 0.1f);
  ImageF exemplar(64, 64, 1);
  for (float& v : exemplar.pixels()) v = normal(engine);
  const ImageF periodic = periodic_component(exemplar.view());
  std::vector<float> plane(periodic.pixels().begin(), periodic.pixels().end());
  const double mean =
      std::accumulate(plane.begin(), plane.end(), 0.0) / static_cast<double>(plane.size());
  for (float& v : plane) v = static_cast<float>(v - mean);
  const std::vector<float> spectrum = periodogram(plane, 64, 64);
  const double target = std::accumulate(spectrum.begin(), spectrum.end(), 0.0);
  const auto variance = [&](double renormalise) {
    const Model model =
        analyze("gabor", exemplar.view(), {{"kappa", 1.0 / 16.0}, {"renormalise", renormalise}}, 1);
    double sum = 0.0;
    for (const GaussianComponent& g : std::get<GaborModel>(model.data().model).gaussians())
      sum += g.variance;
    return sum;
  };
  EXPECT_LT(variance(0.0), 0.97 * target);
  EXPECT_NEAR(variance(1.0), target, 1e-4 * target);
}

TEST(GaborEdit, TransformsTheSelectedGaussiansOnly) {
  const GaborModel model = model_of(
      {{0, 3, 0.1f, 0.0f, 0.004f}, {0, 5, 0.0f, 0.2f, 0.002f}, {0, 7, 0.4f, 0.0f, 0.001f}});
  // Rotate by 90 degrees and double the magnitude K (4 x the variance) of bands 3-5.
  GaussianGroup group;
  group.last_band = 5;
  SpectrumEdit rotate;
  rotate.rotation = std::numbers::pi / 2.0;
  rotate.magnitude = 2.0;
  const GaborModel rotated = edit_gaussians(model, group, rotate);
  ASSERT_EQ(rotated.gaussians().size(), 3u);
  EXPECT_NEAR(rotated.gaussians()[0].frequency_x, 0.0f, 1e-7f);
  EXPECT_NEAR(rotated.gaussians()[0].frequency_y, 0.1f, 1e-7f);
  EXPECT_NEAR(rotated.gaussians()[1].frequency_x, -0.2f, 1e-7f);
  EXPECT_FLOAT_EQ(rotated.gaussians()[1].variance, 0.008f);
  EXPECT_FLOAT_EQ(rotated.gaussians()[2].frequency_x, 0.4f);  // band 7: not in the group
  EXPECT_FLOAT_EQ(rotated.gaussians()[2].variance, 0.001f);

  // Scaling all frequencies by 2 pushes 0.4 beyond Nyquist: that Gaussian is dropped. A band
  // shift of +1 narrows the spectral Gaussians (a_{b+1} = a_b / 2).
  SpectrumEdit scale;
  scale.scale = 2.0;
  scale.bandwidth_shift = 1;
  const GaborModel scaled = edit_gaussians(model, GaussianGroup{}, scale);
  ASSERT_EQ(scaled.gaussians().size(), 2u);
  EXPECT_FLOAT_EQ(scaled.gaussians()[0].frequency_x, 0.2f);
  EXPECT_EQ(scaled.gaussians()[0].band, 4);
  EXPECT_EQ(scaled.gaussians()[1].band, 6);

  // A selection by flags edits exactly the flagged Gaussians; magnitude 0 removes them.
  SpectrumEdit silence;
  silence.magnitude = 0.0;
  const GaborModel silenced = edit_gaussians(model, std::vector<bool>{false, true, false}, silence);
  ASSERT_EQ(silenced.gaussians().size(), 2u);
  EXPECT_FLOAT_EQ(silenced.gaussians()[1].frequency_x, 0.4f);
  EXPECT_THROW(edit_gaussians(model, std::vector<bool>{true}, silence), std::invalid_argument);
  EXPECT_THROW(edit_gaussians(model, GaussianGroup{}, silence), std::invalid_argument);

  SpectrumEdit bad;
  bad.magnitude = -1.0;
  EXPECT_THROW(edit_gaussians(model, GaussianGroup{}, bad), std::invalid_argument);
  bad.magnitude = 1.0;
  bad.rotation = NAN;
  EXPECT_THROW(edit_gaussians(model, GaussianGroup{}, bad), std::invalid_argument);
}

TEST(GaborEdit, MagnitudeScalesTheRenderedVarianceByItsSquare) {
  // Section 8: the magnitude is the kernel amplitude K (eq. 2); the variance K^2 / (4 a^2)
  // scales by its square. Same seeds and impulses: only the amplitudes change, so the ratio is
  // exact up to float rounding. Editing one group leaves the other's variance as it was.
  const GaborModel model = model_of({{0, 3, 0.1f, 0.05f, 0.004f}, {0, 5, -0.2f, 0.1f, 0.002f}});
  SpectrumEdit louder;
  louder.magnitude = 3.0;
  double before = 0.0, after = 0.0, partial = 0.0;
  for (std::uint32_t seed = 1; seed <= 2; ++seed) {
    before += sample_moments(model, seed).variance;
    after += sample_moments(edit_gaussians(model, GaussianGroup{}, louder), seed).variance;
    partial += sample_moments(edit_gaussians(model, std::vector<bool>{false, true}, louder), seed)
                   .variance;
  }
  EXPECT_NEAR(after / before, 9.0, 9e-3);
  // The second Gaussian holds 1/3 of the variance: 2/3 + 9/3 = 11/3 in expectation; the budget
  // moves towards the louder grid, so this one is a fresh draw (1% standard error per run).
  EXPECT_NEAR(partial / before, 11.0 / 3.0, 0.06 * 11.0 / 3.0);
}

// Centroid of the rendered power spectrum around its strongest bin (a 128^2 render, periodograms
// summed over `seeds`), folded so that omega and -omega count together: the frequency of a
// narrow-band noise as the render shows it.
Vec2d rendered_peak(const GaborModel& model, int seeds) {
  constexpr int kSide = 128;
  std::vector<double> power(static_cast<std::size_t>(kSide) * kSide, 0.0);
  std::vector<Vec2d> positions;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) positions.push_back({x + 0.5, y + 0.5});
  for (std::uint32_t seed = 1; seed <= static_cast<std::uint32_t>(seeds); ++seed) {
    ImageF out(kSide * kSide, 1, 1);
    model.evaluate(positions, {}, seed, out.view());
    std::vector<float> plane(out.pixels().begin(), out.pixels().end());
    for (float& v : plane) v -= 0.5f;
    const std::vector<float> p = periodogram(plane, kSide, kSide);
    for (std::size_t i = 0; i < power.size(); ++i) power[i] += p[i];
  }
  const auto signed_bin = [](int i) { return i < kSide / 2 ? i : i - kSide; };
  std::size_t best = 0;
  for (std::size_t i = 0; i < power.size(); ++i)
    if (power[i] > power[best]) best = i;
  const int bx = signed_bin(static_cast<int>(best % kSide));
  const int by = signed_bin(static_cast<int>(best / kSide));
  double sx = 0.0, sy = 0.0, total = 0.0;
  for (int dy = -4; dy <= 4; ++dy)
    for (int dx = -4; dx <= 4; ++dx) {
      const int x = bx + dx, y = by + dy;
      const double w =
          power[static_cast<std::size_t>((y + kSide) % kSide) * kSide + (x + kSide) % kSide];
      sx += w * x;
      sy += w * y;
      total += w;
    }
  return {sx / total / kSide, sy / total / kSide};
}

TEST(GaborEdit, RotationScaleAndTranslationMoveTheRenderedPeak) {
  // A narrow-band noise (band 6, spectral sd 0.6 bins of a 128^2 render) at omega = (0.15, 0.05).
  // The centroid of two renders' periodograms finds its peak with a standard deviation of 0.0013
  // cycles per pixel per coordinate (measured: largest error 0.0028 over these 4 cases); the bound
  // is 4 sd, 0.005 (2 degrees of rotation at this radius), while the edits move the peak by 0.03
  // to 0.2.
  const GaborModel model = model_of({{0, 6, 0.15f, 0.05f, 0.01f}});
  const double angle = 40.0 * std::numbers::pi / 180.0;
  struct Case {
    SpectrumEdit edit;
    Vec2d expected;
  };
  std::vector<Case> cases(4);
  cases[0].expected = {0.15, 0.05};
  cases[1].edit.rotation = angle;
  cases[1].expected = {0.15 * std::cos(angle) - 0.05 * std::sin(angle),
                       0.15 * std::sin(angle) + 0.05 * std::cos(angle)};
  cases[2].edit.scale = 1.5;
  cases[2].expected = {0.225, 0.075};
  cases[3].edit.translation_x = 0.05;
  cases[3].edit.translation_y = -0.1;
  cases[3].expected = {0.2, -0.05};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    Vec2d peak = rendered_peak(edit_gaussians(model, GaussianGroup{}, cases[k].edit), 2);
    // The periodogram is symmetric: take the lobe on the expected side.
    if (peak.x * cases[k].expected.x + peak.y * cases[k].expected.y < 0.0)
      peak = {-peak.x, -peak.y};
    EXPECT_NEAR(peak.x, cases[k].expected.x, 0.005) << "case " << k;
    EXPECT_NEAR(peak.y, cases[k].expected.y, 0.005) << "case " << k;
    if (k == 1) {
      const double measured = std::atan2(peak.y, peak.x) - std::atan2(0.05, 0.15);
      EXPECT_NEAR(measured * 180.0 / std::numbers::pi, 40.0, 2.0);
    }
  }
}

TEST(GaborEdit, BandwidthChangesTheCorrelationLength) {
  // A Gaussian of spectral sd s has the autocorrelation exp(-2 pi^2 s^2 |tau|^2) across its
  // frequency (eq. 3). Doubling the bandwidth (band 5 -> 4) doubles s: at tau = 6 pixels the
  // correlation drops from 0.882 to 0.606. Estimated from 20000 pairs 37 pixels apart (standard
  // error ~0.005); the kernel's truncation at r = 1/a (section 6.1) lowers the wide one a little
  // (measured 0.881 and 0.594). Bound: 0.03, the bias plus 3 standard errors.
  const GaborModel model = model_of({{0, 5, 0.1f, 0.0f, 0.01f}});
  const auto correlation = [](const GaborModel& m) {
    constexpr int kPairs = 20000;
    std::vector<Vec2d> positions;
    for (int i = 0; i < kPairs; ++i) {
      const Vec2d p{37.3 * (i % 200), 37.3 * (i / 200)};
      positions.push_back(p);
      positions.push_back({p.x, p.y + 6.0});
    }
    ImageF out(2 * kPairs, 1, 1);
    m.evaluate(positions, {}, 3, out.view());
    double product = 0.0, square = 0.0;
    for (int i = 0; i < kPairs; ++i) {
      const double a = out.at(2 * i, 0, 0) - 0.5, b = out.at(2 * i + 1, 0, 0) - 0.5;
      product += a * b;
      square += 0.5 * (a * a + b * b);
    }
    return product / square;
  };
  const auto expected = [](int band) {
    const double s = bandwidth(band) / (2.0 * std::sqrt(std::numbers::pi));
    return std::exp(-2.0 * std::numbers::pi * std::numbers::pi * s * s * 36.0);
  };
  SpectrumEdit wider;
  wider.bandwidth_shift = -1;
  const double narrow = correlation(model);
  const double wide = correlation(edit_gaussians(model, GaussianGroup{}, wider));
  EXPECT_NEAR(narrow, expected(5), 0.03);
  EXPECT_NEAR(wide, expected(4), 0.03);
  EXPECT_GT(narrow - wide, 0.1);
}

TEST(GaborGroups, FindsPeaksLinesAndTheDiffuseRest) {
  // Section 8: a spectrum with known Wold components. Peaks: one narrow Gaussian and one peak
  // split over two neighbouring bins. A line through the origin at 30 degrees: 8 Gaussians of
  // band 5 at radii 0.05 ... 0.4. The rest is diffuse: a low-frequency blob, an off-centre blob
  // of wide Gaussians (a single direction, but as wide as it is long: not a line), a weak narrow
  // Gaussian (a peak with too little variance), a narrow ripple on the low-frequency blob (not
  // isolated), and a 5 x 5 patch of narrow Gaussians on neighbouring bins (a broad bump, not
  // compact enough to be a spectral line).
  std::vector<GaussianComponent> gaussians = {
      {0, 7, 0.25f, 0.125f, 0.02f},                       // periodic
      {0, 7, -0.1875f, 0.3125f, 0.006f},                  // periodic (split peak)
      {0, 7, -0.1875f + 1.0f / 128.0f, 0.3125f, 0.006f},  // periodic (split peak)
      {0, 3, 0.0f, 0.0f, 0.05f},                          // low-frequency blob
      {0, 6, 0.05f, 0.0f, 0.0005f},                       // ripple on it
      {0, 7, 0.3f, -0.05f, 0.0001f},                      // weak narrow Gaussian
  };
  const std::size_t periodic = 3;
  const std::size_t first_line = gaussians.size();
  const double angle = std::numbers::pi / 6.0;
  for (int k = 1; k <= 8; ++k)
    gaussians.push_back({0, 5, static_cast<float>(0.05 * k * std::cos(angle)),
                         static_cast<float>(0.05 * k * std::sin(angle)), 0.003f});
  const std::size_t line_end = gaussians.size();
  for (const float dx : {0.0f, 0.025f})
    for (const float dy : {0.0f, 0.025f})
      gaussians.push_back({0, 3, 0.1f + dx, -0.3f + dy, 0.004f});
  for (const float y : {-2.0f, -1.0f, 0.0f, 1.0f, 2.0f})
    for (const float x : {-2.0f, -1.0f, 0.0f, 1.0f, 2.0f})
      gaussians.push_back({0, 7, 0.3f + x / 128.0f, 0.3f + y / 128.0f, 0.0008f});

  const GaborModel model = model_of(gaussians);
  const std::vector<WoldComponent> labels = wold_components(model);
  ASSERT_EQ(labels.size(), gaussians.size());
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const WoldComponent expected = i < periodic                      ? WoldComponent::periodic
                                   : i >= first_line && i < line_end ? WoldComponent::anisotropic
                                                                     : WoldComponent::stochastic;
    EXPECT_EQ(component_name(labels[i]), component_name(expected))
        << "Gaussian " << i << " at " << gaussians[i].frequency_x << ", "
        << gaussians[i].frequency_y;
  }

  // Rotating the whole spectrum keeps the groups; a second channel is grouped on its own.
  SpectrumEdit rotate;
  rotate.rotation = 1.0;
  EXPECT_EQ(wold_components(edit_gaussians(model, GaussianGroup{}, rotate)), labels);
  std::vector<GaussianComponent> two = gaussians;
  two.push_back({1, 4, 0.2f, 0.2f, 0.01f});
  const std::vector<WoldComponent> two_labels = wold_components(model_of(two, 2));
  EXPECT_EQ(std::vector<WoldComponent>(two_labels.begin(), two_labels.end() - 1), labels);
  EXPECT_EQ(two_labels.back(), WoldComponent::stochastic);
}

TEST(GaborGroups, FindsAPeakInACarpetOfWeakNarrowGaussians) {
  // The weighted fit (issue 20's defaults) also covers the diffuse spectrum with narrow
  // Gaussians on neighbouring bins: 16 x 16 of them around a strong peak, each with less than a
  // quarter of a peak's least variance. Linked to its neighbours, the peak would chain into one
  // large cluster that is not compact (plaid_fabric_256 had no periodic group at the defaults).
  std::vector<GaussianComponent> gaussians = {{0, 7, 0.25f, 0.125f, 0.02f}};
  for (int y = -8; y < 8; ++y)
    for (int x = -8; x < 8; ++x)
      if (x != 0 || y != 0)
        gaussians.push_back({0, 7, 0.25f + static_cast<float>(x) / 128.0f,
                             0.125f + static_cast<float>(y) / 128.0f, 0.00002f});
  const std::vector<WoldComponent> labels = wold_components(model_of(gaussians));
  EXPECT_EQ(component_name(labels[0]), "periodic");
  for (std::size_t i = 1; i < labels.size(); ++i)
    EXPECT_NE(labels[i], WoldComponent::periodic) << "Gaussian " << i;
}

TEST(GaborEvaluate, StripsSpanAtMostTheCacheColumns) {
  // The cells within `reach` of a strip of w samples `step` apart span at most
  // (w step + 2 reach) / cell + 2 columns: never more than the cache's 16.
  for (const double cell : {0.3, 1.0, 7.5})
    for (const double reach : {cell / 2, cell, 4 * cell})
      for (const double step : {0.25, 1.0, 8.0}) {
        const std::size_t width = strip_width(step, reach, cell);
        ASSERT_GE(width, 1u);
        if (width > 1) {
          EXPECT_LE((static_cast<double>(width) * step + 2 * reach) / cell + 2,
                    static_cast<double>(ImpulseCache::kSide))
              << cell << " " << reach << " " << step;
        }
      }
  EXPECT_EQ(strip_width(0.0, 1.0, 1.0), 1u);  // not a row: sample by sample
  EXPECT_EQ(strip_width(1.0, 1.0, 1.0), 12u);
}

}  // namespace
}  // namespace stochtex::gabor::gabor_test
