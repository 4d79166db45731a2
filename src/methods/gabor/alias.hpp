#pragma once
// The alias method (Walker 1977) for the kernel parameters of bandwidth-quantised Gabor noise
// (section 6.2): constant-time draws from a discrete distribution, built in linear time.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/hash.hpp"

namespace stochtex::gabor {

// Fills probability[i] (the chance to keep i) and alias[i] (the index drawn otherwise) for the
// distribution proportional to `weights` (non-negative, positive sum). Vose's linear-time
// construction (Vose 1991) with the paper's in-place twist (section 6.2, after Vose's section VII):
// instead of two work lists of "small" and "large" entries, two forward scans find the next small
// and the next large entry, and a large entry that drops below the mean is paired at once when the
// small scan has already passed it. The one work array is the scaled weights, kept in double.
inline void build_alias_table(std::span<const double> weights, std::span<float> probability,
                              std::span<std::uint32_t> alias) {
  const std::size_t n = weights.size();
  double total = 0.0;
  for (const double w : weights) total += w;
  std::vector<double> scaled(n);
  for (std::size_t i = 0; i < n; ++i) {
    scaled[i] = weights[i] * static_cast<double>(n) / total;
    alias[i] = static_cast<std::uint32_t>(i);
  }
  const auto find_small = [&](std::size_t from) {
    while (from < n && scaled[from] >= 1.0) ++from;
    return from;
  };
  const auto find_large = [&](std::size_t from) {
    while (from < n && scaled[from] < 1.0) ++from;
    return from;
  };
  std::size_t small_scan = find_small(0);
  std::size_t small = small_scan++;
  std::size_t large_scan = find_large(0);
  std::size_t large = large_scan++;
  while (small < n && large < n) {
    alias[small] = static_cast<std::uint32_t>(large);
    // The large entry gives the small one what it lacks to fill its column.
    scaled[large] -= 1.0 - scaled[small];
    if (scaled[large] < 1.0) {
      if (large < small_scan) {
        small = large;  // the small scan is past it: pair it now
      } else {
        small_scan = find_small(small_scan);
        small = small_scan++;
      }
      large_scan = find_large(large_scan);
      large = large_scan++;
    } else {
      small_scan = find_small(small_scan);
      small = small_scan++;
    }
  }
  // A paired entry has an alias other than itself (a large entry is never small at the same
  // time); entries never paired hold a full column (their scaled weight is 1 up to rounding).
  for (std::size_t i = 0; i < n; ++i)
    probability[i] = alias[i] != i ? static_cast<float>(scaled[i]) : 1.0f;
}

// The column of a draw: the word's multiply-shift onto [0, count).
inline std::uint32_t alias_column(std::uint32_t word, std::uint32_t count) noexcept {
  return static_cast<std::uint32_t>((static_cast<std::uint64_t>(word) * count) >> 32u);
}

// The entry picked by a column word and a coin: the column's own index or its alias.
inline std::uint32_t alias_pick(const float* probability, const std::uint32_t* alias,
                                std::uint32_t count, std::uint32_t word, float coin) noexcept {
  const std::uint32_t column = alias_column(word, count);
  return coin < probability[column] ? column : alias[column];
}

// One draw: a uniform column, then the column's own index or its alias. Two generator draws, each
// in its own statement (hash.hpp: argument evaluation order is unspecified).
inline std::uint32_t draw_alias(const float* probability, const std::uint32_t* alias,
                                std::uint32_t count, CounterRng& rng) noexcept {
  const std::uint32_t word = rng.next();
  const float coin = rng.uniform();
  return alias_pick(probability, alias, count, word, coin);
}

}  // namespace stochtex::gabor
