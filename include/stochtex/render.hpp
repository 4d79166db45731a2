#pragma once
// Evaluation and rendering. Both are pure functions of (model, positions, footprints, seed): the
// output does not depend on thread count, tile size, evaluation order or batch split, bit for bit.

#include <cstdint>
#include <functional>
#include <span>

#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex {

// Evaluates the model at each position; out has one row of `channels` floats per point
// (out.height == p.size(), out.width == 1) or is any view with p.size() pixels in row-major order.
// `footprints` is either empty (point samples) or has one entry per position.
void evaluate(const Model& model, std::span<const Vec2d> positions,
              std::span<const Footprint> footprints, std::uint32_t seed, ImageView<float> out);

// A regular grid of samples: output pixel (i, j) samples
//   p = origin + scale * (first_pixel_x + i + 1/2, first_pixel_y + j + 1/2).
// A region of a larger render is the same grid with other first_pixel values, so rendering in
// pieces reproduces the whole render exactly.
struct Grid {
  Vec2d origin;
  double scale = 1.0;
  int width = 0;
  int height = 0;
  std::int64_t first_pixel_x = 0;
  std::int64_t first_pixel_y = 0;
};

struct RenderOptions {
  int threads = 0;      // 0 = all hardware threads
  int tile_size = 64;   // pixels per tile side; affects speed only, never the output
  int supersample = 1;  // K: average K x K point samples per pixel (reference for filtering)
  bool filter = true;   // pass each pixel's footprint (scale) to the evaluator
  std::function<void(double)> progress;  // called with the fraction done, from one thread
};

void render(const Model& model, const Grid& grid, std::uint32_t seed, ImageView<float> out,
            const RenderOptions& options = {});

}  // namespace stochtex
