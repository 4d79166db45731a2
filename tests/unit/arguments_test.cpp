// Arguments out of range (docs/design.md §4 and §9, issue 19): evaluate() and render() refuse NaN,
// infinite and out-of-range positions, footprints and grids before any work; exemplars beyond
// +-kMaxExemplarValue and model arrays beyond +-kMaxModelValue are refused with one sentence.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "model/model_data.hpp"
#include "model/value_range.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::arguments_test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

ImageF random_exemplar(int side, int channels, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  ImageF exemplar(side, side, channels);
  for (float& value : exemplar.pixels()) value = uniform(engine);
  return exemplar;
}

// One small model per method (the registry: a new method is covered without a line here).
const std::vector<Model>& every_model() {
  static const std::vector<Model> models = [] {
    std::vector<Model> out;
    for (const MethodInfo& method : methods())
      out.push_back(analyze(method.name, random_exemplar(16, 3, 5).view(), {}, 0));
    return out;
  }();
  return models;
}

TEST(Arguments, EvaluateRefusesPositionsAndFootprintsOutOfRange) {
  for (const Model& model : every_model()) {
    SCOPED_TRACE(std::string(model.method()));
    ImageF out(1, 1, model.channels());
    const auto evaluate_at = [&](Vec2d p, std::vector<Footprint> footprints) {
      const std::vector<Vec2d> positions = {p};
      evaluate(model, positions, footprints, 1, out.view());
    };
    for (const double bad : {kNaN, kInf, -kInf, 1e19, 1e300, kPositionLimit * 1.0000001}) {
      EXPECT_THROW(evaluate_at({bad, 0.0}, {}), std::invalid_argument) << bad;
      EXPECT_THROW(evaluate_at({0.0, bad}, {}), std::invalid_argument) << bad;
      EXPECT_THROW(evaluate_at({0.0, 0.0}, {{{bad, 0.0}, {0.0, 1.0}}}), std::invalid_argument)
          << bad;
      EXPECT_THROW(evaluate_at({0.0, 0.0}, {{{1.0, 0.0}, {0.0, bad}}}), std::invalid_argument)
          << bad;
    }
    // The edge of the range evaluates to finite values, with and without a footprint.
    evaluate_at({kPositionLimit, -kPositionLimit}, {});
    EXPECT_TRUE(std::isfinite(out.at(0, 0, 0)));
    evaluate_at({-kPositionLimit, kPositionLimit}, {{{4.0, 0.0}, {0.0, 4.0}}});
    EXPECT_TRUE(std::isfinite(out.at(0, 0, 0)));
  }
}

TEST(Arguments, RenderRefusesGridsOutOfRangeBeforeAnyWork) {
  for (const Model& model : every_model()) {
    SCOPED_TRACE(std::string(model.method()));
    ImageF out(4, 3, model.channels());
    const auto render_grid = [&](Grid grid) { render(model, grid, 1, out.view()); };
    const Grid good{{10.0, -20.0}, 1.5, 4, 3};
    for (const double bad : {kNaN, kInf, -kInf}) {
      Grid grid = good;
      grid.scale = bad;
      EXPECT_THROW(render_grid(grid), std::invalid_argument) << "scale " << bad;
      grid = good;
      grid.origin.x = bad;
      EXPECT_THROW(render_grid(grid), std::invalid_argument) << "origin " << bad;
    }
    Grid far = good;
    far.origin = {1e300, -1e300};
    EXPECT_THROW(render_grid(far), std::invalid_argument);
    // In range at the origin, beyond it by the scale or by the region's pixel indices.
    Grid scaled = good;
    scaled.origin = {kPositionLimit - 10.0, 0.0};
    scaled.scale = 4.0;
    EXPECT_THROW(render_grid(scaled), std::invalid_argument);
    Grid region = good;
    region.first_pixel_y = std::numeric_limits<std::int64_t>::min();
    EXPECT_THROW(render_grid(region), std::invalid_argument);
    // Nothing was written: the refusal comes before any work.
    for (const float value : out.pixels()) EXPECT_EQ(value, 0.0f);
    Grid edge = good;
    edge.origin = {kPositionLimit - 10.0, 10.0 - kPositionLimit};
    edge.scale = 2.0;
    render_grid(edge);
    for (const float value : out.pixels()) EXPECT_TRUE(std::isfinite(value));
  }
}

TEST(Arguments, CheckGridNamesTheCallerAndTheRange) {
  try {
    check_grid(Grid{{1e300, 0.0}, 1.0, 8, 8}, "--origin 1e300,0");
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("--origin 1e300,0", 0), 0u) << what;
    EXPECT_NE(what.find("4294967296"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(check_grid(Grid{{-100.0, 5.0}, 0.5, 8, 8, -3, 1000}, "grid"));
}

TEST(Arguments, ExemplarValuesBeyondTheRangeAreRefused) {
  ImageF exemplar = random_exemplar(8, 1, 3);
  for (const float value : {kMaxExemplarValue, -kMaxExemplarValue}) {
    exemplar.at(2, 3, 0) = value;
    EXPECT_NO_THROW(validate_exemplar(exemplar.view(), "x.exr"));
  }
  for (const float value : {3e38f, -1.5e6f, 1.0000001e6f}) {
    exemplar.at(2, 3, 0) = value;
    try {
      validate_exemplar(exemplar.view(), "x.exr");
      ADD_FAILURE() << value << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::invalid_input);
      const std::string what = e.what();
      EXPECT_NE(what.find("'x.exr'"), std::string::npos) << what;
      EXPECT_NE(what.find("(2, 3)"), std::string::npos) << what;
    }
  }
}

TEST(Arguments, ExemplarsAtTheEdgeOfTheRangeRenderFinite) {
  // The largest accepted values give models within kMaxModelValue that render finite values.
  ImageF exemplar = random_exemplar(24, 3, 9);
  for (float& value : exemplar.pixels()) value = (2.0f * value - 1.0f) * kMaxExemplarValue;
  for (const MethodInfo& method : methods()) {
    SCOPED_TRACE(std::string(method.name));
    const Model model =
        deserialize_model(serialize_model(analyze(method.name, exemplar.view(), {}, 0)), "x.stx");
    ImageF out(16, 16, 3);
    render(model, Grid{{-5.0, 7.0}, 1.7, 16, 16}, 2, out.view());
    for (const float value : out.pixels()) ASSERT_TRUE(std::isfinite(value));
  }
}

TEST(Arguments, ModelArrayValuesBeyondTheRangeAreRefused) {
  for (const Model& model : every_model()) {
    SCOPED_TRACE(std::string(model.method()));
    std::visit(
        [&](const auto& typed) {
          using Method = std::decay_t<decltype(typed)>;
          const ModelRecord good = typed.to_record(model.params());
          for (const NamedArray& array : good.arrays) {
            // Gabor's spectrum preview is written for readers of the file and recomputed from
            // the Gaussians on load, never read.
            if (array.name == "spectrum") continue;
            for (const float value : {1e38f, -3e38f, -1.01f * kMaxModelValue}) {
              ModelRecord record = good;
              test_support::record_array(record, array.name).back() = value;
              test_support::expect_record_rejected<Method>(
                  record, array.name + " = " + std::to_string(value));
            }
          }
        },
        model.data().model);
  }
}

}  // namespace
}  // namespace stochtex::arguments_test
