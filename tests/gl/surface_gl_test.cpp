// The GL surface evaluator (GlSurfaceEvaluator, src/gl/surface_gl.cpp) against the CPU reference
// evaluate_surface(): tiling's triplanar mapping (stochtex_tiling_triplanar, triplanar.glsl),
// texton and Gabor surface noise (stochtex_texton_surface, stochtex_gabor_surface) and linear
// triplanar mapping (stochtex_triplanar_linear) on points of a sphere with footprints from a point
// sample to a few pyramid levels; and surface_process.glsl's 3-D cell key against core/hash.hpp.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "core/hash.hpp"
#include "gl/context.hpp"
#include "gl/program.hpp"
#include "gl/shaders.hpp"
#include "gl_support.hpp"
#include "io/image_io.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::surface_gl_test {
namespace {

using gl_test::kTextureDir;
using gl_test::max_difference;

TEST(GlSurface, CellKey3dGlslMatchesTheCppSpec) {
  // surface_process.glsl's cell_key(x, y, z, seed, stream) run by a one-off compute shader, bit
  // for bit against core/hash.hpp, negative cells included (their low 32 bits).
  const gl::Context context;
  const std::string source = "#version 450\n" + gl::random_source() +
                             "#define SURFACE_CONTEXT int\n" +
                             gl::shader_source("gl/surface_process.glsl") + R"glsl(
// The walk's callbacks, which the linker wants defined.
uint surface_impulse_count(inout CounterRng rng, int context) { return 0u; }
void surface_impulse(inout CounterRng rng, float t, float z1, float z2, int context,
                     inout vec4 acc) {}
layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer Out { uint values[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  values[i] = cell_key(i * 7919u, 0u - i, i * 31u - 500u, i ^ 0x5bd1e995u, STREAM_POINTS);
}
)glsl";
  const gl::Program program(source);
  constexpr std::uint32_t kCount = 1024;
  const gl::Buffer buffer(kCount * sizeof(std::uint32_t));
  glUseProgram(program.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.id());
  glDispatchCompute(kCount / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<std::uint32_t> values(kCount);
  glGetNamedBufferSubData(buffer.id(), 0,
                          static_cast<GLsizeiptr>(values.size() * sizeof(std::uint32_t)),
                          values.data());
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  for (std::uint32_t i = 0; i < kCount; ++i)
    ASSERT_EQ(values[i],
              cell_key(static_cast<std::int64_t>(i * 7919u), -static_cast<std::int64_t>(i),
                       static_cast<std::int64_t>(i) * 31 - 500, i ^ 0x5bd1e995u, Stream::points))
        << i;
}

// The largest difference between the CPU's evaluate_surface and `evaluator` on `points` (seed 5).
float largest_difference(const Model& model, GlSurfaceEvaluator& evaluator,
                         const std::vector<SurfacePoint>& points, const SurfaceOptions& options) {
  ImageF cpu(static_cast<int>(points.size()), 1, model.channels());
  ImageF gpu(static_cast<int>(points.size()), 1, model.channels());
  evaluate_surface(model, points, options, 5, cpu.view());
  evaluator.evaluate(points, options, 5, gpu.view());
  return max_difference(cpu, gpu);
}

// The renderers' parity bound (TilingAndLrpMatchTheCpuReference: 1e-4, GLSL's erf polynomial
// against the C++ rational erf; float positions and weights here against the CPU's double).
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
      const float worst = largest_difference(model, evaluator, points, options);
      std::cout << c.exemplar << (c.params.empty() ? "" : " transport 1") << " footprint "
                << footprint << ": max |cpu - gl| = " << worst << "\n";
      EXPECT_LT(worst, 1e-4f) << c.exemplar << " footprint " << footprint;
    }
  }
}

// Surface noise on the GPU against the CPU on `count` points of a sphere of radius `radius`, at
// MNI 60 and 15 and footprints from a point sample to a few pyramid levels: the largest
// difference, below `bound`. The footprints stay off the texton filter's discontinuities, which
// float rounding could put either side: the point sample up to a major axis of 1 pixel, and the
// probe count ceil(major / max(minor, 1)) jumping at integer ratios (0.37 keeps it at 3).
void expect_surface_parity(const Model& model, const std::string& label, int count, double radius,
                           float bound) {
  GlSurfaceEvaluator evaluator(model);
  for (const double mni : {60.0, 15.0}) {
    for (const double footprint : {0.0, 1.5, 3.0, 20.0}) {
      const std::vector<SurfacePoint> points =
          test_support::sphere_points(count, radius, footprint, 0.37 * footprint, 17);
      SurfaceOptions options;
      options.surface_mni = mni;
      const float worst = largest_difference(model, evaluator, points, options);
      std::cout << label << " radius " << radius << " mni " << mni << " footprint " << footprint
                << ": max |cpu - gl| = " << worst << "\n";
      EXPECT_LT(worst, bound) << label << " radius " << radius << " mni " << mni << " footprint "
                              << footprint;
    }
  }
}

