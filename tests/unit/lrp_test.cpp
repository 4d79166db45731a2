// Local random-phase noise: the window and its Bessel function, the stratified spectral sampling
// (sections 3.6, 4.2, 4.3 of Gilet et al. 2014), model records and determinism.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <random>

#include "methods/lrp/analysis.hpp"
#include "methods/lrp/evaluate.hpp"
#include "methods/lrp/model.hpp"
#include "methods/lrp/structure_analysis.hpp"
#include "methods/lrp/window.hpp"
#include "metrics/metrics.hpp"
#include "model/model_data.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::lrp::lrp_test {
namespace {

using test_support::expect_corruptions_rejected;
using test_support::expect_record_rejected;
using test_support::record_array;
using test_support::same_bytes;

TEST(LrpWindow, BesselMatchesTheStandardLibraryEverywhere) {
  // The tails are where a truncated series fails: at 3 pi (the window's centre) 5 terms of I_3
  // are 19% low, and the series alone loses accuracy near the switch to the asymptotic expansion.
  // A 5-term series fails this test at x = 3 pi already (relative error 0.19).
  for (const int order : {0, 1, 3})
    for (const double x :
         {0.0, 1e-6, 0.5, 2.0, kKaiserArgument, 15.0, 29.999, 30.001, 45.0, 100.0, 400.0, 700.0}) {
      const double expected = std::cyl_bessel_i(static_cast<double>(order), x);
      const double actual = bessel_i(order, x);
      if (expected == 0.0)
        EXPECT_EQ(actual, 0.0) << "order " << order << " at " << x;
      else
        EXPECT_NEAR(actual / expected, 1.0, 1e-13) << "order " << order << " at " << x;
    }
}

TEST(LrpWindow, KaiserBesselShapeAndTheConstantOfEquationThree) {
  EXPECT_DOUBLE_EQ(kaiser_bessel_window(0.0), 1.0);
  EXPECT_EQ(kaiser_bessel_window(1.5), 0.0);
  EXPECT_EQ(kaiser_bessel_window(-2.0), 0.0);
  // Continuous at the edge: w ~ t^(3/2) with t = 1 - (y / 1.5)^2.
  EXPECT_LT(kaiser_bessel_window(1.4999), 1e-7);
  EXPECT_GT(kaiser_bessel_window(1.4), 0.0);
  for (double y = 0.0; y < 1.5; y += 0.01) {
    EXPECT_LE(kaiser_bessel_window(y + 0.01), kaiser_bessel_window(y));  // decreasing
    EXPECT_DOUBLE_EQ(kaiser_bessel_window(y), kaiser_bessel_window(-y));
  }
  // The paper's constant int_0^inf r w^2 dr ~ 0.1126 (section 4.3) identifies the order-3
  // Bessel function; the printed series ((m+2)! instead of (m+3)!) gives 0.1049, I_0 gives 0.1196.
  EXPECT_NEAR(window_radial_energy(), 0.1126, 5e-5);
  // The evaluator's polynomial form agrees with the exact window to float precision.
  const auto coefficients = window_coefficients();
  for (double y = 0.0; y <= 1.6; y += 0.001)
    EXPECT_NEAR(window_from_square(coefficients, static_cast<float>(y * y)),
                kaiser_bessel_window(y), 1e-6)
        << y;
}

TEST(LrpWindow, FrequencyClampWeights) {
  EXPECT_FLOAT_EQ(clamp_weight(0.0f), 1.0f);
  EXPECT_FLOAT_EQ(clamp_weight(kClampEnd), 0.0f);
  EXPECT_FLOAT_EQ(clamp_weight(1.0f), 0.0f);
}

TEST(LrpWindow, SeventyFivePercentRadius) {
  // delta holds 75% of the window's spectral energy; 100% needs the whole (infinite) spectrum,
  // and the radius grows with the fraction.
  const double half = window_energy_radius(0.5);
  const double three_quarters = window_energy_radius(0.75);
  EXPECT_GT(three_quarters, half);
  EXPECT_GT(half, 0.05);
  EXPECT_LT(three_quarters, 2.0);
}

// An irregular but smooth spectrum: a sum of anisotropic Gaussians.
SpectrumTarget lumpy_spectrum(int size) {
  SpectrumTarget target = gaussian_spectrum(size, 0.1, 0.05, 0.03, 0.01, 1.0);
  const SpectrumTarget wide = gaussian_spectrum(size, 0.0, 0.0, 0.15, 0.08, 1.0);
  for (std::size_t i = 0; i < target.power.size(); ++i) target.power[i] += wide.power[i];
  return target;
}

TEST(LrpStrata, EqualEnergyPowerIntervals) {
  const SpectrumTarget target = lumpy_spectrum(64);
  const double total = std::accumulate(target.power.begin(), target.power.end(), 0.0);
  for (const int strata : {1, 2, 4, 8}) {
    const std::vector<StratumPlan> plans = plan_strata(target.power, 64, strata, 50, true, {}, 1);
    ASSERT_EQ(plans.size(), static_cast<std::size_t>(strata));
    double energy = 0.0;
    for (std::size_t s = 0; s < plans.size(); ++s) {
      energy += plans[s].energy;
      // Equal energy up to one frequency's worth (the largest value of the spectrum).
      EXPECT_NEAR(plans[s].energy, total / strata, 2.0 * plans[0].highest_power + 1e-3 * total)
          << strata << " strata, stratum " << s;
      // Strata are intervals of the power, strongest first (section 4.2).
      if (s > 0) {
        EXPECT_LE(plans[s].highest_power, plans[s - 1].lowest_power);
      }
    }
    EXPECT_NEAR(energy, total, 1e-9 * total);
  }
}

TEST(LrpStrata, SpacingAmplitudeAndSubstrata) {
  const SpectrumTarget target = lumpy_spectrum(64);
  const std::vector<StratumPlan> plans = plan_strata(target.power, 64, 4, 50, true, {}, 7);
  const double radial = window_radial_energy();
  int cosines = 0;
  for (const StratumPlan& plan : plans) {
    const Stratum& s = plan.sampling;
    cosines += s.cosines;
    // Delta_S = T sqrt(J_S) / sqrt(2 |S|) and equation (3) (energy per unit area).
    EXPECT_NEAR(s.spacing / (64.0 * std::sqrt(s.cosines / (2.0 * plan.bins))), 1.0, 1e-7);
    EXPECT_NEAR(
        double(s.amplitude) * s.amplitude * s.cosines * std::numbers::pi * radial / plan.energy,
        1.0, 1e-6);
    // Erosion never empties a stratum: one non-empty sub-stratum per cosine, and the radius used
    // is at most delta.
    EXPECT_LE(plan.eroded_radius, plan.erosion_radius);
    ASSERT_EQ(plan.substrata.size(), static_cast<std::size_t>(s.cosines));
    for (const auto& substratum : plan.substrata) {
      ASSERT_FALSE(substratum.empty());
      for (const auto& bin : substratum) {
        EXPECT_GE(bin[1], 0);  // upper half-plane
        EXPECT_LE(std::abs(bin[0]), 32);
        EXPECT_LE(bin[1], 32);
      }
    }
  }
  // 50 = 13 + 13 + 12 + 12.
  EXPECT_EQ(cosines, 50);
  EXPECT_EQ(plans[0].sampling.cosines, 13);
  EXPECT_EQ(plans[3].sampling.cosines, 12);
  // Stronger strata are smaller, so their windows are wider (finer spectral resolution).
  EXPECT_GT(plans[0].sampling.spacing, plans[3].sampling.spacing);
}

TEST(LrpStrata, ShapedAmplitudesFollowThePowerAndKeepTheEnergy) {
  const int size = 64;
  const SpectrumTarget target = lumpy_spectrum(size);
  const auto power_of = [&](const std::array<int, 2>& bin) {
    // The pair power of a half-plane bin: power(k) + power(-k), one term when k == -k.
    const int kx = bin[0] < 0 ? bin[0] + size : bin[0];
    const int nx = (size - kx) % size;
    const int ny = (size - bin[1]) % size;
    const double p = target.power[static_cast<std::size_t>(bin[1]) * size + kx];
    return (nx == kx && ny == bin[1]) ? p : 2.0 * p;
  };
  for (const bool shaped : {false, true}) {
    const std::vector<StratumPlan> plans = plan_strata(target.power, size, 4, 50, shaped, {}, 7);
    for (const StratumPlan& plan : plans) {
      ASSERT_EQ(plan.weights.size(), plan.substrata.size());
      // Each sub-stratum's list is drawn uniformly, so a cosine's expected squared weight is the
      // mean of w^2 over the list; J_S cosines must carry the stratum's energy, as A_S assumes.
      double expected = 0.0;
      for (std::size_t k = 0; k < plan.substrata.size(); ++k) {
        const auto& bins = plan.substrata[k];
        const auto& weights = plan.weights[k];
        ASSERT_EQ(weights.size(), bins.size());
        double square = 0.0;
        double largest = 0.0;
        for (const float w : weights) {
          square += double(w) * w;
          largest = std::max(largest, double(w) * w);
        }
        const double mean = square / double(weights.size());
        expected += mean;
        if (!shaped) {
          for (const float w : weights) EXPECT_EQ(w, 1.0f);
          continue;
        }
        // Listed in proportion to its power (analysis.cpp, draw_in_proportion_to_power), no
        // cosine's squared weight exceeds twice the list's mean: no rare, heavy draws.
        EXPECT_LE(largest, 2.0 * mean * (1.0 + 1e-6));
        // The power a frequency receives, w^2 summed over its copies in the list, is proportional
        // to the target's power inside the sub-stratum.
        std::map<std::array<int, 2>, double> received;
        for (std::size_t i = 0; i < bins.size(); ++i)
          received[bins[i]] += double(weights[i]) * weights[i];
        for (const auto& [bin, power] : received) {
          const double ratio = power / received.at(bins[0]);
          EXPECT_NEAR(ratio, power_of(bin) / power_of(bins[0]), 1e-5 * ratio);
        }
      }
      EXPECT_NEAR(expected, plan.sampling.cosines, 1e-5 * plan.sampling.cosines);
    }
  }
}

TEST(LrpStrata, SpacingFloorKeepsWiderSpacings) {
  // Parameter `spacing`: Delta_S = max(floor, T sqrt(J_S) / sqrt(2 |S|)).
  const SpectrumTarget target = lumpy_spectrum(64);
  const std::vector<StratumPlan> paper = plan_strata(target.power, 64, 4, 50, true, {}, 7);
  const std::vector<StratumPlan> floored =
      plan_strata(target.power, 64, 4, 50, true, {.floor = 12.0}, 7);
  bool raised = false;
  for (std::size_t s = 0; s < paper.size(); ++s) {
    EXPECT_EQ(floored[s].sampling.spacing, std::max(12.0f, paper[s].sampling.spacing)) << s;
    // The amplitude does not depend on Delta_S (equation 3 in variance units) ...
    EXPECT_EQ(floored[s].sampling.amplitude, paper[s].sampling.amplitude) << s;
    // ... and the erosion radius delta shrinks as 1 / Delta_S.
    EXPECT_NEAR(floored[s].erosion_radius * floored[s].sampling.spacing,
                paper[s].erosion_radius * paper[s].sampling.spacing, 1e-4);
    raised = raised || paper[s].sampling.spacing < 12.0f;
  }
  EXPECT_TRUE(raised);  // the floor is tested on a stratum it changes
}

TEST(LrpStrata, WidenMultipliesThePapersSpacingBeforeTheFloor) {
  // Parameter `widen`: Delta_S = max(floor, widen T sqrt(J_S) / sqrt(2 |S|)).
  const SpectrumTarget target = lumpy_spectrum(64);
  const std::vector<StratumPlan> paper = plan_strata(target.power, 64, 4, 50, true, {}, 7);
  const std::vector<StratumPlan> widened =
      plan_strata(target.power, 64, 4, 50, true, {.widen = 2.0, .floor = 12.0}, 7);
  bool floored = false;
  bool doubled = false;
  for (std::size_t s = 0; s < paper.size(); ++s) {
    const float twice = 2.0f * paper[s].sampling.spacing;
    EXPECT_NEAR(widened[s].sampling.spacing, std::max(12.0f, twice), 1e-5f * twice) << s;
    EXPECT_EQ(widened[s].sampling.amplitude, paper[s].sampling.amplitude) << s;
    floored = floored || twice < 12.0f;
    doubled = doubled || twice > 12.0f;
  }
  EXPECT_TRUE(floored);  // both branches of the rule are exercised
  EXPECT_TRUE(doubled);
}

// A 128² grey tone, 0.5 + 0.2 cos, on bin (5, 3) of crops of side `crop`.
ImageF tone_on_bin_5_3(int crop) {
  ImageF tone(128, 128, 1);
  for (int y = 0; y < tone.height(); ++y)
    for (int x = 0; x < tone.width(); ++x)
      tone.at(x, y, 0) = static_cast<float>(
          0.5 + 0.2 * std::cos(2.0 * std::numbers::pi * (5.0 * x + 3.0 * y) / crop));
  return tone;
}

TEST(LrpWelch, DeblurPutsAToneBackOnItsBin) {
  // A tone on bin (5, 3) of 32-pixel crops: Welch's Hann window spreads it over the 3 x 3 bins
  // around (5, 3) and (-5, -3), (2/3)^2 = 4/9 on each. Per axis, deblur_welch's taps turn
  // [1, 4, 1] / 6 into [1, -2, 3, 92, 3, -2, 1] / 96 (positive taps 100/96, negative -4/96):
  // (92/96)^2 of the tone is back on its bin, and clamping the negative products leaves a total of
  // (100^2 + 4^2) / 96^2.
  constexpr int kCrop = 32;
  const ImageF tone = tone_on_bin_5_3(kCrop);
  std::vector<double> welch = welch_power_spectrum(tone.view(), kCrop);
  welch[0] = 0.0;
  const std::vector<double> deblurred = deblur_welch(welch, kCrop);
  const double before = std::accumulate(welch.begin(), welch.end(), 0.0);
  const double after = std::accumulate(deblurred.begin(), deblurred.end(), 0.0);
  const auto on_bins = [](const std::vector<double>& power) {
    return power[3 * kCrop + 5] + power[(kCrop - 3) * kCrop + kCrop - 5];
  };
  EXPECT_NEAR(on_bins(welch) / before, 4.0 / 9.0, 1e-4);
  EXPECT_NEAR(on_bins(deblurred) / before, (92.0 * 92.0) / (96.0 * 96.0), 1e-4);
  EXPECT_NEAR(after / before, (100.0 * 100.0 + 4.0 * 4.0) / (96.0 * 96.0), 1e-4);
  EXPECT_EQ(deblurred[0], 0.0);
  EXPECT_TRUE(std::all_of(deblurred.begin(), deblurred.end(), [](double v) { return v >= 0.0; }));
}

TEST(LrpStrata, DcPowerJoinsTheStrongestStratum) {
  // With shaped amplitudes, power at DC (the exemplar's variance below the estimate's resolution)
  // is one more frequency of the strongest stratum and keeps its energy; as published (constant
  // amplitudes) DC is ignored.
  SpectrumTarget target = lumpy_spectrum(64);
  const double total = std::accumulate(target.power.begin(), target.power.end(), 0.0);
  target.power[0] = 0.5 * total;
  for (const bool shaped : {false, true}) {
    const std::vector<StratumPlan> plans = plan_strata(target.power, 64, 4, 50, shaped, {}, 7);
    double energy = 0.0;
    bool drawn = false;
    for (std::size_t s = 0; s < plans.size(); ++s) {
      energy += plans[s].energy;
      for (const auto& substratum : plans[s].substrata)
        for (const auto& bin : substratum)
          if (bin == std::array<int, 2>{0, 0}) drawn = true;
    }
    EXPECT_EQ(drawn, shaped);
    EXPECT_NEAR(energy, shaped ? 1.5 * total : total, 1e-9 * total) << shaped;
  }
}

TEST(LrpStrata, SpeckleInTheSupportIsNotEroded) {
  // A flat spectrum with 5% of its bins zero (the weakest speckle of a noisy estimate): with
  // shaped amplitudes the support is closed before the erosion, so nearly every bin stays
  // drawable. Eroding around each hole (delta of about 5 bins here) left a few percent.
  constexpr int kSize = 64;
  SpectrumTarget target{kSize, std::vector<double>(kSize * kSize, 1.0), 0.0};
  target.power[0] = 0.0;
  std::mt19937 engine(5);
  std::uniform_int_distribution<int> pick(0, kSize * kSize - 1);
  for (int hole = 0; hole < kSize * kSize / 40; ++hole) {
    const int index = pick(engine);
    const int x = index % kSize;
    const int y = index / kSize;
    target.power[static_cast<std::size_t>(index)] = 0.0;
    target.power[static_cast<std::size_t>(((kSize - y) % kSize) * kSize + (kSize - x) % kSize)] =
        0.0;
  }
  std::size_t support = 0;
  for (const double p : target.power) support += p > 0.0 ? 1 : 0;
  const std::vector<StratumPlan> plans = plan_strata(target.power, kSize, 4, 50, true, {}, 7);
  std::size_t drawable = 0;
  for (const StratumPlan& plan : plans) {
    EXPECT_GT(plan.erosion_radius, 3.0);
    for (const auto& substratum : plan.substrata) drawable += substratum.size();
  }
  // Half-plane bins against the full plane's support.
  EXPECT_GT(2.0 * double(drawable), 0.9 * double(support));
}

TEST(LrpStrata, KmeansIsSeededAndDeterministic) {
  const SpectrumTarget target = lumpy_spectrum(64);
  const auto a = plan_strata(target.power, 64, 4, 50, true, {}, 3);
  const auto b = plan_strata(target.power, 64, 4, 50, true, {}, 3);
  const auto c = plan_strata(target.power, 64, 4, 50, true, {}, 4);
  bool differs = false;
  for (std::size_t s = 0; s < a.size(); ++s) {
    EXPECT_EQ(a[s].substrata, b[s].substrata);
    differs = differs || a[s].substrata != c[s].substrata;
  }
  EXPECT_TRUE(differs);
}

ImageF random_exemplar(int side, int channels, unsigned seed) {
  std::mt19937 engine(seed);
  std::normal_distribution<float> normal(0.5f, 0.1f);
  ImageF exemplar(side, side, channels);
  // Correlated channels, so that the PCA basis is not the identity.
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const float shared = normal(engine);
      for (int c = 0; c < channels; ++c)
        exemplar.at(x, y, c) = 0.5f * shared + 0.5f * normal(engine) + 0.1f * static_cast<float>(c);
    }
  return exemplar;
}

