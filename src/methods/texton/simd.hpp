#pragma once
// The vectorised texton noise evaluator: sum_impulses (evaluate.hpp) for a run of samples that
// share one footprint, one sample per SIMD lane, with the scalar reference's operations in its
// order, so every lane returns the reference's bytes (docs/design.md §4). The lanes of a vector
// are neighbouring samples: they visit the same grid cells, so each Poisson point is drawn (from
// the cell cache) and mapped to its impulse once for all lanes, and the lanes fetch the texton at
// their own offsets from it; at a grid's spacing those fetches are neighbouring texels, read with
// a few vector loads instead of one load per sample, tap and channel.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

#include "core/cpu_target.hpp"
#include "methods/texton/evaluate.hpp"
#include "methods/texton/model.hpp"
#include "stochtex/model.hpp"

namespace stochtex::texton {

// The impulse of a Poisson point for the vectorised evaluator: impulse(context, cell_x, cell_y,
// index in the cell, u, v), sum_impulses' `impulses` behind a function pointer; or, when impulse
// is null, OneTexton{pyramid}'s.
struct ImpulseSource {
  const void* context;
  Impulse (*impulse)(const void* context, std::int64_t cell_x, std::int64_t cell_y,
                     std::uint32_t index, float u, float v);
  const PyramidLevel* pyramid;
};

// The most samples one call of sum_impulses_simd takes.
inline constexpr std::size_t kSimdBatch = 64;

// acc[i * lanes + c] = the sum sum_impulses<order, lanes> leaves in acc[c] at positions[i] (at
// most kSimdBatch positions, all filtered by `filter`), bit for bit; lanes = texton_lanes(channels)
// of the pyramids in `shape` (their reach).
void sum_impulses_simd(int order, int lanes, std::span<const Vec2d> positions,
                       const std::vector<PyramidLevel>& shape, const FilterSetup& filter,
                       double cell_size, CellCache& cells, const ImpulseSource& impulses,
                       float* acc) noexcept;

// The shot-noise sum of texton noise or texton noise mixing at each position, filtered by its
// footprint (none: point samples): finish(index, texton, acc) receives sum_impulses' acc for
// positions[index] and the FilteredTexton that summed it. The scalar reference one sample at a
// time, or, when simd_enabled(), sum_impulses_simd over runs of samples with identical footprints
// (a grid's), with the same bytes; a sample whose footprint differs from both neighbours' takes
// the scalar loop (one lane of a vector would cost more).
template <int Order, int Channels, typename Impulses, typename Finish>
void shot_noise(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                const std::vector<PyramidLevel>& shape, double cell_size, CellCache& cells,
                const Impulses& impulses, Finish&& finish) noexcept {
  const int top_level = static_cast<int>(shape.size()) - 1;
  const auto setup = [&](std::size_t index) {
    return footprints.empty() ? FilterSetup{} : filter_setup(footprints[index], top_level);
  };
  const auto same_footprint = [&](std::size_t a, std::size_t b) {
    return footprints.empty() ||
           std::memcmp(&footprints[a], &footprints[b], sizeof(Footprint)) == 0;
  };
  ImpulseSource source{
      &impulses,
      [](const void* context, std::int64_t cell_x, std::int64_t cell_y, std::uint32_t index,
         float u,
         float v) { return (*static_cast<const Impulses*>(context))(cell_x, cell_y, index, u, v); },
      nullptr};
  if constexpr (std::is_same_v<Impulses, OneTexton>) source = {nullptr, nullptr, impulses.pyramid};
  const bool simd = simd_enabled();
  float batch[kSimdBatch * Channels];
  for (std::size_t first = 0; first < positions.size();) {
    std::size_t count = 1;
    if (simd)
      while (count < kSimdBatch && first + count < positions.size() &&
             same_footprint(first, first + count))
        ++count;
    const FilterSetup filter = setup(first);
    const FilteredTexton<Order, Channels> texton(shape, filter);
    if (count == 1) {
      float acc[Channels] = {};
      sum_impulses<Order, Channels>(positions[first], texton, cell_size, cells, impulses, acc);
      finish(first, texton, acc);
    } else {
      sum_impulses_simd(Order, Channels, positions.subspan(first, count), shape, filter, cell_size,
                        cells, source, batch);
      for (std::size_t i = 0; i < count; ++i) {
        float acc[Channels];
        for (int c = 0; c < Channels; ++c) acc[c] = batch[i * Channels + c];
        finish(first + i, texton, acc);
      }
    }
    first += count;
  }
}

}  // namespace stochtex::texton
