#pragma once
// Shared by the OpenGL tests: CPU and GL renders of one grid, and their comparison.

#include <algorithm>
#include <cmath>
#include <string>

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

inline float max_difference(const ImageF& a, const ImageF& b) {
  float worst = 0.0f;
  for (std::size_t i = 0; i < a.pixels().size(); ++i)
    worst = std::max(worst, std::abs(a.pixels()[i] - b.pixels()[i]));
  return worst;
}

}  // namespace stochtex::gl_test
