#pragma once
// Evaluation and rendering. Both are pure functions of (model, positions, footprints, seed): the
// output does not depend on thread count, tile size, evaluation order or batch split, bit for bit.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex {

// The precise range of positions (docs/design.md §4): every coordinate that evaluate() and
// render() sample, and every footprint component, must be finite and within +-kPositionLimit
// exemplar pixels. Each evaluator splits p in double into a lattice cell and a float offset;
// below 2^32 the double keeps 2^-20 pixel (the resolution of a float offset of 8 pixels), so the
// offset loses nothing. Measured on grass_lawn_128, the rounding noise of second differences
// along lines of samples 1e-5 pixel apart, against p = 0: at 2^32 0.86 to 1.57 (texton, tiling,
// gabor, lrp), at 2^34 lrp's is 3.7, at 2^40 2 to 24 for every method. Cell indices stay far from
// int64 overflow (positions near 1e19 overflowed it).
inline constexpr double kPositionLimit = 4294967296.0;  // 2^32

// Both functions check their arguments before any work and throw std::invalid_argument (one
// sentence) when the model is empty, the output view does not fit, or a position, footprint or
// grid is not finite or reaches beyond kPositionLimit; evaluation itself never throws.

// Evaluates the model at each position; out has one row of `channels` floats per point
// (out.height == p.size(), out.width == 1) or is any view with p.size() pixels in row-major order.
// `footprints` is either empty (point samples) or has one entry per position.
void evaluate(const Model& model, std::span<const Vec2d> positions,
              std::span<const Footprint> footprints, std::uint32_t seed, ImageView<float> out);

// evaluate() of the field that repeats with the model-space period `period` (both components > 0
// and within kPositionLimit): f(p + period) = f(p) for every p, the same bits wherever p reduced
// into [0, period) is exact (a render's pixel centres are). Every method's random draws are keyed
// by its lattice cells wrapped into the period, the cells adjusted per axis to divide it (by at
// most half a cell over the period, the impulse density kept; docs/render.md "Periodic renders").
// Runs each method's scalar evaluator. Throws std::invalid_argument (one sentence) as evaluate()
// does, and for a bad period or a model that cannot be periodic (periodic_refusal).
void evaluate_periodic(const Model& model, std::span<const Vec2d> positions,
                       std::span<const Footprint> footprints, std::uint32_t seed,
                       ImageView<float> out, Vec2d period);
// Why `model` cannot be evaluated periodically (one sentence), or empty when it can: a texton mix
// (its mixing field is not periodic) and an lrp model with a structure component (its fixed
// cosines are not) cannot.
std::string periodic_refusal(const Model& model);

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
  // A tileable bake (evaluate_periodic): the field repeats with this model-space period; a whole
  // render of it is grid_period(grid). Regions of one bake take the whole output's period.
  std::optional<Vec2d> period;
};

// The period of a tileable bake of the whole grid: (width, height) * scale.
inline Vec2d grid_period(const Grid& grid) {
  return {grid.width * grid.scale, grid.height * grid.scale};
}

void render(const Model& model, const Grid& grid, std::uint32_t seed, ImageView<float> out,
            const RenderOptions& options = {});

// The instruction sets the CPU evaluators run on (docs/design.md §4). By default the best one this
// machine offers, picked at run time (Highway's dynamic dispatch). `reference` is the scalar
// evaluator, the one the GLSL twins mirror; every other target computes each sample with the same
// operations in the same order, one sample per SIMD lane, so every target gives the same bytes
// (tests force each one).
enum class CpuTarget { reference, portable, sse4, avx2, avx512 };

// "reference", "portable" (Highway's fallback for a machine without SSE4: the vectorised
// evaluators' loops, one lane wide), "sse4", "avx2" or "avx512".
std::string_view cpu_target_name(CpuTarget target);
// The targets this machine and build can run: reference first, the default (the best) last.
std::vector<CpuTarget> available_cpu_targets();
// The target evaluate() and render() use now.
CpuTarget cpu_target();
// The target of available_cpu_targets() named `name` (cpu_target_name's names); throws
// std::invalid_argument, one sentence listing this machine's targets, for any other name.
CpuTarget available_cpu_target(std::string_view name);
// Process-wide, for tests, benchmarks and checks; call it while no evaluation runs. Throws
// std::invalid_argument (one sentence) for a target that available_cpu_targets() lacks.
void set_cpu_target(CpuTarget target);

// Throws std::invalid_argument, the sentence starting with `what`, unless the grid's scale and
// origin are finite and every position it samples (pixel corners included) lies within
// kPositionLimit: render() and GlRenderer::render() check their grid with it.
void check_grid(const Grid& grid, std::string_view what);

}  // namespace stochtex