const Model& colour_model() {
  static const Model model =
      analyze("lrp", random_exemplar(40, 3, 2).view(), {{"cosines", 20}}, 5, "random");
  return model;
}

ImageF render_model(const Model& model, const Grid& grid, std::uint32_t seed, int threads = 1) {
  ImageF out(grid.width, grid.height, model.channels());
  RenderOptions options;
  options.threads = threads;
  options.tile_size = 16;
  render(model, grid, seed, out.view(), options);
  return out;
}

// A model file read back holds the same tables and renders the same bytes.
void expect_round_trip(const Model& model) {
  const Model loaded = deserialize_model(serialize_model(model), "memory");
  EXPECT_EQ(loaded.method(), "lrp");
  const LrpData& a = std::get<LrpModel>(model.data().model).data();
  const LrpData& b = std::get<LrpModel>(loaded.data().model).data();
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_EQ(a.colour_basis, b.colour_basis);
  EXPECT_EQ(a.frequencies, b.frequencies);
  EXPECT_EQ(a.substratum_first, b.substratum_first);
  EXPECT_EQ(a.substratum_count, b.substratum_count);
  for (std::size_t s = 0; s < a.strata_table.size(); ++s) {
    EXPECT_EQ(a.strata_table[s].spacing, b.strata_table[s].spacing);
    EXPECT_EQ(a.strata_table[s].amplitude, b.strata_table[s].amplitude);
  }
  const Grid grid{{-3.0, 7.5}, 0.7, 40, 30};
  EXPECT_TRUE(same_bytes(render_model(model, grid, 9), render_model(loaded, grid, 9)));
}

