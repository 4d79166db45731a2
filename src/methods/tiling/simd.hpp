#pragma once
// The vectorised evaluator of histogram-preserving tiling and blending (Heitz & Neyret 2018,
// "High-Performance By-Example Noise using a Histogram-Preserving Blending Operator", DOI
// 10.1145/3233304): TilingModel::blended_gaussian and inverse_transform (model.cpp,
// evaluate.hpp), one sample per SIMD lane, with the same operations in the same order, so every
// lane returns the scalar reference's bytes (docs/design.md §4). It covers the paper's operator
// (no rotation, scale jitter, sharpness or height blend, no radial group), every blend and 1 to
// kMaxChannels channels; TilingModel::evaluate takes the scalar reference for the rest.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "methods/tiling/model.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex::tiling {

// The most pyramid levels: an exemplar side of 65536 pixels halves to 1 in 16 steps.
inline constexpr int kSimdMaxLevels = 17;

// What the lanes read of a model: its pyramid and its tables of every level side by side, each
// level at an offset, so that a lane reads its own level through one int32 index.
struct SimdTiling {
  int channels = 0;
  int width = 0;  // exemplar size in pixels
  int height = 0;
  double edge = 0.0;  // lattice edge
  bool linear = false;
  bool inverse = false;  // T^-1 (the histogram blend)
  const float* blend_mean = nullptr;
  const float* pyramid = nullptr;
  int level_count = 0;
  std::array<std::int32_t, kSimdMaxLevels> level_width{};
  std::array<std::int32_t, kSimdMaxLevels> level_height{};
  std::array<std::int32_t, kSimdMaxLevels> level_first{};  // its texels in pyramid
  std::array<float, kSimdMaxLevels> texels_per_pixel_x{};
  std::array<float, kSimdMaxLevels> texels_per_pixel_y{};
  std::span<const TableGroup> groups;  // lut, decorrelated or direct
  int lut_size = 0;
  int table_size = 0;
  const float* luts = nullptr;  // level l's 3-D table at l * lut_floats
  std::int32_t lut_floats = 0;
  const float* tables = nullptr;  // level l's 1-D tables at l * table_floats
  std::int32_t table_floats = 0;
  const float* colour_basis = nullptr;
  const float* colour_mean = nullptr;
};

// The most samples one call of evaluate_lanes takes.
inline constexpr std::size_t kSimdBatch = 64;

// out's pixels first .. first + positions.size() - 1 (row-major) = the model's value at
// positions (at most kSimdBatch), read at the levels of detail `levels` and `blends`
// (LevelOfDetail), as TilingModel::evaluate writes them, bit for bit.
void evaluate_lanes(const SimdTiling& model, std::span<const Vec2d> positions,
                    const std::int32_t* levels, const float* blends, std::uint32_t seed,
                    ImageView<float> out, std::size_t first) noexcept;

// The prefilter of the tables (pyramid.cpp), in lanes with the scalar reference's bytes:
// fractions[i] = table_coordinate(gaussian_to_uniform(g[i]), size, cells[i]) for i < count.
void table_coordinates(const float* g, std::size_t count, int size, std::int32_t* cells,
                       float* fractions) noexcept;

// A sparse matrix by rows: row i's entries are (cells[k], weights[k]) for k in first[i] ..
// first[i + 1] - 1, in ascending cell order.
struct SparseRows {
  const std::size_t* first = nullptr;
  const std::int32_t* cells = nullptr;
  const float* weights = nullptr;
  std::size_t rows = 0;
};

// out[i][j] = sum_k weights[k] in[cells[k]][j] for every row i and j < width, `in` and `out`
// holding rows of `width` contiguous floats: each product in float, added in double in the order
// of k, rounded to float, as the scalar loop `sum += weight * value` does.
void apply_rows(const SparseRows& matrix, const float* in, float* out, std::size_t width) noexcept;

}  // namespace stochtex::tiling
