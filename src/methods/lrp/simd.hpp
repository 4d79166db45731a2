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
#include <memory>
#include <span>
#include <vector>

#include "methods/lrp/evaluate.hpp"
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
// (x, y) of stratum s lives in slot (x mod W) + W (y mod 4) of its stratum's W x 4 slots, as the
// lists fx[J_S], fy[J_S], phase[J_S], weight[J_S] (stratum_sum's draws, picks and table reads).
// The nodes around a row of samples, up to W wide and 4 high, never share a slot.
class NodeCache {
 public:
  // A cache laid out for `strata`, or null when it cannot be allocated or W would fall below 4
  // (beyond 16,384 cosines over all channels): the caller then takes the scalar reference.
  static std::unique_ptr<NodeCache> make(std::span<const SimdStratum> strata) noexcept;

  // Starts a pass: nodes found in it stay until the next pass starts.
  void next_pass() noexcept { ++pass_; }
  // The offset in data() of node (x, y)'s list of stratum s, drawn into its slot if absent; -1
  // when the slot holds another node found in this pass (take this one in another pass).
  std::int32_t find(std::size_t s, const SimdStratum& stratum, const StratumTables& tables,
                    std::int64_t x, std::int64_t y) noexcept;
  const float* data() const noexcept { return floats_.data(); }

 private:
  struct Slot {
    std::int64_t x = 0;
    std::int64_t y = 0;
    std::uint64_t found_in = 0;  // the pass that found it; 0 = empty
  };
  std::vector<float> floats_;
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> first_float_;  // per stratum
  std::uint32_t width_ = 0;                 // W, a power of two
  std::uint64_t pass_ = 1;
};

// The most samples one call of random_strata_noise takes, and the width of the strips a grid is
// taken in.
inline constexpr std::size_t kSimdBatch = 64;
inline constexpr std::size_t kSimdStrip = 16;

// noise[i * kMaxChannels + c] = the sum of the random strata of channel c at positions[i] (at
// most kSimdBatch positions), channels 0 to `channels` - 1, as LrpModel::evaluate_typed sums them
// (bit for bit); footprints empty for point samples. `cache` was made for the strata.
void random_strata_noise(const RandomStrata& strata, int channels, std::span<const Vec2d> positions,
                         std::span<const Footprint> footprints, NodeCache& cache,
                         float* noise) noexcept;

}  // namespace stochtex::lrp