TEST(LrpModelFile, RoundTripRendersTheSameBytes) {
  expect_round_trip(colour_model());
}

TEST(LrpModelFile, CorruptRecordsAreRejected) {
  const LrpModel& lrp = std::get<LrpModel>(colour_model().data().model);
  const ModelRecord good = lrp.to_record(colour_model().params());
  EXPECT_NO_THROW(LrpModel::from_record(good, "good"));
  expect_corruptions_rejected<LrpModel>(
      good,
      {{"channels", 5},
       {"channels", 2},
       {"strata", 0},
       {"strata", 17},
       {"strata", 2.5},
       {"envelope", 2},
       {"substrata", 1e12},
       {"frequencies", 0},
       {"frequencies", 1e12}},
      {
          {"mean", {0, NAN}},
          {"colour_basis", {1, INFINITY}},
          {"frequencies", {0, 0.75f}},
          {"frequencies", {3, NAN}},
          {"strata", {0, 0.0f}},     // zero cosines
          {"strata", {0, 2.5f}},     // fractional cosines
          {"strata", {1, -1.0f}},    // negative spacing
          {"strata", {1, 0.0f}},     // zero spacing
          {"strata", {2, -1.0f}},    // negative amplitude
          {"strata", {2, 1e30f}},    // absurd amplitude
          {"substrata", {0, 1e7f}},  // first frequency out of the table
          {"substrata", {1, 0.0f}},  // empty sub-stratum
          {"substrata", {1, 1e6f}},  // runs past the table
          {"substrata", {0, -1.0f}},
          {"weights", {0, -1.0f}},  // negative frequency weight
          {"weights", {1, NAN}},
      });
  {
    ModelRecord record = good;
    record.scalars.erase("strata");
    expect_record_rejected<LrpModel>(record, "missing strata");
  }
  {
    ModelRecord record = good;
    record_array(record, "frequencies").pop_back();
    expect_record_rejected<LrpModel>(record, "short frequency table");
  }
}

