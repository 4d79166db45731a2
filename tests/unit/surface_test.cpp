// Surface evaluation (stochtex/surface.hpp): mapping names, argument checks, batch independence,
// and linear triplanar mapping, which on an axis-aligned plane is the plain 2-D evaluation of that
// plane's projection.

#include "stochtex/surface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex {
namespace {

Model test_model(std::string_view method) {
  std::mt19937 engine(8);
  std::normal_distribution<float> normal(0.5f, 0.1f);
  ImageF exemplar(32, 32, 3);
  for (float& value : exemplar.pixels()) value = normal(engine);
  return analyze(method, exemplar.view(), {}, 3);
}

const Model& tiling_model() {
  static const Model model = test_model("tiling");
  return model;
}

// Points spread over a sphere of radius 40 with a frame each, and a footprint of 0.7 pixel.
std::vector<SurfacePoint> sphere_points(int count) {
  return test_support::sphere_points(count, 40.0, 0.7, 0.0, 5);
}

ImageF evaluate_points(const Model& model, std::span<const SurfacePoint> points,
                       const SurfaceOptions& options, std::uint32_t seed) {
  ImageF out(static_cast<int>(points.size()), 1, model.channels());
  evaluate_surface(model, points, options, seed, out.view());
  return out;
}

TEST(Surface, MappingNamesRoundTrip) {
  for (const SurfaceMapping mapping :
       {SurfaceMapping::surface, SurfaceMapping::triplanar, SurfaceMapping::triplanar_linear})
    EXPECT_EQ(mapping_from_name(mapping_name(mapping)), mapping);
  EXPECT_THROW(mapping_from_name("uv"), std::invalid_argument);
}

TEST(Surface, LinearTriplanarOnAnAxisPlaneIsThePlanarEvaluation) {
  const Model& model = tiling_model();
  std::vector<SurfacePoint> points;
  std::vector<Vec2d> positions;
  std::vector<Footprint> footprints;
  for (int i = 0; i < 100; ++i) {
    const double x = 0.37 * i - 11.0;
    const double y = 0.91 * i + 3.0;
    points.push_back({{x, y, 5.0}, {0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}, {1.5, 0.0, 0.0}, {}});
    positions.push_back({x, y});
    footprints.push_back({{1.5, 0.0}, {0.0, 0.0}});
  }
  SurfaceOptions options;
  options.mapping = SurfaceMapping::triplanar_linear;
  const ImageF surface = evaluate_points(model, points, options, 7);
  // The (x, y) plane is the third projection: seed stream 7 + 2.
  ImageF planar(100, 1, model.channels());
  evaluate(model, positions, footprints, 9, planar.view());
  EXPECT_TRUE(test_support::same_bytes(surface, planar));
}

TEST(Surface, TheSameWhateverTheBatchSplit) {
  const Model& model = tiling_model();
  const std::vector<SurfacePoint> points = sphere_points(150);
  SurfaceOptions options;
  options.mapping = SurfaceMapping::triplanar_linear;
  const ImageF whole = evaluate_points(model, points, options, 4);
  ImageF split(150, 1, model.channels());
  evaluate_surface(model, std::span(points).first(61), options, 4, split.view().sub(0, 0, 61, 1));
  evaluate_surface(model, std::span(points).subspan(61), options, 4,
                   split.view().sub(61, 0, 89, 1));
  EXPECT_TRUE(test_support::same_bytes(whole, split));
}

TEST(Surface, BadArgumentsAreRefusedBeforeAnyWork) {
  const Model& model = tiling_model();
  std::vector<SurfacePoint> points = sphere_points(4);
  SurfaceOptions options;
  options.mapping = SurfaceMapping::triplanar_linear;
  ImageF out(4, 1, model.channels());
  const auto refused = [&](const std::vector<SurfacePoint>& bad, const SurfaceOptions& o) {
    EXPECT_THROW(evaluate_surface(model, bad, o, 0, out.view()), std::invalid_argument);
  };
  for (int field = 0; field < 4; ++field) {
    std::vector<SurfacePoint> bad = points;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (field == 0) bad[1].position.x = nan;
    if (field == 1) bad[2].normal = {0.0, 0.0, 2.0};
    if (field == 2) bad[3].tangent = bad[3].normal;
    if (field == 3) bad[0].dpdy.z = std::numeric_limits<double>::infinity();
    refused(bad, options);
  }
  SurfaceOptions sharp = options;
  sharp.triplanar_sharpness = std::numeric_limits<double>::quiet_NaN();
  refused(points, sharp);
  ImageF grey(4, 1, 1);
  EXPECT_THROW(evaluate_surface(model, points, options, 0, grey.view()), std::invalid_argument);
  EXPECT_THROW(evaluate_surface(Model(), points, options, 0, out.view()), std::invalid_argument);
  EXPECT_NO_THROW(evaluate_surface(model, points, options, 0, out.view()));
}

TEST(Surface, AModelWithoutTheMappingIsRefused) {
  const Model model = test_model("lrp");
  EXPECT_FALSE(supports_mapping(model, SurfaceMapping::surface));
  EXPECT_FALSE(supports_mapping(model, SurfaceMapping::triplanar));
  EXPECT_TRUE(supports_mapping(model, SurfaceMapping::triplanar_linear));
  const std::vector<SurfacePoint> points = sphere_points(3);
  ImageF out(3, 1, model.channels());
  SurfaceOptions options;
  try {
    evaluate_surface(model, points, options, 0, out.view());
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "evaluate_surface: lrp models have no surface mapping");
  }
}

}  // namespace
}  // namespace stochtex
