#include "spectral/kmeans.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

namespace stochtex {

std::vector<std::vector<std::array<int, 2>>> kmeans(const std::vector<std::array<int, 2>>& points,
                                                    int clusters, int iterations, CounterRng& rng) {
  const std::size_t n = points.size();
  const auto k_count = static_cast<std::size_t>(clusters);
  std::vector<std::vector<std::array<int, 2>>> groups(k_count);
  if (n <= k_count) {
    // Fewer points than groups: each group gets one, cyclically.
    for (std::size_t j = 0; j < k_count; ++j) groups[j].push_back(points[j % n]);
    return groups;
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<std::array<double, 2>> centres(k_count);
  for (std::size_t j = 0; j < k_count; ++j) {
    const std::uint32_t draw = rng.next();
    const std::size_t pick =
        j + static_cast<std::size_t>((static_cast<std::uint64_t>(draw) * (n - j)) >> 32u);
    std::swap(order[j], order[pick]);
    centres[j] = {double(points[order[j]][0]), double(points[order[j]][1])};
  }
  std::vector<std::size_t> label(n, k_count);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    bool changed = false;
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t best = 0;
      double best_distance = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < k_count; ++j) {
        const double dx = points[i][0] - centres[j][0];
        const double dy = points[i][1] - centres[j][1];
        const double distance = dx * dx + dy * dy;
        if (distance < best_distance) {
          best_distance = distance;
          best = j;
        }
      }
      changed = changed || label[i] != best;
      label[i] = best;
    }
    // An empty group takes the point farthest from its own centre (the classic repair).
    std::vector<std::size_t> sizes(k_count, 0);
    for (const std::size_t l : label) ++sizes[l];
    for (std::size_t j = 0; j < k_count; ++j) {
      if (sizes[j] > 0) continue;
      std::size_t farthest = 0;
      double farthest_distance = -1.0;
      for (std::size_t i = 0; i < n; ++i) {
        if (sizes[label[i]] < 2) continue;
        const double dx = points[i][0] - centres[label[i]][0];
        const double dy = points[i][1] - centres[label[i]][1];
        if (dx * dx + dy * dy > farthest_distance) {
          farthest_distance = dx * dx + dy * dy;
          farthest = i;
        }
      }
      --sizes[label[farthest]];
      label[farthest] = j;
      sizes[j] = 1;
      changed = true;
    }
    std::vector<std::array<double, 2>> sums(k_count, {0.0, 0.0});
    for (std::size_t i = 0; i < n; ++i) {
      sums[label[i]][0] += points[i][0];
      sums[label[i]][1] += points[i][1];
    }
    for (std::size_t j = 0; j < k_count; ++j)
      centres[j] = {sums[j][0] / double(sizes[j]), sums[j][1] / double(sizes[j])};
    if (!changed) break;
  }
  for (std::size_t i = 0; i < n; ++i) groups[label[i]].push_back(points[i]);
  return groups;
}

}  // namespace stochtex