// Same bytes whatever the thread count, a different seed differs, and the sample at pixel (x, y)
// evaluated alone equals the batch's.
void expect_deterministic(const Model& model, const Grid& grid, int x, int y) {
  const ImageF reference = render_model(model, grid, 11, 1);
  EXPECT_TRUE(same_bytes(reference, render_model(model, grid, 11, 2)));
  EXPECT_TRUE(same_bytes(reference, render_model(model, grid, 11, 3)));
  EXPECT_FALSE(same_bytes(reference, render_model(model, grid, 12, 1)));
  const std::vector<Vec2d> one = {
      {grid.origin.x + grid.scale * (x + 0.5), grid.origin.y + grid.scale * (y + 0.5)}};
  const std::vector<Footprint> footprint = {{{grid.scale, 0.0}, {0.0, grid.scale}}};
  ImageF single(1, 1, model.channels());
  evaluate(model, one, footprint, 11, single.view());
  for (int c = 0; c < model.channels(); ++c) EXPECT_EQ(single.at(0, 0, c), reference.at(x, y, c));
}

// The largest second difference along a line of samples 0.001 pixel apart starting at
// (origin, -origin): the noise is smooth at that scale, so it is tiny unless positions were
// rounded to float (near 1e7, spacing 1, the samples would repeat then jump).
double roughness(const Model& model, double origin) {
  std::vector<Vec2d> line;
  for (int i = 0; i < 200; ++i) line.push_back({origin + 0.001 * i, -origin + 0.0007 * i});
  ImageF out(1, 200, 3);
  evaluate(model, line, {}, 3, out.view());
  double largest = 0.0;
  for (int i = 1; i + 1 < 200; ++i)
    largest = std::max(
        largest, static_cast<double>(
                     std::abs(out.at(0, i + 1, 0) - 2.0f * out.at(0, i, 0) + out.at(0, i - 1, 0))));
  return largest;
}

