#pragma once
// Exact Poisson counts for cell-based point processes (docs/design.md §5).
// A Poisson(m) count is drawn by inversion: one uniform u, and the count is the first k with
// u < P(X <= k). The CDF is tabulated once per sampler (in double, rounded to float), so a draw
// is a short search with no arithmetic; uniforms have 24 bits, so the table resolves every
// probability the draw can. For a large m the table would be long and the float CDF would lose
// its tail, so m is split into `chunks` equal parts of mean at most kMaxChunkMean: a sum of
// independent Poisson variables is Poisson with the summed mean, so the count stays exact at every
// mean; only the cost grows, linearly with m / kMaxChunkMean.

#include <array>
#include <cmath>
#include <cstdint>

#include "core/hash.hpp"

namespace stochtex {

class PoissonSampler {
 public:
  static constexpr double kMaxChunkMean = 16.0;
  // mean + 12 sd + 16 at the largest chunk mean: the mass beyond is below 1e-30.
  static constexpr int kTableSize = 96;

  PoissonSampler() { cdf_.fill(1.0f); }
  explicit PoissonSampler(double mean) {
    chunks_ =
        mean <= kMaxChunkMean ? 1u : static_cast<std::uint32_t>(std::ceil(mean / kMaxChunkMean));
    chunk_mean_ = mean / chunks_;
    double probability = std::exp(-chunk_mean_);
    double cumulative = 0.0;
    for (int k = 0; k < kTableSize; ++k) {
      cumulative += probability;
      cdf_[static_cast<std::size_t>(k)] = static_cast<float>(cumulative);
      probability *= chunk_mean_ / (k + 1);
    }
    // The last entry catches every uniform (u < 1): the search always ends inside the table.
    cdf_.back() = 2.0f;
  }

  double mean() const noexcept { return chunk_mean_ * chunks_; }
  // The tabulated CDF and chunk count, for the GLSL twin of the sampler (src/gl).
  const std::array<float, kTableSize>& cdf() const noexcept { return cdf_; }
  std::uint32_t chunks() const noexcept { return chunks_; }

  std::uint32_t operator()(CounterRng& rng) const noexcept {
    std::uint32_t total = 0;
    for (std::uint32_t c = 0; c < chunks_; ++c) {
      const float u = rng.uniform();
      std::uint32_t k = 0;
      while (u >= cdf_[k]) ++k;
      total += k;
    }
    return total;
  }

 private:
  std::uint32_t chunks_ = 1;
  double chunk_mean_ = 0.0;
  std::array<float, kTableSize> cdf_;
};

}  // namespace stochtex
