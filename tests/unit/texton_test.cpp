// Texton noise of many channels (a material's maps, issue 18): the evaluator's padded lane widths
// (texton_lanes: 8, 12, 16) give each channel exactly what a 3-channel model of that channel's
// texton gives, on every CPU path; the model file takes 1 to kMaxChannels channels and refuses
// any other count before allocating.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "core/hash.hpp"
#include "methods/texton/evaluate.hpp"
#include "methods/texton/model.hpp"
#include "methods/texton/params.hpp"
#include "model/model_data.hpp"
#include "stochtex/error.hpp"
#include "stochtex/stochtex.hpp"
#include "stochtex/surface.hpp"
#include "test_support.hpp"

namespace stochtex::texton_test {
namespace {

// A 3-channel model of a random exemplar, for its texton and mean.
const texton::TextonModel& three_channel_texton() {
  static const Model model = [] {
    ImageF exemplar(40, 40, 3);
    std::uint32_t state = 17;
    for (float& value : exemplar.pixels()) {
      state = state * 1664525u + 1013904223u;
      value = static_cast<float>(state >> 8) / 16777216.0f;
    }
    return analyze("texton", exemplar.view(), {{"support", 16}, {"iterations", 5}}, 3);
  }();
  return std::get<texton::TextonModel>(model.data().model);
}

// The same texton and MNI with the paper's Poisson point process.
texton::TextonModel with_poisson_points(const texton::TextonModel& model) {
  return texton::TextonModel(model.channels(), model.support(), model.order(), model.mean_impacts(),
                             texton::kPoissonPoints,
                             {model.coefficients().begin(), model.coefficients().end()},
                             {model.mean().begin(), model.mean().end()});
}

// A model of `channels` channels whose channel c has the texton and mean of channel c % 3 of
// `three` (same support, order and MNI, hence the same impulses).
texton::TextonModel widened(const texton::TextonModel& three, int channels) {
  const auto texels = static_cast<std::size_t>(three.support()) * three.support();
  std::vector<float> coefficients(texels * static_cast<std::size_t>(channels));
  std::vector<float> mean(static_cast<std::size_t>(channels));
  for (std::size_t t = 0; t < texels; ++t)
    for (int c = 0; c < channels; ++c)
      coefficients[t * channels + c] = three.coefficients()[t * 3 + c % 3];
  for (int c = 0; c < channels; ++c) mean[c] = three.mean()[c % 3];
  return texton::TextonModel(channels, three.support(), three.order(), three.mean_impacts(),
                             three.points(), coefficients, mean);
}

// Channel c of `wide` equals channel c % 3 of `three`, bit for bit.
void expect_channels_match(const ImageF& three, const ImageF& wide, const std::string& what) {
  int mismatches = 0;
  for (int y = 0; y < wide.height(); ++y)
    for (int x = 0; x < wide.width(); ++x)
      for (int c = 0; c < wide.channels(); ++c)
        mismatches += three.at(x, y, c % 3) != wide.at(x, y, c);
  EXPECT_EQ(mismatches, 0) << what;
  // The comparison is not vacuous: the noise varies.
  EXPECT_NE(three.at(0, 0, 0), three.at(1, 0, 0)) << what;
}

TEST(TextonChannels, LaneWidthsAreTexelForTexelTheModelsChannels) {
  EXPECT_EQ(texton::texton_lanes(1), 1);
  EXPECT_EQ(texton::texton_lanes(4), 4);
  EXPECT_EQ(texton::texton_lanes(5), 8);
  EXPECT_EQ(texton::texton_lanes(9), 12);
  EXPECT_EQ(texton::texton_lanes(kMaxChannels), 16);
  const texton::TextonModel wide = widened(three_channel_texton(), 9);
  EXPECT_EQ(wide.lanes(), 12);
  for (const texton::PyramidLevel& level : wide.pyramid()) {
    ASSERT_EQ(level.coefficients.size(),
              static_cast<std::size_t>(level.stride) * level.stride * wide.lanes());
    // The padding lanes are zero.
    for (std::size_t i = 9; i < level.coefficients.size(); i += (i % 12 == 11) ? 10 : 1)
      ASSERT_EQ(level.coefficients[i], 0.0f) << i;
  }
}

TEST(TextonChannels, EveryChannelCountEvaluatesEachChannelAsAThreeChannelModel) {
  // Point and filtered samples, and surface noise: for 5 to 16 channels (lane widths 8, 12, 16)
  // every channel is bit for bit what the 3-channel evaluator gives for its texton.
  const texton::TextonModel& three = three_channel_texton();
  constexpr int kPoints = 24;
  std::vector<Vec2d> positions;
  std::vector<Footprint> footprints;
  std::vector<SurfacePoint> surface;
  for (int i = 0; i < kPoints; ++i) {
    const double t = 0.37 * i;
    positions.push_back({13.0 * t - 40.0, 7.5 * t + 1e5});
    const double scale = i % 3 == 0 ? 0.5 : 1.5 * i;
    footprints.push_back({{scale, 0.25 * scale}, {0.0, 0.5 * scale}});
    SurfacePoint point;
    point.position = {5.0 * t, -3.0 * t, 2.0 * t + 1.0};
    point.normal = {0.0, 0.0, 1.0};
    point.tangent = {1.0, 0.0, 0.0};
    point.dpdx = {0.5 * i, 0.0, 0.0};
    point.dpdy = {0.0, 0.25 * i, 0.0};
    surface.push_back(point);
  }
  ImageF point3(kPoints, 1, 3), filtered3(kPoints, 1, 3), surface3(kPoints, 1, 3);
  three.evaluate(positions, {}, 11, point3.view());
  three.evaluate(positions, footprints, 11, filtered3.view());
  three.evaluate_surface(surface, 20.0, 11, surface3.view());
  for (const int channels : {5, 8, 9, 12, 13, kMaxChannels}) {
    const texton::TextonModel wide = widened(three, channels);
    ImageF point(kPoints, 1, channels), filtered(kPoints, 1, channels),
        on_surface(kPoints, 1, channels);
    wide.evaluate(positions, {}, 11, point.view());
    wide.evaluate(positions, footprints, 11, filtered.view());
    wide.evaluate_surface(surface, 20.0, 11, on_surface.view());
    const std::string what = std::to_string(channels) + " channels";
    expect_channels_match(point3, point, what + ", point samples");
    expect_channels_match(filtered3, filtered, what + ", filtered samples");
    expect_channels_match(surface3, on_surface, what + ", surface noise");
    const texton::SurfaceConstants constants = wide.surface_constants(20.0);
    for (int c = channels; c < kMaxChannels; ++c) EXPECT_EQ(constants.constant[c], 0.0f);
  }
}

TEST(TextonChannels, HostileChannelCountsAreRefused) {
  const texton::TextonModel& three = three_channel_texton();
  const ModelRecord good = three.to_record({});
  EXPECT_NO_THROW(texton::TextonModel::from_record(good, "good.stx"));
  for (const double channels : {0.0, -1.0, 17.0, 1e9, 2.5, std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::quiet_NaN()}) {
    ModelRecord record = good;
    record.scalars["channels"] = channels;
    test_support::expect_record_rejected<texton::TextonModel>(
        record, "channels = " + std::to_string(channels));
  }
  // Sixteen channels with arrays of that shape load.
  const texton::TextonModel sixteen = widened(three, kMaxChannels);
  const texton::TextonModel loaded =
      texton::TextonModel::from_record(sixteen.to_record({}), "sixteen.stx");
  EXPECT_EQ(loaded.channels(), kMaxChannels);
}

TEST(TextonChannels, RegistryTakesUpToSixteenChannels) {
  int checked = 0;
  for (const auto& method : methods())
    if (method.name == "texton") {
      EXPECT_EQ(method.max_channels, kMaxChannels);
      ++checked;
    }
  EXPECT_EQ(checked, 1);
}

TEST(TextonSupport, TheDefaultTakesTheWholeExemplarUpTo256AndCrops128Beyond) {
  // support = 0 (the default): no support crop up to kWholeSupportMax, the earlier 128 beyond;
  // an explicit support is clamped to the smaller side as before.
  EXPECT_EQ(texton::texton_support(0, 128, 128), 128);
  EXPECT_EQ(texton::texton_support(0, 256, 300), 256);
  EXPECT_EQ(texton::texton_support(0, 257, 512), texton::kCroppedSupport);
  EXPECT_EQ(texton::texton_support(0, 512, 512), 128);
  EXPECT_EQ(texton::texton_support(64, 512, 512), 64);
  EXPECT_EQ(texton::texton_support(1024, 300, 200), 200);
  // 0 or 2 to 1024: 1 is refused with the parameters.
  EXPECT_THROW(resolve_params("texton", ParamValues{{"support", 1}}), std::invalid_argument);
  ImageF exemplar(40, 24, 1);
  std::uint32_t state = 5;
  for (float& value : exemplar.pixels()) {
    state = state * 1664525u + 1013904223u;
    value = static_cast<float>(state >> 8) / 16777216.0f;
  }
  const Model model = analyze("texton", exemplar.view(), {{"iterations", 2}}, 1);
  EXPECT_EQ(std::get<texton::TextonModel>(model.data().model).support(), 24);
  // The file names the side used, and loads.
  const Model loaded = deserialize_model(serialize_model(model), "texton.stx");
  EXPECT_EQ(loaded.params().at("support"), 24);
  EXPECT_EQ(std::get<texton::TextonModel>(loaded.data().model).support(), 24);
}

// The plaid of smooth exemplars (issue 37, docs/methods/texton.md): a texton as wide as the
// exemplar must fall to zero at its square's border, or every copy ends in a jump and the copies
// sum to a grid of streaks. A smooth, long-correlated exemplar (white noise blurred periodically
// over about 12 pixels): its whole-exemplar texton's border is under a twentieth of its centre
// (measured 0.0004; 1.08 without the window, 0.65 on rock_sandstone's height), where a support of
// half the exemplar keeps the projections' own border (0.37, not windowed).
TEST(TextonSupport, AWholeExemplarTextonFallsToZeroAtItsBorder) {
  constexpr int kSide = 64;
  std::uint32_t state = 11;
  std::vector<float> noise(kSide * kSide);
  for (float& value : noise) {
    state = state * 1664525u + 1013904223u;
    value = static_cast<float>(state >> 8) / 16777216.0f;
  }
  ImageF exemplar(kSide, kSide, 1);
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      double sum = 0.0, weights = 0.0;
      for (int dy = -12; dy <= 12; ++dy)
        for (int dx = -12; dx <= 12; ++dx) {
          const double weight = std::exp(-(dx * dx + dy * dy) / 72.0);
          sum += weight * noise[((y + dy + kSide) % kSide) * kSide + (x + dx + kSide) % kSide];
          weights += weight;
        }
      exemplar.at(x, y, 0) = static_cast<float>(sum / weights);
    }
  const auto border_to_centre = [&](int support) {
    const Model model =
        analyze("texton", exemplar.view(), {{"support", support}, {"iterations", 20}}, 1);
    const auto& texton = std::get<texton::TextonModel>(model.data().model);
    const int side = texton.support();
    double border = 0.0, centre = 0.0;
    int border_count = 0, centre_count = 0;
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const double value =
            std::abs(texton.coefficients()[static_cast<std::size_t>(y) * side + x]);
        if (x == 0 || y == 0 || x == side - 1 || y == side - 1) {
          border += value;
          ++border_count;
        } else if (std::abs(2 * x - side) < side / 4 && std::abs(2 * y - side) < side / 4) {
          centre += value;
          ++centre_count;
        }
      }
    return (border / border_count) / (centre / centre_count);
  };
  const double whole = border_to_centre(0);
  const double half = border_to_centre(kSide / 2);
  std::cout << "texton border / centre: whole exemplar " << whole << ", half " << half << "\n";
  EXPECT_LT(whole, 0.05);
}