TEST(LrpEvaluation, DeterministicWhateverTheThreadsAndSplits) {
  expect_deterministic(colour_model(), Grid{{-20.0, 3.0}, 1.3, 50, 45}, 7, 4);
}

TEST(LrpEvaluation, FarFromTheOriginIsAsPreciseAsAtTheOrigin) {
  EXPECT_LT(roughness(colour_model(), 0.25), 1e-3);
  EXPECT_LT(roughness(colour_model(), 1e7 + 0.25), 1e-3);
}

TEST(LrpAnalysis, RejectsTooSmallExemplarsAndKeepsTheMean) {
  EXPECT_THROW(analyze("lrp", random_exemplar(8, 1, 1).view(), {}, 0), Error);
  const ImageF exemplar = random_exemplar(24, 1, 3);
  const Model model = analyze("lrp", exemplar.view(), {}, 0);
  const ImageF out = render_model(model, {{0.0, 0.0}, 1.0, 64, 64}, 1);
  double sum = 0.0, exemplar_sum = 0.0;
  for (const float v : out.pixels()) sum += v;
  for (const float v : exemplar.pixels()) exemplar_sum += v;
  EXPECT_NEAR(sum / 4096.0, exemplar_sum / 576.0, 0.02);
  EXPECT_THROW(ring_spectrum(6, 0.1, 0.01, 1.0), std::invalid_argument);
  EXPECT_THROW(spectrum_model(ring_spectrum(16, 0.1, 0.01, 1.0), {{"strata", 0}}),
               std::invalid_argument);
}

