// The GL surface evaluator (GlSurfaceEvaluator, src/gl/surface_gl.cpp) against the CPU reference
// evaluate_surface(): tiling's triplanar mapping (stochtex_tiling_triplanar, triplanar.glsl) on
// points of a sphere with footprints from a point sample to a few pyramid levels.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "gl_support.hpp"
#include "io/image_io.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/surface.hpp"

namespace stochtex {
namespace {

using gl_test::kTextureDir;
using gl_test::max_difference;

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
          test_support::sphere_points(3000, 120.0, footprint, 0.5 * footprint, 17);
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
  const std::vector<SurfacePoint> points = test_support::sphere_points(4, 10.0, 1.0, 0.5, 17);
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
