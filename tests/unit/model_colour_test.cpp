// A model's colour (docs/design.md §14, model/model_colour.hpp): the expectation of decoded
// colour D(m, s), the removed deviations a model's own evaluator gives, and srgb renders that are
// the same bytes on every CPU target and thread count.

#include "model/model_colour.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/srgb.hpp"
#include "model/model_data.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::model_colour_test {
namespace {

// E[decode(m + s Z)] by the midpoint rule on 20 000 steps of Z over [-8, 8].
double reference_expectation(double mean, double deviation) {
  constexpr int kSteps = 20000;
  double sum = 0.0;
  double weights = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double z = -8.0 + 16.0 * (i + 0.5) / kSteps;
    const double w = std::exp(-0.5 * z * z);
    sum += w * srgb_decode(mean + deviation * z);
    weights += w;
  }
  return sum / weights;
}

TEST(ModelColour, ExpectationOfDecodedColour) {
  // A point sample is decoded exactly.
  for (const float v : {-0.2f, 0.0f, 0.02f, 0.04045f, 0.3f, 0.5f, 1.0f, 1.4f})
    EXPECT_EQ(expected_decoded(v, 0.0f), srgb_decode(v)) << v;
  // Elsewhere the table is within a tenth of an 8-bit level of the quadrature, once encoded (how
  // a PNG output shows it), inside and between its cells.
  for (const double mean : {-0.3, 0.01, 0.2, 0.4137, 0.5, 0.77, 1.0, 1.3})
    for (const double deviation : {0.004, 0.05, 0.1234, 0.3, 0.7, 1.2})
      EXPECT_NEAR(srgb_encode(static_cast<double>(
                      expected_decoded(static_cast<float>(mean), static_cast<float>(deviation)))),
                  srgb_encode(reference_expectation(mean, deviation)), 0.1 / 255.0)
          << mean << " " << deviation;
  // It grows with the deviation, decoding being convex: zoomed out, brighter than decode(mean).
  EXPECT_GT(expected_decoded(0.5f, 0.2f), srgb_decode(0.5f));
}

Model grey_model(const std::string& method) {
  std::mt19937 engine(9);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  ImageF exemplar(48, 48, 1);
  for (float& v : exemplar.pixels()) v = normal(engine);
  // A smooth texture of values in about [0.1, 0.9].
  ImageF smooth(48, 48, 1);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) {
      float sum = 0.0f;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx)
          sum += exemplar.at((x + dx + 48) % 48, (y + dy + 48) % 48, 0);
      smooth.at(x, y, 0) = 0.5f + 0.04f * sum;
    }
  const ParamValues fast =
      method == "texton" ? ParamValues{{"support", 12}, {"iterations", 5}} : ParamValues{};
  return analyze(method, smooth.view(), fast, 1);
}

// The srgb texton model of grey_model, made once for the tests below (measuring its removed
// deviations evaluates it some 10^5 times, seconds under the sanitizers).
const Model& srgb_texton() {
  static const Model model = with_colour_space(grey_model("texton"), ColourSpace::srgb);
  return model;
}

TEST(ModelColour, RemovedDeviationIsTheMethodsOwnFilter) {
  const Model& srgb = srgb_texton();
  const ModelColour& colour = srgb.data().colour;
  ASSERT_EQ(colour.removed_deviation.size(), static_cast<std::size_t>(kRemovedSteps));
  EXPECT_EQ(removed_deviation(colour, 1, 0, 1.0), 0.0f);
  EXPECT_EQ(removed_deviation(colour, 1, 0, 0.0), 0.0f);
  // Non-decreasing with the footprint (measured, to the noise of 8 192 samples), up to the
  // channel's whole deviation far beyond the texture's correlation length.
  float previous = 0.0f;
  for (int k = 0; k < kRemovedSteps; ++k) {
    const float r = colour.removed_deviation[static_cast<std::size_t>(k)];
    EXPECT_GE(r, previous - 0.01f * colour.removed_deviation.back()) << k;
    previous = std::max(previous, r);
  }
  EXPECT_GT(colour.removed_deviation.back(), 0.0f);
  EXPECT_NEAR(removed_deviation(colour, 1, 0, 1e6), colour.removed_deviation.back(), 1e-6);
}

// Decoding after evaluation (texton) and in the tables (tiling, whose calibration evaluates the
// model as it is made) give the same bytes on the scalar reference and the best vector target
// (CpuTargets.* holds every target to the reference's bytes) and whatever the threads and tiles.
TEST(ModelColour, SrgbRendersAreTheSameBytesOnEveryTargetAndThreadCount) {
  const Model tiling_data = grey_model("tiling");
  for (const bool tiling : {false, true}) {
    std::vector<float> first;
    for (const CpuTarget target : {CpuTarget::reference, available_cpu_targets().back()}) {
      set_cpu_target(target);
      const Model srgb = tiling ? with_colour_space(tiling_data, ColourSpace::srgb) : srgb_texton();
      for (const int threads : {1, 2}) {
        ImageF image(40, 24, 1);
        RenderOptions options;
        options.threads = threads;
        options.tile_size = threads == 1 ? 64 : 8;
        render(srgb, Grid{{3.0, 5.0}, 3.5, 40, 24}, 7, image.view(), options);
        const std::vector<float> values(image.pixels().begin(), image.pixels().end());
        if (first.empty()) first = values;
        EXPECT_EQ(values, first) << (tiling ? "tiling " : "texton ") << cpu_target_name(target)
                                 << " " << threads;
      }
    }
    set_cpu_target(available_cpu_targets().back());
  }
}

}  // namespace
}  // namespace stochtex::model_colour_test