TEST(LrpAnalysis, DeblurredModelPutsAToneOnItsBin) {
  // A grey tone on bin (5, 3) of the Welch crops (T = 64 for a 128² exemplar). The model's
  // expected power per frequency, A_S^2 w_f^2 / n_k summed over the sub-strata that hold it,
  // follows the estimate it was cut from: 4/9 on the tone's bin as published, (92/96)^2 of
  // (100^2 + 4^2) / 96^2 with `deblur` (LrpWelch.DeblurPutsAToneBackOnItsBin).
  const ImageF tone = tone_on_bin_5_3(64);
  const auto share_on_the_tone = [&](const ParamValues& params) {
    const Model model = analyze("lrp", tone.view(), params, 0);
    const LrpData& data = std::get<LrpModel>(model.data().model).data();
    double total = 0.0;
    double on_bin = 0.0;
    std::size_t k = 0;
    for (const Stratum& stratum : data.strata_table)
      for (int j = 0; j < stratum.cosines; ++j, ++k) {
        const std::uint32_t first = data.substratum_first[k];
        const std::uint32_t count = data.substratum_count[k];
        for (std::uint32_t i = first; i < first + count; ++i) {
          const double weight = double(stratum.amplitude) * data.weights[i];
          const double power = weight * weight / count;
          total += power;
          if (std::lround(data.frequencies[2 * i] * 64) == 5 &&
              std::lround(data.frequencies[2 * i + 1] * 64) == 3)
            on_bin += power;
        }
      }
    return on_bin / total;
  };
  EXPECT_NEAR(share_on_the_tone({{"deblur", 0}}), 4.0 / 9.0, 0.01);
  EXPECT_NEAR(share_on_the_tone({}), (92.0 * 92.0) / (100.0 * 100.0 + 4.0 * 4.0), 0.01);
}

// Section 5: a colour model with every part of the structure (R, blocks, turbulence, placement).
const Model& structure_model() {
  static const Model model = analyze(
      "lrp", random_exemplar(40, 3, 2).view(),
      {{"cosines", 20}, {"ratio", 0.3}, {"turbulence", 3.0}, {"placement", 1}}, 5, "random");
  return model;
}

TEST(LrpStructure, RatioSplitsTheCosineBudget) {
  // Section 5.3: J_R = rJ, at least one cosine when r > 0, none at r = 0.
  EXPECT_EQ(structure_cosines(0.0, 50), 0);
  EXPECT_EQ(structure_cosines(0.1, 50), 5);
  EXPECT_EQ(structure_cosines(0.001, 50), 1);
  EXPECT_EQ(structure_cosines(1.0, 50), 50);
  const LrpData& none = std::get<LrpModel>(colour_model().data().model).data();
  EXPECT_TRUE(none.structure.empty());
  const LrpData& data = std::get<LrpModel>(structure_model().data().model).data();
  ASSERT_FALSE(data.structure.empty());
  EXPECT_EQ(data.structure.cosines, 6);  // round(0.3 x 20)
  int random_cosines = 0;
  for (const Stratum& stratum : data.strata_table) random_cosines += stratum.cosines;
  EXPECT_EQ(random_cosines, 3 * 14);  // (1 - r) J per channel
  EXPECT_EQ(data.structure.turbulence, 3.0f);
  EXPECT_TRUE(data.structure.placement);
  EXPECT_EQ(data.structure.turbulence_strata.size(), static_cast<std::size_t>(kTurbulenceStrata));
}