// Texton surface noise (stochtex_texton_surface, texton surface.glsl on surface_process.glsl):
// the GPU walks the CPU's impulses (same cells, keys and draws) and sums the same filtered textons,
// so they differ by float rounding, growing with |position| (float on the GPU, double on the CPU).
// Measured maxima over 600 points: 3.4e-6 (radius 120), 1.0e-5 (460), 6.5e-5 (3000 pixels from
// the origin); the bounds keep a 3x margin.
TEST(GlSurface, TextonSurfaceNoiseMatchesTheCpuReference) {
  const ImageF metal = read_image(kTextureDir + "/metal_grey_256.png");
  const ImageF grass = read_image(kTextureDir + "/grass_lawn_128.png");
  const Model grey = analyze("texton", metal.view(), {{"support", 24}, {"order", 1}}, 0);
  const Model colour = analyze("texton", grass.view(), {{"support", 24}, {"order", 3}}, 0);
  expect_surface_parity(grey, "texton grey", 600, 120.0, 1e-5f);
  expect_surface_parity(colour, "texton colour", 600, 120.0, 1e-5f);
  expect_surface_parity(grey, "texton grey", 600, 460.0, 3e-5f);
  expect_surface_parity(grey, "texton grey", 600, 3000.0, 2e-4f);
}

// Surface Gabor noise (stochtex_gabor_surface, gabor surface.glsl on surface_process.glsl): the
// same impulses and kernels, exp and cos as the same float polynomials on both sides. Measured
// maxima over 300 points: 6.9e-6 (radius 120), 3.7e-5 (460), 1.1e-4 (3000: a float position's
// error moves each kernel's phase; 5.4e-4 before the kernel taper, where it also moved kernels
// across the support's edge); bounds with a 3x margin.
TEST(GlSurface, GaborSurfaceNoiseMatchesTheCpuReference) {
  const ImageF metal = read_image(kTextureDir + "/metal_grey_256.png");
  const ImageF grass = read_image(kTextureDir + "/grass_lawn_128.png");
  const ParamValues params = {{"impulses", 64}, {"iterations", 30}};
  const Model grey = analyze("gabor", metal.view(), params, 0);
  const Model colour = analyze("gabor", grass.view(), params, 0);
  expect_surface_parity(grey, "gabor grey", 300, 120.0, 3e-5f);
  expect_surface_parity(colour, "gabor colour", 300, 120.0, 3e-5f);
  expect_surface_parity(grey, "gabor grey", 300, 460.0, 1e-4f);
  expect_surface_parity(grey, "gabor grey", 300, 3000.0, 4e-4f);
}

// Linear triplanar mapping (triplanar_linear.glsl) calls each method's planar GLSL on the three
// axis planes, as the CPU calls evaluate(). Measured maxima over 600 points of a sphere of radius
// 120 at sharpness 4 and the footprints below (float positions and weights against double): texton
// 6.0e-7, tiling 5.2e-6 (1.7e-6 at the tile radius 1/2 of the earlier default; the radius chosen
// from this exemplar, 0.354, puts more lattice vertices in float), gabor 1.4e-6; bounds 3x each.
TEST(GlSurface, LinearTriplanarMatchesTheCpuReference) {
  const ImageF exemplar = read_image(kTextureDir + "/grass_lawn_128.png");
  const std::vector<std::pair<Model, float>> models = {
      {analyze("texton", exemplar.view(), {{"support", 24}}, 0), 2e-6f},
      {analyze("tiling", exemplar.view(), {}, 0), 1.6e-5f},
      {analyze("gabor", exemplar.view(), {{"impulses", 64}, {"iterations", 30}}, 0), 4.5e-6f}};
  for (const auto& [model, bound] : models) {
    GlSurfaceEvaluator evaluator(model);
    // sphere_points' tangents lie in the (y,z) plane wherever |n_x| < 0.9, so there the projected
    // footprint is exactly `footprint` long: 3.3, not 3, keeps texton's probe count off a jump.
    for (const double footprint : {0.0, 1.5, 3.3, 20.0}) {
      const std::vector<SurfacePoint> points =
          test_support::sphere_points(600, 120.0, footprint, 0.37 * footprint, 17);
      SurfaceOptions options;
      options.mapping = SurfaceMapping::triplanar_linear;
      const float worst = largest_difference(model, evaluator, points, options);
      std::cout << model.method() << " triplanar-linear footprint " << footprint
                << ": max |cpu - gl| = " << worst << "\n";
      EXPECT_LT(worst, bound) << model.method() << " footprint " << footprint;
    }
  }
}

TEST(GlSurface, AMappingWithoutGlslIsRefused) {
  const ImageF exemplar = read_image(kTextureDir + "/grass_lawn_128.png");
  const Model tiling = analyze("tiling", exemplar.view(), {}, 0);
  const Model lrp = analyze("lrp", exemplar.view(), {{"cosines", 10}}, 0);
  EXPECT_TRUE(gl_supports_mapping(tiling, SurfaceMapping::triplanar));
  EXPECT_TRUE(gl_supports_mapping(tiling, SurfaceMapping::triplanar_linear));
  EXPECT_FALSE(gl_supports_mapping(tiling, SurfaceMapping::surface));
  EXPECT_FALSE(gl_supports_mapping(lrp, SurfaceMapping::triplanar));
  EXPECT_FALSE(gl_supports_mapping(lrp, SurfaceMapping::triplanar_linear));
  const std::vector<SurfacePoint> points = test_support::sphere_points(4, 10.0, 1.0, 0.5, 17);
  ImageF out(4, 1, 3);
  SurfaceOptions options;
  options.mapping = SurfaceMapping::triplanar_linear;
  try {
    evaluate_surface_gl(lrp, points, options, 0, out.view());
    ADD_FAILURE() << "accepted";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(),
                 "the gl backend has no GLSL triplanar-linear mapping for lrp models; use "
                 "--backend cpu");
  }
  // The CPU's argument checks come first: lrp has no triplanar mapping at all.
  options.mapping = SurfaceMapping::triplanar;
  EXPECT_THROW(evaluate_surface_gl(lrp, points, options, 0, out.view()), std::invalid_argument);
}

}  // namespace
}  // namespace stochtex::surface_gl_test