// The point process (`points`, params.hpp): a model file written before the choice existed has no
// `points` scalar and renders the paper's Poisson process, byte for byte as before; the balanced
// process draws the same points' positions from other counts and gives each impact a random sign.
TEST(TextonPoints, AFileWithoutTheChoiceRendersThePaperPoissonProcess) {
  const texton::TextonModel& balanced = three_channel_texton();
  ASSERT_TRUE(balanced.balanced_points());
  const texton::TextonModel poisson = with_poisson_points(balanced);
  ModelRecord record = poisson.to_record({});
  ASSERT_EQ(record.scalars.erase("points"), 1u);
  const texton::TextonModel legacy = texton::TextonModel::from_record(record, "old.stx");
  EXPECT_EQ(legacy.points(), texton::kPoissonPoints);
  // The Poisson process subtracts E f = lambda sum(alpha); signed impacts have E f = 0.
  for (int c = 0; c < 3; ++c) EXPECT_EQ(balanced.constant_term()[c], balanced.mean()[c]);
  EXPECT_NE(poisson.constant_term()[0], poisson.mean()[0]);

  constexpr int kSide = 32;
  std::vector<Vec2d> positions;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) positions.push_back({1.5 * x - 20.0, 1.5 * y + 7.0});
  ImageF from_poisson(kSide, kSide, 3), from_legacy(kSide, kSide, 3),
      from_balanced(kSide, kSide, 3);
  poisson.evaluate(positions, {}, 4, from_poisson.view());
  legacy.evaluate(positions, {}, 4, from_legacy.view());
  balanced.evaluate(positions, {}, 4, from_balanced.view());
  EXPECT_TRUE(test_support::same_bytes(from_poisson, from_legacy));
  EXPECT_FALSE(test_support::same_bytes(from_poisson, from_balanced));
  // A file that names a process outside the choices is refused.
  record.scalars["points"] = 2;
  EXPECT_THROW(texton::TextonModel::from_record(record, "bad.stx"), Error);
}

