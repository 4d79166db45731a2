#pragma once
// The vectorised evaluator of LRP noise's random strata (equation 1): the scalar loop of
// LrpModel::evaluate_typed and stratum_sum (evaluate.hpp), one sample per SIMD lane, with the same
// operations in the same order, so every lane returns the scalar reference's bytes
// (docs/design.md §4). What it adds: the cosines of a lattice node (its J_S draws, picks and table
// reads) are drawn once into a cache and shared by every lane and every later sample that sees
// the node, and the cosine polynomials of 4 to 16 samples run side by side.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "methods/lrp/evaluate.hpp"
#include "methods/lrp/model.hpp"
#include "methods/lrp/window.hpp"
#include "stochtex/model.hpp"

namespace stochtex::lrp {

// One random stratum as the batch sees it: StratumDraw with its amplitude and channel.
struct SimdStratum {
  StratumDraw draw;
  float amplitude;
  int channel;
};

struct RandomStrata {
  std::span<const SimdStratum> strata;  // in the model's order, silent ones (A_S = 0) left out
  StratumTables tables;                 // tables.weights is not null
  const std::array<float, kWindowTerms>* window;
  float mean_envelope;
  bool normalise;
};

// The cosines of recently seen lattice nodes, kept for one evaluate() call (a render tile): node
// (x, y) of stratum s lives in slot (x + 7 y) mod `slots` of its stratum, as the lists
// fx[J_S], fy[J_S], phase[J_S], weight[J_S] (StratumSum's draw, pick and table reads). 7 rows
// apart, the nodes around a row of samples never share a slot.
class NodeCache {
 public:
  static constexpr std::size_t kFloats = 16384;  // 64 KiB
  static constexpr std::size_t kMaxSlots = 1024;
  static constexpr std::size_t kMaxSlotsPerStratum = 64;

  // Lays the slots out for `strata` (the cache starts empty); false when one node of every
  // stratum does not fit (J above about 1,300 cosines over all channels): the caller then takes
  // the scalar reference.
  bool layout(std::span<const SimdStratum> strata) noexcept;

  // Starts a pass: nodes found in it stay until the next pass starts.
  void next_pass() noexcept { ++pass_; }
  // The offset in data() of node (x, y)'s list of stratum s, drawn into its slot if absent; -1
  // when the slot holds another node found in this pass (take this one in another pass).
  std::int32_t find(std::size_t s, const SimdStratum& stratum, const StratumTables& tables,
                    std::int64_t x, std::int64_t y) noexcept;
  const float* data() const noexcept { return floats_.data(); }

 private:
  std::array<float, kFloats> floats_;
  std::array<std::int64_t, kMaxSlots> x_;
  std::array<std::int64_t, kMaxSlots> y_;
  std::array<std::uint64_t, kMaxSlots> found_in_;  // the pass that found it; 0 = empty
  std::array<std::uint32_t, kMaxChannels * kMaxStrataPerChannel> first_slot_;
  std::array<std::uint32_t, kMaxChannels * kMaxStrataPerChannel> first_float_;
  std::uint32_t slots_ = 0;  // per stratum, a power of two
  std::uint64_t pass_ = 1;
};

// The most samples one call of add_random_strata takes.
inline constexpr std::size_t kSimdBatch = 64;

// noise[i * kMaxChannels + c] = the sum of the random strata of channel c at positions[i] (at
// most kSimdBatch positions), channels 0 to `channels` - 1, as LrpModel::evaluate_typed sums them
// (bit for bit); footprints empty for point samples. `cache` has been laid out for the strata.
void random_strata_noise(const RandomStrata& strata, int channels, std::span<const Vec2d> positions,
                         std::span<const Footprint> footprints, NodeCache& cache,
                         float* noise) noexcept;

}  // namespace stochtex::lrp
