#pragma once
// Shared by the OpenGL tests: CPU and GL renders of one grid, and their comparison.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "stochtex/gpu.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::gl_test {

inline const std::string kTextureDir = STOCHTEX_TEXTURE_DIR;

inline ImageF render_cpu(const Model& model, const Grid& grid, std::uint32_t seed,
                         bool filter = true) {
  ImageF out(grid.width, grid.height, model.channels());
  RenderOptions options;
  options.filter = filter;
  render(model, grid, seed, out.view(), options);
  return out;
}

inline ImageF render_gpu(const Model& model, const Grid& grid, std::uint32_t seed, int tile = 512,
                         bool filter = true) {
  ImageF out(grid.width, grid.height, model.channels());
  GpuRenderOptions options;
  options.tile_size = tile;
  options.filter = filter;
  render_gl(model, grid, seed, out.view(), options);
  return out;
}

using test_support::same_bytes;

// A model to export (tests of export-shader): method, exemplar, parameters and the side of the
// grid its renders are compared on.
struct ExportCase {
  const char* method;
  const char* exemplar;
  ParamValues params;
  int size;
};

// The export cases: every method of the registry at least once (checked), every lrp section 5
// option, both tiling transports.
inline std::vector<ExportCase> export_cases() {
  std::vector<ExportCase> cases = {
      {"texton", "grass_lawn_128.png", {{"support", 48}}, 48},
      {"tiling", "grass_lawn_128.png", {}, 48},
      {"tiling", "metal_grey_256.png", {{"transport", 1}}, 48},
      {"lrp", "metal_grey_256.png", {{"cosines", 10}}, 32},
      // Section 5: fixed phases, turbulence and random placement.
      {"lrp",
       "wool_knit_blue_256.png",
       {{"cosines", 10}, {"ratio", 0.3}, {"turbulence", 2.0}, {"placement", 1}},
       32},
      {"gabor", "grass_lawn_128.png", {{"impulses", 256}}, 24},
  };
  for (const MethodInfo& method : methods())
    EXPECT_TRUE(std::any_of(cases.begin(), cases.end(),
                            [&](const ExportCase& c) { return c.method == method.name; }))
        << "no export case for " << method.name;
  return cases;
}

inline float max_difference(const ImageF& a, const ImageF& b) {
  float worst = 0.0f;
  for (std::size_t i = 0; i < a.pixels().size(); ++i)
    worst = std::max(worst, std::abs(a.pixels()[i] - b.pixels()[i]));
  return worst;
}

}  // namespace stochtex::gl_test