TEST(TextonPoints, BalancedCellsHoldAWholeNumberOfPoints) {
  // The cells of the balanced process are sized (0.6 r or a little more) so that each holds
  // exactly lambda a^2 points; the Poisson process keeps the paper's a = 0.6 r.
  const texton::TextonModel& balanced = three_channel_texton();
  const texton::TextonModel poisson = with_poisson_points(balanced);
  const double points = balanced.intensity() * balanced.cell_size() * balanced.cell_size();
  EXPECT_NEAR(points, std::round(points), 1e-9);
  EXPECT_EQ(balanced.cell_count().mean(), std::round(points));
  EXPECT_GE(balanced.cell_size(), poisson.cell_size());
  EXPECT_LT(points - poisson.intensity() * poisson.cell_size() * poisson.cell_size(), 1.0);
  for (int i = 0; i < 100; ++i) {
    CounterRng rng(cell_key(i, -3 * i, 1, Stream::points));
    ASSERT_EQ(balanced.cell_count()(rng), std::round(points));
  }
}

TEST(TextonPoints, SignsAreFairCoins) {
  // impulse_sign over 40 000 (cell, index, seed) triples: the count of -1 is binomial(n, 1/2),
  // within 5 standard deviations of n / 2; and the sign of a point does not repeat its
  // neighbour's more often than chance (the same bound on the count of equal consecutive signs).
  int negative = 0;
  int repeats = 0;
  int total = 0;
  float previous = 0.0f;
  for (std::int64_t cell = -100; cell < 100; ++cell)
    for (std::uint32_t index = 0; index < 200; ++index) {
      const float sign = texton::impulse_sign(cell, 3 * cell + 1, index, 9u);
      ASSERT_TRUE(sign == 1.0f || sign == -1.0f);
      negative += sign < 0.0f;
      repeats += sign == previous;
      previous = sign;
      ++total;
    }
  const double bound = 5.0 * std::sqrt(0.25 * total);
  EXPECT_NEAR(negative, 0.5 * total, bound);
  EXPECT_NEAR(repeats, 0.5 * (total - 1), bound);
}

