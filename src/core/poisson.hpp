#pragma once
// Exact Poisson counts for cell-based point processes (DESIGN.md section 5).
// A Poisson(m) count is drawn by inversion (sequential search of the CDF, one uniform draw). For a
// large m the CDF terms lose float precision, so m is split into `chunks` equal parts of mean at
// most kMaxChunkMean: a sum of independent Poisson variables is Poisson with the summed mean, so
// the count stays exact at every mean; only the cost grows, linearly with m / kMaxChunkMean.

#include <cmath>
#include <cstdint>

#include "core/hash.hpp"

namespace stochtex {

class PoissonSampler {
 public:
  static constexpr float kMaxChunkMean = 16.0f;

  PoissonSampler() = default;
  explicit PoissonSampler(double mean) {
    chunks_ =
        mean <= kMaxChunkMean ? 1u : static_cast<std::uint32_t>(std::ceil(mean / kMaxChunkMean));
    chunk_mean_ = static_cast<float>(mean / chunks_);
    exp_neg_chunk_mean_ = static_cast<float>(std::exp(-static_cast<double>(chunk_mean_)));
    // Beyond mean + 12 sd + 16 the remaining mass is below 1e-30: the search stops there.
    max_chunk_count_ =
        static_cast<std::uint32_t>(chunk_mean_ + 12.0f * std::sqrt(chunk_mean_) + 16.0f);
  }

  double mean() const noexcept { return static_cast<double>(chunk_mean_) * chunks_; }

  std::uint32_t operator()(CounterRng& rng) const noexcept {
    std::uint32_t total = 0;
    for (std::uint32_t c = 0; c < chunks_; ++c) {
      const float u = rng.uniform();
      std::uint32_t k = 0;
      float p = exp_neg_chunk_mean_;
      float cdf = p;
      while (u >= cdf && k < max_chunk_count_) {
        ++k;
        p *= chunk_mean_ / static_cast<float>(k);
        const float next_cdf = cdf + p;
        if (next_cdf == cdf) break;  // the remaining tail is below float resolution
        cdf = next_cdf;
      }
      total += k;
    }
    return total;
  }

 private:
  std::uint32_t chunks_ = 1;
  float chunk_mean_ = 0.0f;
  float exp_neg_chunk_mean_ = 1.0f;
  std::uint32_t max_chunk_count_ = 0;
};

}  // namespace stochtex
