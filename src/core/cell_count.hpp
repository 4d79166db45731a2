#pragma once
// The number of points in a cell of a cell-based point process (docs/design.md §5).
// A count is drawn by inversion: one uniform u, and the count is the first k with u < P(X <= k).
// The CDF is tabulated once per sampler (in double, rounded to float), so a draw is a short search
// with no arithmetic, the same on the CPU and in GLSL; uniforms have 24 bits, so the table
// resolves every probability the draw can. For a large mean the table would be long (and a
// Poisson CDF in float would lose its tail), so the mean m is split into `chunks` equal parts of
// mean at most kMaxChunkMean, one draw each, and the count is their sum.
//
// Two distributions:
// - poisson(m): exact Poisson counts (a sum of independent Poisson variables is Poisson with the
//   summed mean, so the count stays exact at every mean; only the cost grows, linearly with
//   m / kMaxChunkMean).
// - balanced(m): each chunk holds floor(m_c) or floor(m_c) + 1 points, the latter with
//   probability m_c - floor(m_c): the integer count of mean m_c with the least variance
//   (at most 1/4 per chunk, against m for Poisson). Points still fall uniformly in their cell.
//   A caller free to size its cells takes whole_mean(m): then every cell holds the same count.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/hash.hpp"

namespace stochtex {

class CellCount {
 public:
  static constexpr double kMaxChunkMean = 16.0;
  // mean + 12 sd + 16 at the largest chunk mean: the Poisson mass beyond is below 1e-30.
  static constexpr int kTableSize = 96;

  CellCount() { cdf_.fill(1.0f); }

  static CellCount poisson(double mean) {
    CellCount count(mean);
    double probability = std::exp(-count.chunk_mean_);
    double cumulative = 0.0;
    for (int k = 0; k < kTableSize; ++k) {
      cumulative += probability;
      count.cdf_[static_cast<std::size_t>(k)] = static_cast<float>(cumulative);
      probability *= count.chunk_mean_ / (k + 1);
    }
    count.cdf_.back() = 2.0f;
    return count;
  }

  static CellCount balanced(double mean) {
    CellCount count(mean);
    const double whole = std::floor(count.chunk_mean_);
    const auto low = static_cast<std::size_t>(whole);
    for (std::size_t k = 0; k < low; ++k) count.cdf_[k] = 0.0f;
    count.cdf_[low] = static_cast<float>(1.0 - (count.chunk_mean_ - whole));
    for (std::size_t k = low + 1; k < count.cdf_.size(); ++k) count.cdf_[k] = 2.0f;
    return count;
  }

  // The smallest mean >= `mean` (and >= 1) that balanced() splits into whole chunk means, so
  // that every chunk, hence every cell, holds exactly that many points: a cell process with no
  // count variance at all. The caller sizes its cells to hold it.
  static double whole_mean(double mean) {
    for (auto whole = static_cast<std::uint32_t>(std::max(1.0, std::ceil(mean)));; ++whole) {
      const CellCount count(whole);
      if (whole % count.chunks_ == 0) return whole;
    }
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
  // The chunks of `mean`; the table is the caller's. The last entry catches every uniform
  // (u < 1): the search always ends inside the table.
  explicit CellCount(double mean)
      : chunks_(mean <= kMaxChunkMean
                    ? 1u
                    : static_cast<std::uint32_t>(std::ceil(mean / kMaxChunkMean))),
        chunk_mean_(mean / chunks_) {
    cdf_.fill(2.0f);
  }

  std::uint32_t chunks_ = 1;
  double chunk_mean_ = 0.0;
  std::array<float, kTableSize> cdf_;
};

}  // namespace stochtex