TEST(TextonPoints, BalancedPointsAreUniformAndEvenlySpreadInTheirCell) {
  // Each point of the shifted lattice is uniform in the cell over the shift: over 16 384 shifts
  // (a fine grid of both coordinates, offset), point i's u and v fill 16 bins within 5 standard
  // deviations of the binomial count. Unstratified points of a cell come as close as chance
  // makes them (11 uniform points: the nearest pair at a median 0.21 / sqrt(11), 0.41 / sqrt(11)
  // at the 95th percentile); the lattice keeps every pair of n points at least 0.5 / sqrt(n)
  // apart on the torus (measured minimum 0.556 / sqrt(n) over n = 2 to 128).
  constexpr int kBins = 16;
  constexpr int kShifts = 16384;
  for (const std::uint32_t i : {0u, 7u, 100u}) {
    std::vector<int> bins_u(kBins, 0), bins_v(kBins, 0);
    for (int k = 0; k < kShifts; ++k) {
      const float shift = (static_cast<float>(k) + 0.37f) / kShifts;
      const float u = texton::lattice_point(shift, i, texton::kLatticeStepU);
      const float v = texton::lattice_point(shift, i, texton::kLatticeStepV);
      ASSERT_TRUE(u >= 0.0f && u < 1.0f && v >= 0.0f && v < 1.0f);
      ++bins_u[static_cast<std::size_t>(u * kBins)];
      ++bins_v[static_cast<std::size_t>(v * kBins)];
    }
    const double expected = static_cast<double>(kShifts) / kBins;
    const double bound = 5.0 * std::sqrt(expected * (1.0 - 1.0 / kBins));
    for (int b = 0; b < kBins; ++b) {
      EXPECT_NEAR(bins_u[b], expected, bound) << "point " << i << ", u bin " << b;
      EXPECT_NEAR(bins_v[b], expected, bound) << "point " << i << ", v bin " << b;
    }
  }
  for (std::uint32_t n = 2; n <= 128; ++n) {
    double nearest = 2.0;
    for (std::uint32_t a = 0; a < n; ++a)
      for (std::uint32_t b = a + 1; b < n; ++b) {
        const auto torus = [](float x, float y) {
          const double d = std::abs(static_cast<double>(x) - y);
          return std::min(d, 1.0 - d);
        };
        const double du = torus(texton::lattice_point(0.3f, a, texton::kLatticeStepU),
                                texton::lattice_point(0.3f, b, texton::kLatticeStepU));
        const double dv = torus(texton::lattice_point(0.8f, a, texton::kLatticeStepV),
                                texton::lattice_point(0.8f, b, texton::kLatticeStepV));
        nearest = std::min(nearest, std::hypot(du, dv));
      }
    EXPECT_GE(nearest * std::sqrt(n), 0.5) << n << " points";
  }
}

}  // namespace
}  // namespace stochtex::texton_test
