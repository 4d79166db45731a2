// Surface evaluation (stochtex/surface.hpp): mapping names, argument checks, batch independence,
// and linear triplanar mapping, which on an axis-aligned plane is the plain 2-D evaluation of that
// plane's projection.

#include "stochtex/surface.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::surface_test {
namespace {

using test_support::white_noise_model;

const Model& tiling_model() {
  static const Model model = white_noise_model("tiling");
  return model;
}

// Small texton and gabor models (support 12: textons about 13 pixels wide) for surface noise.
const Model& surface_model(std::string_view method) {
  static const Model texton = [] {
    std::mt19937 engine(8);
    std::normal_distribution<float> normal(0.5f, 0.1f);
    ImageF exemplar(32, 32, 3);
    for (float& value : exemplar.pixels()) value = normal(engine);
    return analyze("texton", exemplar.view(), {{"support", 12}}, 3);
  }();
  static const Model gabor = white_noise_model("gabor");
  return method == "texton" ? texton : gabor;
}

// The frame field of a mesh without texture coordinates (docs/surface.md): the tangent is the
// fixed axis e_x projected on the tangent plane, singular only where the normal is +-e_x.
SurfacePoint with_frame(const Vec3d& position, Vec3d n) {
  const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  n = {n.x / length, n.y / length, n.z / length};
  Vec3d t{1.0 - n.x * n.x, -n.x * n.y, -n.x * n.z};
  const double t_length = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
  t = {t.x / t_length, t.y / t_length, t.z / t_length};
  return {position, n, t, {}, {}};
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
  const Model model = white_noise_model("lrp");
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

TEST(SurfaceNoise, TheSameWhateverTheBatchSplit) {
  for (const std::string_view method : {"texton", "gabor"}) {
    const Model& model = surface_model(method);
    ASSERT_TRUE(supports_mapping(model, SurfaceMapping::surface)) << method;
    const std::vector<SurfacePoint> points = sphere_points(150);
    const SurfaceOptions options;
    const ImageF whole = evaluate_points(model, points, options, 4);
    ImageF split(150, 1, model.channels());
    evaluate_surface(model, std::span(points).first(61), options, 4, split.view().sub(0, 0, 61, 1));
    evaluate_surface(model, std::span(points).subspan(61), options, 4,
                     split.view().sub(61, 0, 89, 1));
    EXPECT_TRUE(test_support::same_bytes(whole, split)) << method;
  }
}

TEST(SurfaceNoise, OnAPlaneValuesAreFiniteAndDependOnlyOnThePosition) {
  for (const std::string_view method : {"texton", "gabor"}) {
    const Model& model = surface_model(method);
    // The plane z = 3 with the frame (e_x, e_y): points, then the same points reversed and one
    // of them twice, with footprints that differ only along the normal (which projects to 0).
    std::vector<SurfacePoint> points;
    for (int i = 0; i < 64; ++i)
      points.push_back({{0.83 * i - 20.0, 0.37 * i + 1e6, 3.0},
                        {0.0, 0.0, 1.0},
                        {1.0, 0.0, 0.0},
                        {0.0, 0.0, 0.5 * (i % 3)},
                        {}});
    std::vector<SurfacePoint> reversed(points.rbegin(), points.rend());
    reversed.push_back(points[5]);
    const SurfaceOptions options;
    const ImageF forward = evaluate_points(model, points, options, 9);
    const ImageF backward = evaluate_points(model, reversed, options, 9);
    double variation = 0.0;
    for (int i = 0; i < 64; ++i)
      for (int c = 0; c < model.channels(); ++c) {
        ASSERT_TRUE(std::isfinite(forward.at(i, 0, c))) << method;
        EXPECT_EQ(forward.at(i, 0, c), backward.at(63 - i, 0, c)) << method;
        variation += std::abs(forward.at(i, 0, c) - forward.at(0, 0, c));
      }
    for (int c = 0; c < model.channels(); ++c)
      EXPECT_EQ(backward.at(64, 0, c), forward.at(5, 0, c)) << method;
    EXPECT_GT(variation, 0.0) << method << ": a constant is not a noise";
    // Another seed, another noise.
    EXPECT_FALSE(test_support::same_bytes(forward, evaluate_points(model, points, options, 10)));
  }
}

TEST(SurfaceNoise, SurfaceMniOutOfRangeIsRefused) {
  const Model& model = surface_model("texton");
  const std::vector<SurfacePoint> points = sphere_points(3);
  ImageF out(3, 1, model.channels());
  for (const double mni : {0.5, 1001.0, std::numeric_limits<double>::quiet_NaN()}) {
    SurfaceOptions options;
    options.surface_mni = mni;
    EXPECT_THROW(evaluate_surface(model, points, options, 0, out.view()), std::invalid_argument);
  }
}

// A mesh without texture coordinates: two triangles sharing the edge (A, B), per-vertex normals
// interpolated (shared at A and B), the frame from the fixed axis e_x. Points at distance d on
// either side of the edge converge to the same value as d -> 0: the noise is continuous across
// the edge (docs/surface.md). Measured largest gap over 40 points along the edge at d = 1, 0.1,
// 0.01, 0.001 pixel: texton 0.43, 0.090, 0.0094, 0.00095; gabor 0.36, 0.082, 0.0082, 0.00094
// (linear in d: the noise is Lipschitz).
TEST(SurfaceNoise, ContinuousAcrossATriangleEdge) {
  const Vec3d a{0.0, 0.0, 0.0}, b{60.0, 10.0, 5.0}, c{20.0, 50.0, 30.0}, e{40.0, -45.0, -20.0};
  const Vec3d na{0.1, 0.2, 1.0}, nb{-0.3, 0.4, 1.0}, nc{0.5, -0.6, 1.0}, ne{0.2, 0.7, 1.0};
  const auto mix = [](const Vec3d& p, const Vec3d& q, const Vec3d& r, double wp, double wq,
                      double wr) {
    return Vec3d{wp * p.x + wq * q.x + wr * r.x, wp * p.y + wq * q.y + wr * r.y,
                 wp * p.z + wq * q.z + wr * r.z};
  };
  for (const std::string_view method : {"texton", "gabor"}) {
    const Model& model = surface_model(method);
    std::vector<double> gaps;
    for (const double distance : {1.0, 1e-1, 1e-2, 1e-3}) {
      std::vector<SurfacePoint> points;
      for (int i = 1; i <= 40; ++i) {
        const double s = i / 41.0;
        // Barycentric weight `w` of the far vertex: a point at about `distance` from the edge.
        const double w = distance / 50.0;
        points.push_back(with_frame(mix(a, b, c, (1.0 - s) * (1.0 - w), s * (1.0 - w), w),
                                    mix(na, nb, nc, (1.0 - s) * (1.0 - w), s * (1.0 - w), w)));
        points.push_back(with_frame(mix(a, b, e, (1.0 - s) * (1.0 - w), s * (1.0 - w), w),
                                    mix(na, nb, ne, (1.0 - s) * (1.0 - w), s * (1.0 - w), w)));
      }
      const ImageF values = evaluate_points(model, points, {}, 3);
      double gap = 0.0;
      for (int i = 0; i < 80; i += 2)
        for (int k = 0; k < model.channels(); ++k)
          gap = std::max<double>(gap, std::abs(values.at(i, 0, k) - values.at(i + 1, 0, k)));
      gaps.push_back(gap);
    }
    std::cout << method << " largest gap across the edge at d = 1, 0.1, 0.01, 0.001: " << gaps[0]
              << " " << gaps[1] << " " << gaps[2] << " " << gaps[3] << "\n";
    // The noise is Lipschitz (bilinear texton, Gaussian kernel, tent weight): the gap shrinks
    // with d, to float rounding; at d = 1 it is a real difference (the test can fail).
    EXPECT_GT(gaps[0], 1e-2) << method;
    EXPECT_LT(gaps[2], 0.2 * gaps[0]) << method;
    EXPECT_LT(gaps[3], 2e-3) << method;
  }
}

}  // namespace
}  // namespace stochtex::surface_test
