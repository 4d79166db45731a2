#pragma once
// The vectorised evaluator of bandwidth-quantised Gabor noise (GaborModel::evaluate): one grid's
// kernel sum at one sample, the scalar reference's `sum`, bit for bit (docs/design.md §4). What it
// adds: the impulses of a Poisson cell (its count, positions and alias-table kernels, section 6.2)
// are drawn once, 4 to 16 at a time, into a cache that every later sample seeing the cell shares,
// and the kernels of a cell are evaluated 4 to 16 impulses at a time, one impulse per lane, with
// the scalar reference's operations. Only the sum runs in scalar order: the values of the impulses
// within the kernel's support are added one by one, in the cell and impulse order of the
// reference.

#include <hwy/aligned_allocator.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "core/cell_count.hpp"
#include "core/surface_process.hpp"
#include "methods/gabor/evaluate.hpp"
#include "stochtex/model.hpp"

namespace stochtex::gabor {

// The impulses of the recently seen cells of one grid at one thinning level, kept for one
// evaluate() call (a render tile). Cell (x, y) lives in slot (x mod 16) + 16 (y mod 16): the cells
// around a sample (at most 9 x 9, where a grid's cells are a quarter of its kernel radius) never
// share a slot, and a strip of samples whose cells span at most 16 columns (strip_width) finds
// the cells of the rows above it still cached. A slot holds the lists u * cell_size,
// v * cell_size, omega_x, omega_y and phase of its cell's impulses, in the reference's order;
// cells of more than kCapacity impulses are drawn block by block at each use.
struct ImpulseCache {
  static constexpr std::uint32_t kSide = 16;
  static constexpr std::uint32_t kSlots = kSide * kSide;
  static constexpr std::uint32_t kCapacity = 128;  // a multiple of every lane count
  static constexpr std::size_t kLists = 5;

  static std::size_t slot(std::int64_t x, std::int64_t y) noexcept {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(x) & (kSide - 1)) |
                                    ((static_cast<std::uint64_t>(y) & (kSide - 1)) << 4u));
  }
  // Allocates the lists (640 KiB, aligned for every SIMD target); false when that fails.
  bool reserve() noexcept {
    if (!storage) storage = hwy::AllocateAligned<float>(kSlots * kLists * kCapacity);
    return storage != nullptr;
  }
  float* lists(std::size_t slot) noexcept { return storage.get() + slot * kLists * kCapacity; }

  // The grid, its cell-count sampler, the level's random stream and cell side whose cells the
  // cache holds from now on; the cache starts empty.
  void start(const GridKernels& grid_kernels, const CellCount& grid_cell_count,
             std::uint32_t grid_level_seed, float grid_cell_size) noexcept {
    kernels = grid_kernels;
    cell_count = &grid_cell_count;
    level_seed = grid_level_seed;
    cell_size = grid_cell_size;
    for (bool& v : valid) v = false;
  }

  GridKernels kernels{};
  const CellCount* cell_count = nullptr;
  std::uint32_t level_seed = 0;
  float cell_size = 0.0f;
  bool valid[kSlots] = {};
  std::int64_t x[kSlots];
  std::int64_t y[kSlots];
  std::uint32_t count[kSlots];
  hwy::AlignedFreeUniquePtr<float[]> storage;
  alignas(64) float scratch[kLists * kCapacity];  // a block of a cell too large for a slot
};

// How many samples of a row, `step` apart along x, one strip may hold so that its cells at
// `cell_size` within `reach` of them span at most ImpulseCache::kSide columns: at least 1.
inline std::size_t strip_width(double step, double reach, double cell_size) noexcept {
  const double extent = (ImpulseCache::kSide - 2) * cell_size - 2.0 * reach;
  if (!(step > 0.0) || extent <= step) return 1;
  return static_cast<std::size_t>(std::min(extent / step, 1e6));
}

// sum_i g_i(p - x_i) over the impulses of `cells` within the kernel's support, as
// GaborModel::evaluate's scalar loop sums them (bit for bit); `cache` was started for the grid
// and level, `cell_size` is its cell side in double.
float impulse_sum(ImpulseCache& cache, const KernelShape& shape, const CellRange& cells, Vec2d p,
                  double cell_size) noexcept;

// Surface Gabor noise's kernel sum of one grid at one point, as GaborModel::evaluate_surface's
// scalar loop over for_each_surface_impulse sums it (bit for bit): the impulses of a cell of the
// 3-D process are drawn 4 to 16 at a time (their draws by their counters,
// core/surface_process.hpp), rejected by the tent weight and the envelope in every lane, and the
// kernels of the others are evaluated a vector at a time; `seed` is the grid's level seed, `depth`
// the tent's half width.
float surface_impulse_sum(const GridKernels& kernels, const KernelShape& shape,
                          const SurfacePoint& p, const SurfaceFrame& frame, double reach,
                          double depth, double cell_size, const CellCount& count,
                          std::uint32_t seed) noexcept;

}  // namespace stochtex::gabor