TEST(LrpStructure, RegionHoldsTheRatioOfTheEnergy) {
  const ImageF exemplar = random_exemplar(40, 1, 4);
  ImageF component(40, 40, 1);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) component.at(x, y, 0) = exemplar.at(x, y, 0) - 0.5f;
  double previous = 0.0;
  for (const double ratio : {0.05, 0.2, 0.5, 1.0}) {
    const FixedPhaseRegion region = fixed_phase_region(component.view(), 32, ratio);
    // R is built by whole frequencies: it reaches r and overshoots by at most one frequency.
    EXPECT_GE(region.energy_fraction, ratio - 1e-12);
    EXPECT_LT(region.energy_fraction, ratio + 0.05);
    EXPECT_GT(region.bins.size(), previous);
    previous = static_cast<double>(region.bins.size());
    // R is symmetric (k and -k), so removing it from a spectrum keeps it real.
    std::vector<double> power(32 * 32, 1.0);
    remove_region(power, region);
    for (int ky = 0; ky < 32; ++ky)
      for (int kx = 0; kx < 32; ++kx)
        EXPECT_EQ(power[static_cast<std::size_t>(ky) * 32 + kx],
                  power[static_cast<std::size_t>((32 - ky) % 32) * 32 + (32 - kx) % 32]);
  }
  EXPECT_NEAR(fixed_phase_region(component.view(), 32, 1.0).energy_fraction, 1.0, 1e-12);
}

TEST(LrpStructure, SubdivisionIsAPartitionOfUnity) {
  // Every cosine of every block kept (a 4 x 4 region has 10 distinct real cosines): the blocks'
  // windows sum to one, so n_R is the structure image to float precision. Kept short of that,
  // the deviation falls as blocks shrink, and the subdivision stops below 1/256 (section 5.3).
  const ImageF exemplar = random_exemplar(40, 1, 6);
  ImageF component(40, 40, 1);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) component.at(x, y, 0) = exemplar.at(x, y, 0) - 0.5f;
  const std::vector<FixedPhaseRegion> regions = {fixed_phase_region(component.view(), 16, 1.0)};
  const std::vector<float> identity = {1.0f};
  std::vector<SubdivisionLevel> levels;
  const StructureData exact = reduce_structure(regions, 10, identity, &levels);
  ASSERT_FALSE(levels.empty());
  EXPECT_LT(levels.back().deviation, 1e-6);
  EXPECT_GT(levels.front().deviation, kStructureTolerance);  // 10 cosines cannot draw 16 x 16
  EXPECT_EQ(exact.blocks, levels.back().blocks);
  levels.clear();
  reduce_structure(regions, 4, identity, &levels);
  for (std::size_t i = 1; i < levels.size(); ++i)
    EXPECT_LT(levels[i].deviation, levels[i - 1].deviation) << "level " << i;
}

TEST(LrpStructure, ModelFileRoundTripAndHostileRecords) {
  const Model& model = structure_model();
  const Model loaded = deserialize_model(serialize_model(model), "memory");
  const StructureData& a = std::get<LrpModel>(model.data().model).data().structure;
  const StructureData& b = std::get<LrpModel>(loaded.data().model).data().structure;
  EXPECT_EQ(a.cosine_table, b.cosine_table);
  EXPECT_EQ(a.turbulence_frequencies, b.turbulence_frequencies);
  const Grid grid{{-3.0, 7.5}, 0.7, 40, 30};
  EXPECT_TRUE(same_bytes(render_model(model, grid, 9), render_model(loaded, grid, 9)));

  const ModelRecord good =
      std::get<LrpModel>(model.data().model).to_record(structure_model().params());
  EXPECT_NO_THROW(LrpModel::from_record(good, "good"));
  expect_corruptions_rejected<LrpModel>(
      good,
      {{"structure_period", 12},
       {"structure_period", 1e9},
       {"structure_blocks", 3},
       {"structure_blocks", 4096},
       {"structure_cosines", 0},
       {"structure_cosines", 1e9},
       {"placement", 2},
       {"turbulence", -1},
       {"turbulence", NAN},
       {"turbulence_strata", 99},
       {"turbulence_substrata", 1e12},
       {"turbulence_frequencies", 0}},
      {
          {"structure_cosines", {0, 0.75f}},          // frequency above Nyquist
          {"structure_cosines", {2, NAN}},            // amplitude
          {"structure_cosines", {2, -1.0f}},          // negative amplitude
          {"structure_cosines", {3, 7.0f}},           // phase outside [0, 1]
          {"turbulence_strata", {0, 0.0f}},           // zero cosines
          {"turbulence_strata", {1, 0.0f}},           // zero spacing
          {"turbulence_substrata", {0, 1e7f}},        // outside the frequency table
          {"turbulence_frequencies", {1, INFINITY}},  // non-finite frequency
      });
}

TEST(LrpStructure, DeterministicWhateverTheThreadsAndSplits) {
  // Placement blocks, turbulence and structure blocks are all pure functions of (p, seed).
  expect_deterministic(structure_model(), Grid{{-70.0, 3.0}, 1.3, 90, 75}, 61, 40);
}

TEST(LrpStructure, FarFromTheOriginIsAsPreciseAsAtTheOrigin) {
  // As LrpEvaluation's test, with structure blocks, turbulence and placement.
  EXPECT_LT(roughness(structure_model(), 0.25), 1e-3);
  EXPECT_LT(roughness(structure_model(), 1e7 + 0.25), 1e-3);
}

