// The GL surface evaluator (GlSurfaceEvaluator, src/gl/surface_gl.cpp) against the CPU reference
// evaluate_surface(): tiling's triplanar mapping (stochtex_tiling_triplanar, triplanar.glsl) on
// points of a sphere with footprints from a point sample to a few pyramid levels.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "gl_support.hpp"
#include "io/image_io.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/surface.hpp"

namespace stochtex {
namespace {

using gl_test::kTextureDir;
using gl_test::max_difference;

// `count` points of a sphere of radius `radius` centred at `centre`, random normals, each with a
// tangent frame and a footprint of `footprint` pixels along the tangent and half as much across.
std::vector<SurfacePoint> sphere_points(int count, double radius, Vec3d centre, double footprint) {
  std::mt19937 engine(17);
  std::normal_distribution<double> normal;
  std::vector<SurfacePoint> points;
  for (int i = 0; i < count; ++i) {
    Vec3d n{normal(engine), normal(engine), normal(engine)};
    const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    n = {n.x / length, n.y / length, n.z / length};
    const Vec3d axis = std::abs(n.x) < 0.9 ? Vec3d{1.0, 0.0, 0.0} : Vec3d{0.0, 1.0, 0.0};
    Vec3d t{n.y * axis.z - n.z * axis.y, n.z * axis.x - n.x * axis.z, n.x * axis.y - n.y * axis.x};
    const double t_length = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
    t = {t.x / t_length, t.y / t_length, t.z / t_length};
    const Vec3d b{n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x};
    points.push_back({{centre.x + radius * n.x, centre.y + radius * n.y, centre.z + radius * n.z},
                      n,
                      t,
                      {footprint * t.x, footprint * t.y, footprint * t.z},
                      {0.5 * footprint * b.x, 0.5 * footprint * b.y, 0.5 * footprint * b.z}});
  }
  return points;
}

// The renderers' parity bound (TilingAndLrpMatchTheCpuReference: 1e-4, GLSL's erf polynomial
// against std::erf; float positions and weights here against the CPU's double).
TEST(GlSurface, TilingTriplanarMatchesTheCpuReference) {
  struct Case {
    const char* exemplar;
    ParamValues params;
  };
  const std::vector<Case> cases = {{"grass_lawn_128.png", {}},
                                   {"metal_grey_256.png", {}},
                                   {"grass_lawn_128.png", {{"transport", 1}}}};
  for (const Case& c : cases) {
    const ImageF exemplar = read_image(kTextureDir + "/" + c.exemplar);
    const Model model = analyze("tiling", exemplar.view(), c.params, 0);
    GlSurfaceEvaluator evaluator(model);
    for (const double footprint : {0.0, 1.0, 3.0, 20.0}) {
      const std::vector<SurfacePoint> points =
          sphere_points(3000, 120.0, {0.0, 0.0, 0.0}, footprint);
      SurfaceOptions options;
      options.mapping = SurfaceMapping::triplanar;
      ImageF cpu(100, 30, model.channels());
      ImageF gpu(100, 30, model.channels());
      evaluate_surface(model, points, options, 5, cpu.view());
      evaluator.evaluate(points, options, 5, gpu.view());
      const float worst = max_difference(cpu, gpu);
      std::cout << c.exemplar << (c.params.empty() ? "" : " transport 1") << " footprint "
                << footprint << ": max |cpu - gl| = " << worst << "\n";
      EXPECT_LT(worst, 1e-4f) << c.exemplar << " footprint " << footprint;
    }
  }
}

TEST(GlSurface, AMappingWithoutGlslIsRefused) {
  const ImageF exemplar = read_image(kTextureDir + "/grass_lawn_128.png");
  const Model tiling = analyze("tiling", exemplar.view(), {}, 0);
  const Model lrp = analyze("lrp", exemplar.view(), {{"cosines", 10}}, 0);
  EXPECT_TRUE(gl_supports_mapping(tiling, SurfaceMapping::triplanar));
  EXPECT_FALSE(gl_supports_mapping(tiling, SurfaceMapping::triplanar_linear));
  EXPECT_FALSE(gl_supports_mapping(lrp, SurfaceMapping::triplanar));
  const std::vector<SurfacePoint> points = sphere_points(4, 10.0, {}, 1.0);
  ImageF out(4, 1, 3);
  SurfaceOptions options;
  options.mapping = SurfaceMapping::triplanar_linear;
  try {
    evaluate_surface_gl(tiling, points, options, 0, out.view());
    ADD_FAILURE() << "accepted";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(),
                 "the gl backend has no GLSL triplanar-linear mapping for tiling models; use "
                 "--backend cpu");
  }
  // The CPU's argument checks come first: lrp has no triplanar mapping at all.
  options.mapping = SurfaceMapping::triplanar;
  EXPECT_THROW(evaluate_surface_gl(lrp, points, options, 0, out.view()), std::invalid_argument);
}

}  // namespace
}  // namespace stochtex
