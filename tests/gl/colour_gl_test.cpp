// srgb models on the GL backend (issue 36, docs/design.md §14): render_gl and the GL surface
// evaluator return linear light as the CPU does. render_gl decodes the shader's values after the
// read-back with the CPU's own function (decode_expectation, one footprint width per grid), the
// surface functions in GLSL (gl/colour.glsl: each point's footprint, each plane's for linear
// triplanar mapping), and tiling's GL twin reads the tables that decode its colour. Each case
// compares the srgb model's CPU and GL renders against the parity of the same model as data: the
// decoding multiplies a difference by at most its slope, 5.8 over the table's means -1 to 2
// (2.4 / 1.055 ((2 + 0.055) / 1.055)^1.4), so the srgb gap stays within 5.8 times the data gap
// (plus 1e-6 of float rounding). A backend that returned encoded values would miss it by the
// decoding itself (about 0.2 at mid-grey).

#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <vector>

#include "gl_support.hpp"
#include "io/image_io.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::colour_gl_test {
namespace {

using gl_test::kTextureDir;
using gl_test::max_difference;
using gl_test::render_cpu;

using gl_test::kDecodingSlope;

ImageF render_gpu(const Model& model, const Grid& grid, GlFilter filter) {
  ImageF out(grid.width, grid.height, model.channels());
  GpuRenderOptions options;
  options.texture_filter = filter;
  render_gl(model, grid, 5, out.view(), options);
  return out;
}

TEST(GlColour, SrgbRendersMatchTheCpuReference) {
  const std::vector<gl_test::ExportCase> cases = gl_test::export_cases();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const gl_test::ExportCase& c = cases[k];
    const Model& data = gl_test::case_models()[k][0];
    const Model& srgb = gl_test::case_models()[k][1];
    std::vector<GlFilter> filters = {GlFilter::exact};
    if (std::string(c.method) == "texton" || std::string(c.method) == "tiling")
      filters.push_back(GlFilter::hardware);
    for (const GlFilter filter : filters)
      for (const double scale : {1.0, 16.0}) {
        const Grid grid{{-20.5, 13.0}, scale, c.size, c.size};
        const float raw = max_difference(render_cpu(data, grid, 5), render_gpu(data, grid, filter));
        const float decoded =
            max_difference(render_cpu(srgb, grid, 5), render_gpu(srgb, grid, filter));
        const std::string label = std::string(c.method) + " " + c.exemplar + " scale " +
                                  std::to_string(scale) +
                                  (filter == GlFilter::hardware ? " hardware" : " exact");
        std::cout << label << ": max |cpu - gl| data " << raw << ", srgb " << decoded << "\n";
        EXPECT_LE(decoded, kDecodingSlope * raw + 1e-6f) << label;
      }
  }
}

TEST(GlColour, SrgbSurfaceMappingsMatchTheCpuReference) {
  const ImageF grass = read_image(kTextureDir + "/grass_lawn_128.png");
  struct Case {
    const char* method;
    ParamValues params;
    SurfaceMapping mapping;
  };
  const std::vector<Case> cases = {
      {"texton", {{"support", 24}}, SurfaceMapping::surface},
      {"texton", {{"support", 24}}, SurfaceMapping::triplanar_linear},
      {"tiling", {}, SurfaceMapping::triplanar},
  };
  for (const Case& c : cases) {
    const Model data = analyze(c.method, grass.view(), c.params, 0);
    const Model srgb = with_colour_space(data, ColourSpace::srgb);
    SurfaceOptions options;
    options.mapping = c.mapping;
    for (const double footprint : {0.0, 3.0, 20.0}) {
      const std::vector<SurfacePoint> points =
          test_support::sphere_points(600, 120.0, footprint, 0.37 * footprint, 17);
      const auto gap = [&](const Model& model) {
        ImageF cpu(static_cast<int>(points.size()), 1, model.channels());
        ImageF gpu(static_cast<int>(points.size()), 1, model.channels());
        evaluate_surface(model, points, options, 5, cpu.view());
        evaluate_surface_gl(model, points, options, 5, gpu.view());
        return max_difference(cpu, gpu);
      };
      const float raw = gap(data);
      const float decoded = gap(srgb);
      const std::string label = std::string(c.method) + " " + std::string(mapping_name(c.mapping)) +
                                " footprint " + std::to_string(footprint);
      std::cout << label << ": max |cpu - gl| data " << raw << ", srgb " << decoded << "\n";
      EXPECT_LE(decoded, kDecodingSlope * raw + 1e-6f) << label;
    }
  }
}

}  // namespace
}  // namespace stochtex::colour_gl_test