TEST(LrpStructure, ContinuousTargetsHaveNoPhasesToKeep) {
  EXPECT_THROW(spectrum_model(ring_spectrum(16, 0.1, 0.01, 1.0), {{"ratio", 0.2}}),
               std::invalid_argument);
}

// Materials (issue 18): the maps of a material set side by side, up to kMaxChannels channels.
// rock_sandstone with every map: 9 channels; small budgets keep it quick.
const ImageF& rock_exemplar() {
  static const ImageF exemplar = test_support::material_exemplar(
      "rock_sandstone", {"albedo", "normal", "roughness", "height", "ao"});
  return exemplar;
}

const Model& material() {
  static const Model model =
      analyze("lrp", rock_exemplar().view(), {{"cosines", 8}, {"strata", 2}}, 5, "rock");
  return model;
}

const Model& structured_material() {
  static const Model model = analyze(
      "lrp", rock_exemplar().view(),
      {{"cosines", 8}, {"strata", 2}, {"ratio", 0.3}, {"turbulence", 2.0}, {"placement", 1}}, 5,
      "rock");
  return model;
}

TEST(LrpMaterial, ModelFileRoundTripRendersTheSameBytes) {
  ASSERT_EQ(material().channels(), 9);
  expect_round_trip(material());
  expect_round_trip(structured_material());
}

TEST(LrpMaterial, DeterministicWhateverTheThreadsAndSplits) {
  expect_deterministic(material(), Grid{{-20.0, 3.0}, 1.3, 30, 25}, 7, 4);
  expect_deterministic(structured_material(), Grid{{-20.0, 3.0}, 1.3, 30, 25}, 3, 9);
}

TEST(LrpMaterial, HostileChannelCountsAreRefusedBeforeAnyArray) {
  const LrpModel& lrp = std::get<LrpModel>(material().data().model);
  const ModelRecord good = lrp.to_record(material().params());
  EXPECT_NO_THROW(LrpModel::from_record(good, "good"));
  expect_corruptions_rejected<LrpModel>(good,
                                        {{"channels", 0},
                                         {"channels", -9},
                                         {"channels", 8},
                                         {"channels", 16},
                                         {"channels", 17},
                                         {"channels", 9.5},
                                         {"channels", 1e9},
                                         {"channels", 1e300},
                                         {"channels", NAN}},
                                        {});
  // Beyond kMaxChannels the scalar itself is named, before any array is read (a record without
  // arrays would otherwise fail on the first one).
  for (const double channels : {17.0, 1e9}) {
    ModelRecord record = good;
    record.scalars["channels"] = channels;
    record.arrays.clear();
    try {
      LrpModel::from_record(record, "bad.stx");
      ADD_FAILURE() << channels << " channels accepted";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("lrp channels"), std::string::npos) << error.what();
    }
  }
  LrpData data = lrp.data();
  data.channels = kMaxChannels + 1;
  EXPECT_THROW(LrpModel{data}, std::invalid_argument);
}

TEST(LrpMaterial, OnePcaOverAllChannelsAndColourAlphaKeptUpToFour) {
  // 1-4 channels: colour (the first 1 or 3) and alpha are analysed apart, so each component (a
  // column of the basis) lives on colour or on alpha alone; 5 and more: one PCA over all
  // channels, whose components mix the first 3 channels with the others on these correlated
  // exemplars.
  for (const int channels : {2, 4, 5, 16}) {
    const Model model =
        analyze("lrp", random_exemplar(24, channels, 4).view(), {{"cosines", 4}}, 1);
    const LrpData& data = std::get<LrpModel>(model.data().model).data();
    const int colour = channels >= 3 ? 3 : 1;
    double mixed = 0.0;
    for (int k = 0; k < channels; ++k) {
      std::array<double, 2> largest{};
      for (int c = 0; c < channels; ++c)
        largest[c < colour ? 0 : 1] =
            std::max(largest[c < colour ? 0 : 1],
                     static_cast<double>(
                         std::abs(data.colour_basis[static_cast<std::size_t>(c * channels + k)])));
      mixed = std::max(mixed, std::min(largest[0], largest[1]));
    }
    if (channels <= 4)
      EXPECT_EQ(mixed, 0.0) << channels;
    else
      EXPECT_GT(mixed, 0.1) << channels;
  }
}

TEST(LrpMaterial, ChannelStreamsAreDistinctAndSkipTheTurbulence) {
  // Channels 0 to 3 keep their streams (every 1-4 channel model renders the same bytes); none
  // takes a turbulence axis' key, so the turbulence stays independent of every channel.
  for (int c = 0; c < kMaxChannels; ++c) {
    if (c < 4) {
      EXPECT_EQ(channel_stream(c), c);
    }
    for (std::int64_t axis = 0; axis < kTurbulenceAxes; ++axis)
      EXPECT_NE(channel_stream(c), kTurbulenceStreamBase + axis) << c;
    for (int d = 0; d < c; ++d) EXPECT_NE(channel_stream(c), channel_stream(d));
  }
}

}  // namespace
}  // namespace stochtex::lrp::lrp_test
